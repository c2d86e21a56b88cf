#include "core/simulation/piece.h"

#include "core/integrators/stability.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {

double Piece::largestStableStep() const {
  return slime::largestStableStep(integrator_, highestFrequency_, highestDampingRate_);
}

void Piece::dragTo(const glm::dvec3& target, int which) {
  Hand& hand = hands_[which];
  if (!hand.holding) return;
  hand.target = target;
  hand.pendingTarget = target;
}

void Piece::release(int which) {
  Hand& hand = hands_[which];
  const glm::dvec3 target = hand.target;
  hand = Hand{};
  hand.target = target;  // grabTarget() still says where it let go
}

void Piece::applyHandForce(double maxForce) {
  for (Hand& hand : hands_) hand.spring.maxForce = maxForce;
}

bool Piece::anyGrabbing() const {
  return std::any_of(std::begin(hands_), std::end(hands_), [](const Hand& hand) { return hand.holding; });
}

glm::dvec3 Piece::grabbedPoint(int which) const {
  const Hand& hand = hands_[which];
  if (!hand.holding) return hand.target;
  glm::dvec3 sum(0.0);
  const std::vector<glm::dvec3>& x = state().positions;
  for (std::size_t k = 0; k < hand.nodes.size(); ++k) sum += x[hand.nodes[k]] - grabOffset(hand, k);
  return sum / static_cast<double>(hand.nodes.size());
}

void measureShape(std::span<const SurfaceView> surfaces, SlimeMetrics& metrics) {
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (const SurfaceView& surface : surfaces)
    for (const glm::dvec3& p : surface.positions) {
      low = glm::min(low, p);
      high = glm::max(high, p);
    }
  metrics.height = high.z - low.z;
  metrics.width = std::max(high.x - low.x, high.y - low.y);
  metrics.aspect = metrics.width > 0.0 ? metrics.height / metrics.width : 1.0;
  metrics.minZ = low.z;
}

// Shape from the drawn surface (the membrane's vertices, the smooth map's placing of the bulk body's
// icosphere), not from the bulk body's outer nodes, which lie 0.3-0.7 mm from what is drawn and
// exported. Energy and speed from every simulated point.
SlimeMetrics Piece::metricsOf(const std::vector<double>& freeInverseMasses) const {
  SlimeMetrics metrics;
  const ParticleState& state = this->state();
  for (std::size_t i = 0; i < state.size(); ++i) {
    const double speedSquared = glm::dot(state.velocities[i], state.velocities[i]);
    metrics.kineticEnergy += 0.5 * speedSquared / freeInverseMasses[i];
    metrics.maxSpeed = std::max(metrics.maxSpeed, std::sqrt(speedSquared));
  }
  metrics.volumeRatio = volume() / restVolume();
  const SurfaceView drawn = surface();
  measureShape({&drawn, 1}, metrics);
  return metrics;
}

}  // namespace slime

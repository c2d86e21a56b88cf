#include "core/contact/floor_adhesion.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

// r^n of the creep law; n = 1/2 is a square root (pow took 1 % of the default slime's step).
double creepFactor(double ratio) {
  if constexpr (kAdhesionCreepExponent == 0.5) return std::sqrt(ratio);
  return std::pow(ratio, kAdhesionCreepExponent);
}

}  // namespace

double adhesionGrownShare(double age) {
  return kAdhesionFreshShare + (1.0 - kAdhesionFreshShare) * (1.0 - std::exp(-age / kAdhesionDwell));
}

double adhesionCreepDistance(double pull, double holds, double h) {
  const double ratio = holds > 0.0 ? pull / holds : 0.0;
  return h * kAdhesionCreepSpeed * creepFactor(ratio);
}

void FloorAdhesion::reset(const std::vector<Triangle>& surface, std::size_t surfaceNodes) {
  stuck_.assign(surfaceNodes, 0);
  left_.assign(surfaceNodes, 0);
  start_.assign(surfaceNodes, glm::dvec3(0.0));
  area_.assign(surfaceNodes, 0.0);
  age_.assign(surfaceNodes, 0.0);
  peeled_ = 0;
  strengthHeld_ = 0.0;
  momentumTaken_ = displacementTaken_ = glm::dvec3(0.0);
  // Each surface node's neighbours along the surface triangles' edges, sorted and unique.
  std::vector<std::vector<std::uint32_t>> lists(surfaceNodes);
  for (const Triangle& t : surface) {
    const std::uint32_t v[3] = {t.x, t.y, t.z};
    for (int a = 0; a < 3; ++a)
      if (v[a] < surfaceNodes) {
        lists[v[a]].push_back(v[(a + 1) % 3]);
        lists[v[a]].push_back(v[(a + 2) % 3]);
      }
  }
  neighbourStart_.assign(1, 0);
  neighbours_.clear();
  for (std::vector<std::uint32_t>& list : lists) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    neighbours_.insert(neighbours_.end(), list.begin(), list.end());
    neighbourStart_.push_back(static_cast<std::uint32_t>(neighbours_.size()));
  }
}

void FloorAdhesion::carryOver(const FloorAdhesion& from, const std::vector<std::uint32_t>& source) {
  for (std::size_t i = 0; i < stuck_.size() && i < source.size(); ++i) {
    const std::uint32_t j = source[i];
    if (j == kNoSource || j >= from.stuck_.size()) continue;
    stuck_[i] = from.stuck_[j];
    left_[i] = from.left_[j];
    start_[i] = from.start_[j];
    age_[i] = from.age_[j];
  }
}

std::size_t FloorAdhesion::stuckCount() const {
  return static_cast<std::size_t>(std::count(stuck_.begin(), stuck_.end(), 1));
}

void FloorAdhesion::beginSubstep(const ParticleState& state) {
  for (std::size_t i = 0; i < stuck_.size(); ++i)
    if (stuck_[i]) start_[i] = state.positions[i];
}

// A_i = Σ over its surface triangles of max(0, −n̂_z)·A_t / 3: the floor-facing area it holds.
void FloorAdhesion::updateAreas(const std::vector<Triangle>& surface, const std::vector<glm::dvec3>& x) {
  std::fill(area_.begin(), area_.end(), 0.0);
  for (const Triangle& t : surface) {
    if (t.x >= area_.size() || t.y >= area_.size() || t.z >= area_.size()) continue;
    if (!stuck_[t.x] && !stuck_[t.y] && !stuck_[t.z]) continue;
    const glm::dvec3 n = glm::cross(x[t.y] - x[t.x], x[t.z] - x[t.x]);  // 2 A n̂
    const double downward = std::max(0.0, -n.z) / 6.0;                   // (projected area) / 3
    area_[t.x] += downward;
    area_[t.y] += downward;
    area_[t.z] += downward;
  }
}

bool FloorAdhesion::onEdge(std::size_t node) const {
  for (std::uint32_t k = neighbourStart_[node]; k < neighbourStart_[node + 1]; ++k)
    if (!stuck_[neighbours_[k]]) return true;
  return false;
}

void FloorAdhesion::endSubstep(ParticleState& state, const std::vector<Triangle>& surface,
                               const std::vector<double>& freeInverseMasses, double strength, double h) {
  if (strength <= 0.0) return;
  const std::size_t count = std::min(stuck_.size(), state.size());
  bool anyStuck = false;
  for (std::size_t i = 0; i < count && !anyStuck; ++i) anyStuck = stuck_[i] != 0;
  if (anyStuck) updateAreas(surface, state.positions);
  // Hold or peel. Peeling is decided on the state before this pass, so one substep's front moves by
  // at most one ring of nodes.
  std::vector<std::uint32_t> peel;
  strengthHeld_ = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    if (!stuck_[i] || state.inverseMasses[i] == 0.0) continue;
    glm::dvec3 move = state.positions[i] - start_[i];
    move.z = std::max(move.z, 0.0);
    const double pull = glm::length(move) / (freeInverseMasses[i] * h * h);  // F = m |Δx| / h², N
    age_[i] += h;
    const double holds = adhesionGrownShare(age_[i]) * strength * area_[i];  // σ(t) A_i, N
    const bool edge = onEdge(i);
    if (pull > holds && edge) {
      peel.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    strengthHeld_ += holds;
    // Held: it creeps by h v_c r^n along its pull (at most as far as the pull moved it); only an edge
    // node may lift, and lifted out of the band it has peeled.
    const double moved = glm::length(move);
    const double creep = moved > 0.0 ? std::min(1.0, adhesionCreepDistance(pull, holds, h) / moved) : 0.0;
    glm::dvec3& x = state.positions[i];
    const glm::dvec3 before = x, velocityBefore = state.velocities[i];
    x.x = start_[i].x + creep * move.x;
    x.y = start_[i].y + creep * move.y;
    x.z = std::min(x.z, start_[i].z + (edge ? creep * move.z : 0.0));
    if (edge && x.z > kAdhesionContactBand) peel.push_back(static_cast<std::uint32_t>(i));
    state.velocities[i] = glm::dvec3(0.0, 0.0, std::min(0.0, state.velocities[i].z));
    displacementTaken_ += (before - x) / freeInverseMasses[i];
    momentumTaken_ += (velocityBefore - state.velocities[i]) / freeInverseMasses[i];
  }
  for (std::uint32_t i : peel) {
    stuck_[i] = 0;
    left_[i] = 1;
    ++peeled_;
  }
  // New contacts: a surface node at rest on the floor (in the band, not rising) that has not just
  // peeled there.
  for (std::size_t i = 0; i < count; ++i) {
    const double z = state.positions[i].z;
    if (left_[i]) {
      if (z > 2.0 * kAdhesionContactBand) left_[i] = 0;
      continue;
    }
    if (stuck_[i] || state.inverseMasses[i] == 0.0) continue;
    if (z <= kAdhesionContactBand && state.velocities[i].z <= 0.0) {
      stuck_[i] = 1;  // caught where it lands: its sliding stops
      age_[i] = 0.0;
      const glm::dvec3 velocityBefore = state.velocities[i];
      state.velocities[i] = glm::dvec3(0.0, 0.0, std::min(0.0, state.velocities[i].z));
      momentumTaken_ += (velocityBefore - state.velocities[i]) / freeInverseMasses[i];
    }
  }
}

}  // namespace slime

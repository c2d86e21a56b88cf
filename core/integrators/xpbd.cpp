#include "core/integrators/xpbd.h"

#include "core/geometry/volume.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

void projectSprings(ParticleState& state, double h, const XpbdModel& model,
                    const std::vector<glm::dvec3>& previous) {
  const SpringSet& springs = *model.springs;
  std::vector<glm::dvec3>& x = state.positions;
  const std::vector<double>& w = state.inverseMasses;
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
    const double weight = w[i] + w[j];
    if (weight == 0.0) continue;
    const glm::dvec3 d = x[j] - x[i];
    const double length = glm::length(d);
    if (length == 0.0) continue;
    const glm::dvec3 n = d / length;
    const double constraint = length - springs.restLengths[s];
    const double compliance = 1.0 / (springs.stiffnesses[s] * h * h);         // α̃
    const double gamma = model.damping / (springs.stiffnesses[s] * h);  // α β / h
    const double rate = glm::dot(n, (x[j] - previous[j]) - (x[i] - previous[i]));  // ∇C·(x - x_prev)
    const double deltaLambda = (-constraint - gamma * rate) / ((1.0 + gamma) * weight + compliance);
    x[j] += (w[j] * deltaLambda) * n;
    x[i] -= (w[i] * deltaLambda) * n;
  }
}

void projectVolume(ParticleState& state, const XpbdModel& model, XpbdScratch& scratch) {
  const double volume = volumeGradient(state.positions, *model.triangles, scratch.volumeGradient);
  double weight = 0.0;
  for (std::size_t i = 0; i < state.size(); ++i)
    weight += state.inverseMasses[i] * glm::dot(scratch.volumeGradient[i], scratch.volumeGradient[i]);
  if (weight == 0.0) return;
  const double deltaLambda = -(volume - model.restVolume) / weight;
  for (std::size_t i = 0; i < state.size(); ++i)
    state.positions[i] += (state.inverseMasses[i] * deltaLambda) * scratch.volumeGradient[i];
}

}  // namespace

void xpbdSubstep(ParticleState& state, double h, const XpbdModel& model, XpbdScratch& scratch) {
  const std::size_t count = state.size();
  scratch.previousPositions = state.positions;
  for (std::size_t i = 0; i < count; ++i) {
    if (state.inverseMasses[i] != 0.0) state.velocities[i] += h * model.gravity;
    state.positions[i] += h * state.velocities[i];
  }
  if (model.springs) projectSprings(state, h, model, scratch.previousPositions);
  if (model.triangles && !model.triangles->empty()) projectVolume(state, model, scratch);
  for (std::size_t i = 0; i < count; ++i) {
    glm::dvec3& x = state.positions[i];
    glm::dvec3& previous = scratch.previousPositions[i];
    if (state.inverseMasses[i] != 0.0 && x.z < 0.0) {
      // A point that started the substep inside the floor (a scene placed so) is lifted out
      // without the lift becoming speed: v = Δx/h would throw it up at depth/h.
      previous.z = std::max(previous.z, 0.0);
      const double depth = -x.z;
      x.z = 0.0;
      const glm::dvec2 slide(x.x - previous.x, x.y - previous.y);
      const double length = glm::length(slide);
      const double undo = length <= model.friction * depth ? 1.0 : model.friction * depth / length;
      x.x -= undo * slide.x;
      x.y -= undo * slide.y;
    }
    state.velocities[i] = (x - previous) / h;
  }
}

}  // namespace slime

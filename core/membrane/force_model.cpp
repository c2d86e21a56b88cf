#include "core/membrane/force_model.h"

#include "core/geometry/volume.h"

namespace slime {

double computeAccelerations(const ForceModel& model, const std::vector<double>& inverseMasses,
                            const std::vector<glm::dvec3>& positions,
                            const std::vector<glm::dvec3>& velocities, ForceScratch& scratch,
                            std::vector<glm::dvec3>& accelerations) {
  const std::size_t count = positions.size();
  scratch.forces.assign(count, glm::dvec3(0.0));
  if (model.springs) addSpringForces(*model.springs, positions, velocities, model.damping, scratch.forces);
  double pressure = 0.0;
  if (model.triangles && !model.triangles->empty()) {
    const double volume = volumeGradient(positions, *model.triangles, scratch.volumeGradient);
    pressure = fillPressure(volume, model.restVolume, model.restPressure, model.bulkModulus);
    for (std::size_t i = 0; i < count; ++i) scratch.forces[i] += pressure * scratch.volumeGradient[i];
  }
  accelerations.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double w = inverseMasses[i];
    accelerations[i] = w == 0.0 ? glm::dvec3(0.0) : scratch.forces[i] * w + model.gravity;
  }
  return pressure;
}

}  // namespace slime

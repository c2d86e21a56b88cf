#include "core/bulk/viscoelastic.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

double lameLambdaFor(double shearModulus, double poisson) {
  return 2.0 * shearModulus * poisson / (1.0 - 2.0 * poisson);
}

double creepTimeConstant(const ViscoelasticMaterial& material) {
  return material.relaxationTime * (material.longTermShear + material.maxwellShear) / material.longTermShear;
}

TetRest makeTetRest(const glm::dvec3& x0, const glm::dvec3& x1, const glm::dvec3& x2, const glm::dvec3& x3) {
  const glm::dmat3 shape(x1 - x0, x2 - x0, x3 - x0);
  TetRest rest;
  rest.restInverse = glm::inverse(shape);
  rest.volume = glm::determinant(shape) / 6.0;
  rest.forceMap = -rest.volume * glm::transpose(rest.restInverse);
  return rest;
}

double energyDensity(const ViscoelasticMaterial& material, const glm::dmat3& f, const glm::dmat3& maxwellInverse) {
  const double lambdaPrime = volumetricModulus(material);
  const glm::dmat3 c = glm::transpose(f) * f;
  const glm::dmat3 cb = c * maxwellInverse;
  const double traceC = c[0][0] + c[1][1] + c[2][2];
  const double traceCB = cb[0][0] + cb[1][1] + cb[2][2];
  const double j = glm::determinant(f);
  const double volumeTerm = j - restVolumeRatio(material);
  // The constant makes Ψ(I) = 0: λ'/2 (1 − α)².
  const double restVolumeTerm = 1.0 - restVolumeRatio(material);
  return 0.5 * material.longTermShear * (traceC - 3.0) +
         0.5 * lambdaPrime * (volumeTerm * volumeTerm - restVolumeTerm * restVolumeTerm) +
         material.maxwellShear * (0.5 * (traceCB - 3.0) - (j - 1.0));
}

int maxwellFlowInterval(double relaxationTime, double dt, int fewest) {
  constexpr double kFlowsPerRelaxationTime = 60.0;
  constexpr int kMostSteps = 16;
  const double steps = std::floor(relaxationTime / (kFlowsPerRelaxationTime * dt));
  return static_cast<int>(std::clamp(steps, static_cast<double>(fewest), static_cast<double>(kMostSteps)));
}

}  // namespace slime

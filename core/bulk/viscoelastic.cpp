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

double energyDensity(const ViscoelasticMaterial& material, const glm::dmat3& f, const glm::dmat3& maxwellInverse,
                     const glm::dmat3& plasticInverse) {
  const glm::dmat3 c = glm::transpose(f) * f;
  const glm::dmat3 cb = c * plasticInverse;
  const double traceC = c[0][0] + c[1][1] + c[2][2];
  const double traceCB = cb[0][0] + cb[1][1] + cb[2][2];
  return energyDensity(material, f, maxwellInverse) + 0.5 * material.longTermShear * (traceCB - traceC);
}

double deviatoricStretchMeasure(const glm::dmat3& f, const glm::dmat3& plasticInverse) {
  const glm::dmat3 c = glm::transpose(f) * f;
  const double det = glm::determinant(c);
  if (!(det > 0.0)) return 0.0;
  const glm::dmat3 a = c * plasticInverse * inverseCubeRootOfPositive(det);  // C̄ B_p
  const glm::dmat3 a2 = a * a;
  const double trace = a[0][0] + a[1][1] + a[2][2];
  const double traceOfSquare = a2[0][0] + a2[1][1] + a2[2][2];
  return std::sqrt(std::max(0.0, 1.5 * (traceOfSquare - trace * trace / 3.0)));
}

double equivalentStretch(double measure) {
  // u² − 1/u is increasing for u ≥ 1; Newton from above converges monotonically (the function is convex there).
  double u = std::max(1.0, std::sqrt(measure + 1.0)) + 1.0;
  for (int i = 0; i < 60; ++i) {
    const double residual = u * u - 1.0 / u - measure;
    const double step = residual / (2.0 * u + 1.0 / (u * u));
    u -= step;
    if (std::abs(step) < 1e-15 * u) break;
  }
  return std::max(u, 1.0);
}

PlasticFlow plasticFlowOver(const ViscoelasticMaterial& material, double dt) {
  PlasticFlow flow;
  flow.yieldMeasure = yieldMeasure(material.yieldStretch);
  flow.flow = material.plastic ? -std::expm1(-dt / material.plasticFlowTime) : 0.0;
  flow.recovery = material.plastic && material.recoveryTime > 0.0 ? -std::expm1(-dt / material.recoveryTime) : 0.0;
  return flow;
}

glm::dmat3 plasticInverseOf(const glm::dmat3& g) {
  const double a00 = g[1][1] * g[2][2] - g[1][2] * g[1][2], a11 = g[0][0] * g[2][2] - g[0][2] * g[0][2];
  const double a22 = g[0][0] * g[1][1] - g[0][1] * g[0][1], a01 = g[0][2] * g[1][2] - g[0][1] * g[2][2];
  const double a02 = g[0][1] * g[1][2] - g[0][2] * g[1][1], a12 = g[0][1] * g[0][2] - g[0][0] * g[1][2];
  const double inverseDet = 1.0 / (g[0][0] * a00 + g[0][1] * a01 + g[0][2] * a02);
  return glm::dmat3(a00, a01, a02, a01, a11, a12, a02, a12, a22) * inverseDet;
}

glm::dmat3 relaxLongTermBranch(const glm::dmat3& f, const glm::dmat3& metric, const PlasticFlow& flow) {
  const glm::dmat3 c = glm::transpose(f) * f;
  const double detC = glm::determinant(c);
  if (!(detC > 0.0)) return metric;
  const glm::dmat3 isochoric = c * inverseCubeRootOfPositive(detC);
  const double s = deviatoricStretchMeasure(f, plasticInverseOf(metric));
  const double w = s > flow.yieldMeasure ? flow.flow * (1.0 - flow.yieldMeasure / s) : 0.0;
  const double r = s > flow.yieldMeasure ? 0.0 : flow.recovery;
  const glm::dmat3 g = metric + w * (isochoric - metric) + r * (glm::dmat3(1.0) - metric);
  const double det = glm::determinant(g);
  if (!(det > 0.0)) return metric;
  return g * inverseCubeRootOfPositive(det);
}

double plasticStretchOfTrace(double trace) {
  if (!(trace > 3.0)) return 1.0;
  // λ² + 2/λ is increasing for λ ≥ 1 and convex: Newton from above (λ² < trace) converges monotonically.
  double stretch = std::sqrt(trace);
  for (int i = 0; i < 60; ++i) {
    const double step = (stretch * stretch + 2.0 / stretch - trace) / (2.0 * stretch - 2.0 / (stretch * stretch));
    stretch -= step;
    if (!(std::abs(step) > 1e-12 * stretch)) break;
  }
  return std::max(stretch, 1.0);
}

double damageOfTrace(double trace, double damageStretch) {
  if (damageStretch <= 0.0) return 0.0;
  return std::clamp((plasticStretchOfTrace(trace) - damageStretch) / damageStretch, 0.0, 1.0);
}

double plasticHoldTime(double yieldStretch, double flowTime, double u0, double u) {
  const double a = yieldStretch, c = 1.0 / a;
  const double weight = 1.0 / (2.0 * a * a + c);
  const double k = c - 0.25 * a * a;  // v² + a v + c = (v + a/2)² + k
  const auto arc = [&](double v) {    // ∫ dv / ((v + a/2)² + k)
    const double w = v + 0.5 * a;
    if (k > 0.0) return std::atan(w / std::sqrt(k)) / std::sqrt(k);
    if (k < 0.0) {
      const double m = std::sqrt(-k);
      return std::log((w - m) / (w + m)) / (2.0 * m);
    }
    return -1.0 / w;
  };
  const auto primitive = [&](double v) {
    return weight * (std::log(v - a) - 0.5 * std::log(v * v + a * v + c) - 1.5 * a * arc(v));
  };
  return 3.0 * flowTime * (primitive(u0) - primitive(u));
}

int maxwellFlowInterval(double relaxationTime, double dt, int fewest) {
  constexpr double kFlowsPerRelaxationTime = 60.0;
  constexpr int kMostSteps = 16;
  const double steps = std::floor(relaxationTime / (kFlowsPerRelaxationTime * dt));
  return static_cast<int>(std::clamp(steps, static_cast<double>(fewest), static_cast<double>(kMostSteps)));
}

}  // namespace slime

#include "core/viscoelastic.h"

#include "core/cube_root.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

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

MaxwellRest relaxMaxwellBranch(const glm::dmat3& f, const MaxwellRest& rest, double decay) {
  // G = C + (G_v − C)·decay with C = FᵀF (C_ij = f_i·f_j for F's columns), all symmetric: six entries.
  const glm::dmat3& g = rest.metric;
  const double c00 = glm::dot(f[0], f[0]), c11 = glm::dot(f[1], f[1]), c22 = glm::dot(f[2], f[2]);
  const double c01 = glm::dot(f[0], f[1]), c02 = glm::dot(f[0], f[2]), c12 = glm::dot(f[1], f[2]);
  const double m00 = c00 + (g[0][0] - c00) * decay, m11 = c11 + (g[1][1] - c11) * decay;
  const double m22 = c22 + (g[2][2] - c22) * decay, m01 = c01 + (g[0][1] - c01) * decay;
  const double m02 = c02 + (g[0][2] - c02) * decay, m12 = c12 + (g[1][2] - c12) * decay;
  // Its adjugate (cofactors) and determinant.
  const double a00 = m11 * m22 - m12 * m12, a11 = m00 * m22 - m02 * m02, a22 = m00 * m11 - m01 * m01;
  const double a01 = m02 * m12 - m01 * m22, a02 = m01 * m12 - m02 * m11, a12 = m01 * m02 - m00 * m12;
  const double det = m00 * a00 + m01 * a01 + m02 * a02;
  if (!(det > 0.0)) return rest;  // an inverted element keeps its rest state this step
  // G_v = G·det^(−1/3) and B_v = G_v⁻¹ = adj G · det^(1/3)/det = adj G · det^(−2/3).
  const double scale = inverseCubeRoot(det);
  const double inverseScale = scale * scale;
  MaxwellRest flowed;
  flowed.metric = glm::dmat3(m00, m01, m02, m01, m11, m12, m02, m12, m22) * scale;
  flowed.inverse = glm::dmat3(a00, a01, a02, a01, a11, a12, a02, a12, a22) * inverseScale;
  return flowed;
}

}  // namespace slime

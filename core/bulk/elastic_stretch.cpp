#include "core/bulk/elastic_stretch.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace slime {

double largestSymmetricEigenvalue(const glm::dmat3& m, glm::dvec3* direction) {
  const double p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
  const double q = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
  double largest = 0.0;
  if (p1 <= 1e-30 * (q * q + 1e-300)) {
    largest = std::max({m[0][0], m[1][1], m[2][2]});
  } else {
    const double p2 = (m[0][0] - q) * (m[0][0] - q) + (m[1][1] - q) * (m[1][1] - q) + (m[2][2] - q) * (m[2][2] - q) + 2.0 * p1;
    const double p = std::sqrt(p2 / 6.0);
    const glm::dmat3 b = (m - q * glm::dmat3(1.0)) / p;
    const double r = std::clamp(glm::determinant(b) / 2.0, -1.0, 1.0);
    largest = q + 2.0 * p * std::cos(std::acos(r) / 3.0);
  }
  if (direction != nullptr) {
    // The eigenvector is orthogonal to the rows of m − λI: the longest cross product of two of them.
    const glm::dmat3 shifted = m - largest * glm::dmat3(1.0);
    const glm::dvec3 r0 = glm::dvec3(shifted[0][0], shifted[1][0], shifted[2][0]);
    const glm::dvec3 r1 = glm::dvec3(shifted[0][1], shifted[1][1], shifted[2][1]);
    const glm::dvec3 r2 = glm::dvec3(shifted[0][2], shifted[1][2], shifted[2][2]);
    glm::dvec3 best = glm::cross(r0, r1);
    for (const glm::dvec3& candidate : {glm::cross(r0, r2), glm::cross(r1, r2)})
      if (glm::dot(candidate, candidate) > glm::dot(best, best)) best = candidate;
    const double length = glm::length(best);
    *direction = length > 0.0 ? best / length : glm::dvec3(1.0, 0.0, 0.0);
  }
  return largest;
}

double elasticStretchSquared(const BulkBody& body, const std::vector<glm::dvec3>& x, std::size_t e,
                             glm::dvec3* direction) {
  const Tetrahedron& t = body.mesh.tetrahedra[e];
  const glm::dmat3 f = deformationGradient(body.rest[e], x[t.x], x[t.y], x[t.z], x[t.w]);
  const glm::dmat3 inverse = body.material.maxwellShear > 0.0 ? maxwellInverse(body, e) : glm::dmat3(1.0);
  return largestSymmetricEigenvalue(f * inverse * glm::transpose(f), direction);
}

double tearMeasure(const BulkBody& body, const std::vector<glm::dvec3>& x, std::size_t e, double tearStretch) {
  const double excess = std::sqrt(std::max(elasticStretchSquared(body, x, e), 0.0)) - 1.0;
  const double room = (tearStretch - 1.0) * (1.0 - damage(body, e));
  if (room <= 0.0) return excess > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  return excess / room;
}

MostTorn mostTornDamagedElement(const BulkBody& body, double tearStretch) {
  MostTorn most;
  if (body.material.damageStretch <= 0.0) return most;
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    if (damage(body, e) <= 0.0) continue;
    const double measure = tearMeasure(body, body.state.positions, e, tearStretch);
    if (measure >= 1.0 && measure > most.measure) {
      most.measure = measure;
      most.tetrahedron = e;
    }
  }
  return most;
}

MostStretched mostStretchedElement(const BulkBody& body, double atLeast) {
  MostStretched most;
  const std::vector<glm::dvec3>& x = body.state.positions;
  double largest = atLeast * atLeast;
  bool found = false;
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const glm::dmat3 f = deformationGradient(body.rest[e], x[t.x], x[t.y], x[t.z], x[t.w]);
    const glm::dmat3 b = body.material.maxwellShear > 0.0 ? f * maxwellInverse(body, e) * glm::transpose(f)
                                                           : f * glm::transpose(f);
    if (b[0][0] + b[1][1] + b[2][2] < largest) continue;  // λ_max ≤ the trace
    const double squared = largestSymmetricEigenvalue(b);
    if (squared > largest || (!found && squared >= largest)) {
      largest = squared;
      most.tetrahedron = e;
      found = true;
    }
  }
  if (found) most.stretch = std::sqrt(largest);
  return most;
}

}  // namespace slime

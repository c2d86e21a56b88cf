#include "core/membrane/slime_body.h"

#include "core/geometry/volume.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {

std::vector<double> vertexAreas(const std::vector<glm::dvec3>& positions, const std::vector<Triangle>& triangles) {
  std::vector<double> areas(positions.size(), 0.0);
  for (const Triangle& t : triangles) {
    const double third =
        glm::length(glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x])) / 6.0;
    areas[t.x] += third;
    areas[t.y] += third;
    areas[t.z] += third;
  }
  return areas;
}

namespace {

// The pressure whose force p ∇V best cancels the springs' pull at rest (least squares on the
// breathing mode): p0 = -Σ F_i·∇_i V / Σ |∇_i V|².
double balancingPressure(const SlimeBody& body) {
  std::vector<glm::dvec3> forces(body.state.size(), glm::dvec3(0.0));
  const std::vector<glm::dvec3> still(body.state.size(), glm::dvec3(0.0));
  addSpringForces(body.springs, body.state.positions, still, 0.0, forces);
  std::vector<glm::dvec3> gradient;
  volumeGradient(body.state.positions, body.triangles, gradient);
  double work = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < forces.size(); ++i) {
    work += glm::dot(forces[i], gradient[i]);
    norm += glm::dot(gradient[i], gradient[i]);
  }
  return norm > 0.0 ? -work / norm : 0.0;
}

// Turns the mesh about its centre so that the middle of one icosahedron face points straight down:
// the ball then rests on a flat, three-fold symmetric spot at every level (on a corner it would
// topple at level 0) and does not start rolling from a lopsided first contact. Subdivision keeps
// the icosahedron's 12 vertices first, so level 0's first face names the same corners at any level.
void standOnFace(std::vector<glm::dvec3>& positions, const glm::dvec3& center) {
  const Triangle face = makeIcosphere(0, 1.0, glm::dvec3(0.0)).triangles[0];
  const glm::dvec3 from = glm::normalize(positions[face.x] + positions[face.y] + positions[face.z] - 3.0 * center);
  const glm::dvec3 to{0.0, 0.0, -1.0};
  const glm::dvec3 axis = glm::cross(from, to);
  const double sine = glm::length(axis), cosine = glm::dot(from, to);
  if (sine < 1e-12) return;
  const glm::dvec3 k = axis / sine;
  for (glm::dvec3& p : positions) {  // Rodrigues' rotation formula
    const glm::dvec3 r = p - center;
    p = center + r * cosine + glm::cross(k, r) * sine + k * glm::dot(k, r) * (1.0 - cosine);
  }
}

// Turns the mesh about the vertical through its centre to the heading (0.5° steps over the
// icosahedron's 60° symmetry) with the smallest horizontal extent max(x extent, y extent): at low
// levels the polyhedron's footprint is a hexagon whose measured width depends on its heading.
void faceNarrowestHeading(std::vector<glm::dvec3>& positions, const glm::dvec3& center) {
  constexpr double kPi = 3.14159265358979323846;
  double bestAngle = 0.0, bestWidth = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 120; ++step) {
    const double angle = step * 0.5 * kPi / 180.0, c = std::cos(angle), s = std::sin(angle);
    double lowX = 1e300, highX = -1e300, lowY = 1e300, highY = -1e300;
    for (const glm::dvec3& p : positions) {
      const double x = c * (p.x - center.x) - s * (p.y - center.y), y = s * (p.x - center.x) + c * (p.y - center.y);
      lowX = std::min(lowX, x), highX = std::max(highX, x), lowY = std::min(lowY, y), highY = std::max(highY, y);
    }
    const double width = std::max(highX - lowX, highY - lowY);
    if (width < bestWidth - 1e-12) bestWidth = width, bestAngle = angle;
  }
  const double c = std::cos(bestAngle), s = std::sin(bestAngle);
  for (glm::dvec3& p : positions) {
    const double x = p.x - center.x, y = p.y - center.y;
    p.x = center.x + c * x - s * y;
    p.y = center.y + s * x + c * y;
  }
}

}  // namespace

SlimeBody buildSlimeBody(const SlimeSettings& slime) {
  SlimeBody body;
  TriangleMesh mesh = makeIcosphere(slime.level, slime.radius, slime.position);
  standOnFace(mesh.positions, slime.position);
  faceNarrowestHeading(mesh.positions, slime.position);
  body.triangles = std::move(mesh.triangles);
  body.state.positions = std::move(mesh.positions);
  body.state.velocities.assign(body.state.positions.size(), glm::dvec3(0.0));
  body.springs = makeEdgeSprings(body.state.positions, body.triangles, slime.stiffness, 0.0);
  body.springOpposites = edgeOpposites(body.springs.ends, body.triangles);
  body.edgeLengths = body.springs.restLengths;
  double sum = 0.0;
  for (double length : body.edgeLengths) sum += length;
  body.meanEdgeLength = sum / static_cast<double>(body.edgeLengths.size());
  body.restVolume = enclosedVolume(body.state.positions, body.triangles);
  body.restPositions = body.state.positions;
  body.restVertexAreas = vertexAreas(body.restPositions, body.triangles);
  for (double area : body.restVertexAreas) body.restArea += area;
  applySlimeMaterial(body, slime);
  return body;
}

void applySlimeMaterial(SlimeBody& body, const SlimeSettings& slime) {
  const std::vector<double>& areas = body.restVertexAreas;
  const double totalArea = body.restArea;
  body.totalMass = slime.mass;
  body.freeInverseMasses.resize(areas.size());
  // Mass by area share of the rest (round) surface.
  for (std::size_t i = 0; i < areas.size(); ++i)
    body.freeInverseMasses[i] = totalArea / (slime.mass * areas[i]);
  if (body.state.inverseMasses.size() != areas.size()) body.state.inverseMasses = body.freeInverseMasses;
  for (std::size_t i = 0; i < areas.size(); ++i)
    if (body.state.inverseMasses[i] != 0.0) body.state.inverseMasses[i] = body.freeInverseMasses[i];

  const double prestrain = kPrestrainPerPressure * slime.pressure;
  for (std::size_t s = 0; s < body.springs.size(); ++s) {
    body.springs.stiffnesses[s] = seriesStiffness(slime.stiffness, body.meanEdgeLength, body.edgeLengths[s]);
    body.springs.restLengths[s] = body.edgeLengths[s] / (1.0 + prestrain);
  }
  body.bulkModulus = kBulkModulusPerPressure * slime.pressure;
  // The rest pressure balances the skin in its built (round) shape, so compute it there.
  SlimeBody round;
  round.state.positions = body.restPositions;
  round.triangles = body.triangles;
  round.springs = body.springs;
  body.restPressure = slime.pressure > 0.0 ? balancingPressure(round) : 0.0;
}

}  // namespace slime

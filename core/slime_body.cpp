#include "core/slime_body.h"

#include "core/volume.h"

#include <glm/geometric.hpp>

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

}  // namespace

SlimeBody buildSlimeBody(const SlimeSettings& slime) {
  SlimeBody body;
  TriangleMesh mesh = makeIcosphere(slime.level, slime.radius, slime.position);
  body.triangles = std::move(mesh.triangles);
  body.state.positions = std::move(mesh.positions);
  body.state.velocities.assign(body.state.positions.size(), glm::dvec3(0.0));
  body.springs = makeEdgeSprings(body.state.positions, body.triangles, slime.stiffness, 0.0);
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

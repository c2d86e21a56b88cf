// The slime as simulated data, built from its settings: an icosphere's vertices as mass points,
// the mesh edges as springs, the closed surface for the volume, and the material constants that
// turn the relative settings (pressure, ...) into SI values.
//
// How the material scales with the subdivision level so the ball behaves the same at levels 0..7:
//  - mass is spread by each vertex's share of the surface area (one third of its triangles' areas);
//  - the series rule k = k_e d_e / d uses d_e = the mean edge of the current level, so every spring
//    has about k_e and the skin's membrane modulus (√3 k for a triangle lattice) does not depend on
//    the level;
//  - the skin is pre-stretched (rest lengths = edges / (1 + prestrain)); its tension √3 k_e·prestrain/(1+prestrain)
//    (N/m, level independent) is balanced by the filling's rest pressure, like a water balloon;
//  - the damper coefficient k_d (N·s/m) per spring gives a skin viscosity independent of the level.
// What does scale is the highest frequency, ω_max ≈ 2.48 √(k/m) with m ∝ 4^-level: explicit
// steps must halve per level.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/geometry/particle_state.h"
#include "core/settings/settings.h"
#include "core/membrane/springs.h"

#include <vector>

namespace slime {

// Skin prestrain per unit of slime.pressure, and the filling's bulk modulus per unit of it, Pa.
constexpr double kPrestrainPerPressure = 1.0;
constexpr double kBulkModulusPerPressure = 3.0e4;

struct SlimeBody {
  ParticleState state;                 // at rest at slime.position
  std::vector<double> freeInverseMasses;  // inverse masses when nothing is grabbed
  std::vector<Triangle> triangles;
  SpringSet springs;
  std::vector<glm::u32vec2> springOpposites;  // per spring, the third vertices of its two triangles (volume.h)
  std::vector<glm::dvec3> restPositions;  // the built, round shape
  std::vector<double> restVertexAreas;    // each vertex's area share of the round shape, m^2
  std::vector<double> edgeLengths;     // d of each spring at build time (the series rule's d)
  double meanEdgeLength = 0.0;         // d_e
  double restVolume = 0.0;             // V0, m^3
  double restArea = 0.0;               // m^2
  double restPressure = 0.0;           // the fill pressure that balances the prestressed skin, Pa
  double bulkModulus = 0.0;            // Pa
  double totalMass = 0.0;              // kg
};

SlimeBody buildSlimeBody(const SlimeSettings& slime);

// Live material changes that keep the geometry: mass, stiffness, pressure. Recomputes the spring
// constants, rest lengths, inverse masses and rest pressure.
void applySlimeMaterial(SlimeBody& body, const SlimeSettings& slime);

// Area share of each vertex (one third of its triangles' areas).
std::vector<double> vertexAreas(const std::vector<glm::dvec3>& positions, const std::vector<Triangle>& triangles);

}  // namespace slime

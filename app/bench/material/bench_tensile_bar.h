// The meshed bar of the tensile test (issue 29, item 5a): a small tetrahedral cylinder of the slime's
// material, its end faces' nodes clamped (held) and moved apart at a constant engineering strain rate,
// gravity off, as a rheometer pulls a specimen between two grips.
//
// Mesh. A disc of `rings` rings (ring k at radius R·k/K holds 6k nodes, the centre one node; each
// ring zipped to the next by walking both in angle), extruded in equal layers along x; each prism cut
// into three tetrahedra by its nodes' disc order, as the ball's shells are (tet_mesh.cpp: each lateral
// quad is cut from the top of its smaller vertex to the bottom of its larger one, so neighbouring
// prisms share the cut, the mesh is conforming and no tetrahedron is degenerate). Nodes layer by
// layer, so the stiffness is banded (bandwidth 3·(2·nodes per layer)).
//
// Element code. Each tetrahedron is the bulk body's own: `makeTetRest`, `deformationGradient`,
// `firstPiolaStress` with its forces P·(−V0 Dm⁻ᵀ), and the Maxwell flow `relaxMaxwellBranch` once per
// step (core/bulk/viscoelastic.h).
//
// Solve. Quasi-static: at each strain the free nodes are put where the forces balance (Newton's
// method on the elastic energy with the Maxwell rest states held over the step, the tangent assembled
// from the exact directional derivative of P and factored by banded Cholesky), then the Maxwell
// branches flow over the step's Δt = Δε/ε̇. Not the slime's explicit integrator: the closed form it is
// checked against is the quasi-static response of the material, and a dynamic bar would add its own
// inertia (at ε̇ = 5 /s the grips move at a sixth of the bar's wave speed: it rings) and the edge
// dampers' Kelvin–Voigt stress η·ε̇ (150 Pa at 5 /s and the default 30 Pa·s, as large as the material's).
//
// Measured. The nominal stress: the grips' axial reaction (the sum of the internal forces on one end's
// held nodes, which at equilibrium is the force through every cross-section) over the mesh's initial
// cross-section (its rest volume over its length: the polygon disc, not π R²). The strain two ways:
// the grips' (the held ends' separation), and the gauge's — as an extensometer on the middle half of the
// bar does — the mean axial stretch between the cross-sections at L/4 and 3L/4, where the clamps' hold on
// the lateral contraction no longer reaches.
#pragma once

#include "core/bulk/tet_mesh.h"
#include "core/bulk/viscoelastic.h"

#include <vector>

namespace slime {

struct CylinderMesh {
  TetMesh mesh;               // positions and tetrahedra (no surface)
  int nodesPerLayer = 0;
  int layers = 0;             // layers of nodes (elements: layers − 1 along the axis)
  double length = 0.0;        // m, along x, centred on the origin
  double radius = 0.0;        // m
  double crossSection = 0.0;  // m², the polygon disc's area
};

// A cylinder of `radius` and `length` along x, `rings` rings across and `segments` element layers along.
CylinderMesh makeCylinderTetMesh(double radius, double length, int rings, int segments);

struct MeshedBarOptions {
  double radius = 0.01;       // m
  double length = 0.08;       // m (4 diameters)
  int rings = 2;              // rings across the radius
  int segments = 16;          // element layers along the length
  double newtonTolerance = 1e-9;  // of the largest free force, relative to the grips' reaction
  int maxNewtonIterations = 40;
};

struct MeshedBarRun {
  std::vector<double> strains;       // the grips' engineering strain
  std::vector<double> stresses;      // nominal stress, Pa
  std::vector<double> gaugeStrains;  // the middle half's engineering strain
  std::vector<double> middleWidths;  // the middle cross-section's width over its rest width
  int nodes = 0, tetrahedra = 0;
  int newtonIterations = 0;          // over the whole run
  int factorisations = 0;            // of the tangent, over the whole run
  double smallestVolumeRatio = 1.0;  // of any element, J
};

// Stretches the bar from rest to `maxStrain` at `strainRate` in `steps` equal steps.
MeshedBarRun stretchMeshedBar(const ViscoelasticMaterial& material, double strainRate, double maxStrain, int steps,
                              const MeshedBarOptions& options = {});

}  // namespace slime

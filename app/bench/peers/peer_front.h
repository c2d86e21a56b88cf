// The peers on the front's charts (issue 45 item 2): what `bullet_tets --front` and `jolt_tets --front`
// share. Each peer simulates the slime's own tetrahedral ball (makeBallTetMesh, radius 4 cm, 0.268 kg,
// lumped masses) behind the PeerWorld interface; this file runs the same oracles on it at every step ×
// iterations point and writes the points for `slime bench physics --front`:
//  - the peer's stiffness fitted once per resolution, to the static sag: its rest height equals the
//    slime's (`slime sim`, the default slime with viscosity off, or --target-rest-height), at the grid's
//    shortest step and most iterations; the same value at every point;
//  - cost: thread CPU ms per simulated ms of a 2 cm drop onto the floor, landing and contact included;
//  - rest height: the drop's mean height (top minus bottom node) over the last half of the run;
//  - Lamb's n = 2 spheroidal and torsional modes: the free, weightless ball started with the velocity
//    of the mode's shape, its amplitude tracked by mass-weighted projection, frequency fitted from the
//    zero crossings and the damping ratio from the modal energy's decay (app/bench/material/modal_fit.h).
// The JSON: {"peer", "processor", "points": [{"resolution", "step_ms", "iterations", "cost_ms_per_ms",
// "shear_modulus_pa", "density_kg_m3", "radius_m", "poisson", "spheroidal_hz", "torsional_hz",
// "damping_ratio", "rest_height_m", "diverged"}]}; app/bench/peers/README.md says more.
#pragma once

#include "core/bulk/tet_mesh.h"

#include <glm/vec3.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace slime::peers {

constexpr double kRadius = 0.04;  // m
constexpr double kMass = 0.268;   // kg
constexpr double kDrop = 0.02;    // m between the floor and the ball's bottom at the start
constexpr double kPoisson = 0.4;  // the default slime's

// The ball at one resolution, centred on the origin, with each node's lumped mass (a quarter of each
// of its tetrahedra's share of the mass, by volume).
struct PeerBall {
  TetMesh mesh;
  std::vector<double> masses;
  double restVolume = 0.0;
  double density() const { return kMass / restVolume; }
};
PeerBall makePeerBall(int resolution);

// One scene of a peer: the ball, translated by `centre`, stepped by `step` seconds with `iterations`.
struct PeerScene {
  double shearModulus = 0.0;  // Pa, the peer's parameter G (each peer maps it to its own stiffness)
  double step = 0.0;          // s
  int iterations = 1;
  bool dropped = true;  // true: gravity 9.81 m/s² and a static floor at z = 0; false: weightless, no floor
  glm::dvec3 centre{0.0};
  std::vector<glm::dvec3> velocities;  // per node at the start; empty: at rest
};

// A peer's world holding the ball; the only interface the oracles use.
class PeerWorld {
 public:
  virtual ~PeerWorld() = default;
  virtual void step() = 0;  // one step of PeerScene::step
  virtual void positions(std::vector<glm::dvec3>& out) const = 0;   // world positions, per node
  virtual void velocities(std::vector<glm::dvec3>& out) const = 0;  // per node
};

using PeerFactory = std::function<std::unique_ptr<PeerWorld>(const PeerBall&, const PeerScene&)>;

struct PeerInfo {
  std::string name;                  // "jolt", "bullet": the JSON's "peer"
  bool iterates = true;              // false: the peer has no iterations, each point has iterations 1
  double stableStepFloor = 1.0e-4;   // s: the fit halves a diverging step down to this
};

// `<program> --front ...`: parses the front's options from argv (program name at 0), runs the grid and
// writes the JSON. Returns the process's exit status (2 on a bad option, with the usage on stderr).
int runFront(int argc, char** argv, const PeerInfo& peer, const PeerFactory& factory);

}  // namespace slime::peers

// The slime's own tetrahedral body in Bullet's finite-element deformable solver, for `slime bench
// physics` to set beside the bulk body at each resolution: the same tetrahedra (makeBallTetMesh, 85 to
// 23,059 nodes), radius 4 cm, mass 0.268 kg, a stable neo-Hookean energy (Smith et al. 2018 as Bullet
// implements it, btDeformableNeoHookeanForce) with the slime's long-term shear modulus G∞ = longTerm·G
// and Lamé's λ = 2G∞ν / (1 − 2ν) (the rest shape is the long-term one), dropped 2 cm onto a static floor
// at fixed steps. Bullet's explicit scheme, as its own volumetric demo runs it (setImplicit(false), a
// 240 Hz step "for stability issues"): with setImplicit(true) Bullet 3.24 left this 4 cm ball hanging
// in the air, every step's velocity zero, in SI units and in centimetres and grams alike. Each
// resolution takes the longest step of 1/240, 1/480, ... 1/7680 s that keeps every node finite and no
// tetrahedron inverted at the end (--step H fixes it).
// Prints and writes (--json FILE), per resolution: CPU ms per simulated ms (this process, every thread,
// set-up excluded), the rest aspect (height / width), the volume against the rest volume and the
// inverted tetrahedra at the end.
//   usage: bullet_tets [--resolutions 1,2,3] [--seconds 2] [--step H] [--modulus 1200]
//                      [--long-term 0.4] [--poisson 0.4] [--json FILE]
#include "core/bulk/tet_mesh.h"

#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableGravityForce.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btDeformableNeoHookeanForce.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <btBulletDynamicsCommon.h>

#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace {

constexpr double kRadius = 0.04, kMass = 0.268, kDrop = 0.02;
constexpr double kMaxWallSeconds = 60.0;  // a resolution slower than this stops early and says so

struct Options {
  std::vector<int> resolutions{1, 2, 3};
  double seconds = 2.0;
  double step = 0.0;  // 0: the longest stable step of 1/240, 1/480, ... 1/7680 s
  double modulus = 1200.0, longTerm = 0.4, poisson = 0.4;
  std::string json;
};

double cpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec + usage.ru_stime.tv_sec + 1e-6 * usage.ru_stime.tv_usec;
}

double bodyVolume(const btSoftBody& body, const std::vector<slime::Tetrahedron>& tetrahedra, int* inverted) {
  double volume = 0.0;
  *inverted = 0;
  const auto at = [&](std::uint32_t i) {
    const btVector3& p = body.m_nodes[static_cast<int>(i)].m_x;
    return glm::dvec3(p.x(), p.y(), p.z());
  };
  for (const slime::Tetrahedron& t : tetrahedra) {
    const double v = slime::tetrahedronVolume(at(t.x), at(t.y), at(t.z), at(t.w));
    if (v <= 0.0) ++*inverted;
    volume += v;
  }
  return volume;
}

nlohmann::json runBody(int resolution, const Options& options, double step) {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btDeformableBodySolver deformableSolver;
  btDeformableMultiBodyConstraintSolver solver;
  solver.setDeformableSolver(&deformableSolver);
  btDeformableMultiBodyDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration, &deformableSolver);
  const btVector3 gravity(0, 0, -9.81);
  world.setGravity(gravity);
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = gravity;
  info.m_sparsesdf.Initialize();
  info.m_sparsesdf.setDefaultVoxelsz(btScalar(0.005));
  info.m_sparsesdf.Reset();

  btBoxShape floorShape(btVector3(1, 1, 0.5));
  floorShape.setMargin(btScalar(0.001));
  btTransform floorPlace;
  floorPlace.setIdentity();
  floorPlace.setOrigin(btVector3(0, 0, -0.5));
  btDefaultMotionState floorMotion(floorPlace);
  btRigidBody floor(btRigidBody::btRigidBodyConstructionInfo(0, &floorMotion, &floorShape));
  floor.setFriction(0.6);
  world.addRigidBody(&floor);

  const slime::TetMesh mesh = slime::makeBallTetMesh(resolution, kRadius, {0.0, 0.0, kRadius + kDrop});
  std::vector<btVector3> positions;
  for (const glm::dvec3& p : mesh.positions) positions.emplace_back(btScalar(p.x), btScalar(p.y), btScalar(p.z));
  // Lumped masses: each node a quarter of its tetrahedra's share of the mass, by volume.
  std::vector<double> lumped(positions.size(), 0.0);
  double total = 0.0;
  for (const slime::Tetrahedron& t : mesh.tetrahedra) {
    const double v = slime::tetrahedronVolume(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z], mesh.positions[t.w]);
    for (int corner = 0; corner < 4; ++corner) lumped[t[corner]] += 0.25 * v;
    total += v;
  }
  std::vector<btScalar> masses;
  for (double share : lumped) masses.push_back(btScalar(kMass * share / total));
  auto* body = new btSoftBody(&info, static_cast<int>(positions.size()), positions.data(), masses.data());
  for (const slime::Tetrahedron& t : mesh.tetrahedra)
    body->appendTetra(static_cast<int>(t.x), static_cast<int>(t.y), static_cast<int>(t.z), static_cast<int>(t.w));
  // The edges as links too, as CreateFromTetGenData makes them: the node tree Bullet's contact builds
  // pairs neighbouring nodes along the links, and without them it never finishes.
  for (const glm::u32vec2& edge : slime::tetrahedronEdges(mesh.tetrahedra))
    body->appendLink(static_cast<int>(edge.x), static_cast<int>(edge.y), nullptr, true);
  body->initializeDmInverse();
  body->m_tetraScratches.resize(body->m_tetras.size());
  body->m_tetraScratchesTn.resize(body->m_tetras.size());
  btSoftBodyHelpers::generateBoundaryFaces(body);
  body->getCollisionShape()->setMargin(btScalar(0.003));
  body->m_cfg.kKHR = 1;  // contact hardness against kinematic and rigid bodies, as Bullet's demos
  body->m_cfg.kCHR = 1;
  body->m_cfg.kDF = 0.6;  // friction, as the slime's
  body->m_cfg.collisions = btSoftBody::fCollision::SDF_RD | btSoftBody::fCollision::SDF_RDN;  // nodes against the floor
  world.addSoftBody(body);

  const double shear = options.longTerm * options.modulus;
  const double lambda = 2.0 * shear * options.poisson / (1.0 - 2.0 * options.poisson);
  btDeformableGravityForce gravityForce(gravity);
  btDeformableNeoHookeanForce elasticity(btScalar(shear), btScalar(lambda), btScalar(0.01));
  world.addForce(body, &gravityForce);
  world.addForce(body, &elasticity);
  world.setImplicit(false);
  world.setLineSearch(false);

  int inverted = 0;
  const double restVolume = bodyVolume(*body, mesh.tetrahedra, &inverted);
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = cpuSeconds();
  const auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  long steps = 0;
  bool finite = true;
  while (steps * step < options.seconds && wall() < kMaxWallSeconds && finite) {
    world.stepSimulation(btScalar(step), 1, btScalar(step));
    ++steps;
    finite = std::isfinite(body->m_nodes[0].m_x.z());
  }
  const double cpu = cpuSeconds() - cpuStart, simulated = steps * step;

  btVector3 low(1e30, 1e30, 1e30), high(-1e30, -1e30, -1e30);
  for (int i = 0; i < body->m_nodes.size(); ++i) {
    low.setMin(body->m_nodes[i].m_x);
    high.setMax(body->m_nodes[i].m_x);
    finite = finite && std::isfinite(body->m_nodes[i].m_x.length2());
  }
  const double volume = bodyVolume(*body, mesh.tetrahedra, &inverted);
  const double width = std::max(high.x() - low.x(), high.y() - low.y());
  world.removeSoftBody(body);
  delete body;
  world.removeRigidBody(&floor);
  return {{"engine", "bullet btDeformableNeoHookeanForce (explicit)"},
          {"resolution", resolution}, {"nodes", mesh.positions.size()}, {"tetrahedra", mesh.tetrahedra.size()},
          {"step", step}, {"steps", steps}, {"seconds", simulated},
          {"settled", simulated >= options.seconds - 0.5 * step}, {"finite", finite},
          {"cpu_seconds", cpu}, {"cpu_ms_per_simulated_ms", simulated > 0 ? cpu / simulated : 0.0},
          {"aspect", finite && width > 0 ? (high.z() - low.z()) / width : 0.0},
          {"volume_ratio", finite && restVolume > 0 ? volume / restVolume : 0.0}, {"inverted", inverted},
          {"min_z", low.z()}, {"shear_modulus", shear}, {"lambda", lambda}};
}

bool parseList(const char* text, std::vector<int>& out) {
  out.clear();
  for (const char* p = text; *p; ++p) {
    if (*p == ',') continue;
    if (*p < '1' || *p > '4') return false;
    out.push_back(*p - '0');
  }
  return !out.empty();
}

bool parseNumber(const char* text, double low, double high, double& out) {
  char* end = nullptr;
  out = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(out) && out >= low && out <= high;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  const char* usage =
      "usage: bullet_tets [--resolutions 1,2,3 (each 1 to 4)] [--seconds S (0.01 to 60)] [--step H (1e-5 to 0.05 s)]\n"
      "                   [--modulus G (Pa, > 0)] [--long-term F (0 to 1)] [--poisson NU (0 to 0.49)] [--json FILE]\n";
  for (int i = 1; i < argc; i += 2) {
    if (i + 1 >= argc) {
      std::fprintf(stderr, "bullet_tets: %s needs a value\n%s", argv[i], usage);
      return 2;
    }
    const char* value = argv[i + 1];
    bool ok = true;
    if (!std::strcmp(argv[i], "--resolutions")) ok = parseList(value, options.resolutions);
    else if (!std::strcmp(argv[i], "--seconds")) ok = parseNumber(value, 0.01, 60.0, options.seconds);
    else if (!std::strcmp(argv[i], "--step")) ok = parseNumber(value, 1e-5, 0.05, options.step);
    else if (!std::strcmp(argv[i], "--modulus")) ok = parseNumber(value, 1e-3, 1e9, options.modulus);
    else if (!std::strcmp(argv[i], "--long-term")) ok = parseNumber(value, 1e-3, 1.0, options.longTerm);
    else if (!std::strcmp(argv[i], "--poisson")) ok = parseNumber(value, 0.0, 0.49, options.poisson);
    else if (!std::strcmp(argv[i], "--json")) options.json = value;
    else ok = false;
    if (!ok) {
      std::fprintf(stderr, "bullet_tets: bad option %s %s\n%s", argv[i], value, usage);
      return 2;
    }
  }
  nlohmann::json report = nlohmann::json::array();
  for (int resolution : options.resolutions) {
    nlohmann::json run, tries = nlohmann::json::array();
    for (double step = options.step > 0.0 ? options.step : 1.0 / 240.0; step >= 1.0 / 7681.0; step *= 0.5) {
      run = runBody(resolution, options, step);
      tries.push_back({{"step", step}, {"finite", run["finite"]}, {"inverted", run["inverted"]}});
      if (options.step > 0.0 || (run["finite"].get<bool>() && run["inverted"].get<int>() == 0)) break;
    }
    run["tries"] = tries;
    std::printf("bullet tets  resolution %d (%d nodes)  step %.3g ms  %.3f CPU ms per simulated ms  aspect %.3f  volume %.3f  "
                "inverted %d%s%s\n", resolution, run["nodes"].get<int>(), 1e3 * run["step"].get<double>(), run["cpu_ms_per_simulated_ms"].get<double>(),
                run["aspect"].get<double>(), run["volume_ratio"].get<double>(), run["inverted"].get<int>(),
                run["settled"].get<bool>() ? "" : "  (stopped before settling)",
                run["finite"].get<bool>() ? "" : "  (NaN)");
    std::fflush(stdout);
    report.push_back(run);
  }
  if (!options.json.empty()) std::ofstream(options.json) << report.dump(2) << "\n";
  return 0;
}

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
// With --front it measures the front's points instead (peer_front.h: the same oracles as jolt_tets, its
// modulus G fitted to the static sag, Bullet's damping 0, one point per step; Bullet's explicit scheme
// has no iterations):
//          bullet_tets --front [--resolutions 1,2] [--steps-ms 1,2,4,8,16.7] [--seconds S] [--json FILE]
//                      [--target-rest-height H,...] [--slime PATH]
#include "app/bench/peers/peer_front.h"
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
#include <memory>
#include <string>
#include <vector>

namespace {

using slime::peers::kDrop;
using slime::peers::kRadius;
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

// Bullet's deformable world holding the ball: a static floor when dropped, gravity as a deformable
// force, the stable neo-Hookean elasticity of shear modulus G and Lamé's λ with its damping, the edges as
// links (the node tree Bullet's contact builds pairs neighbouring nodes along the links, and without
// them it never finishes), explicit steps.
class BulletWorld final : public slime::peers::PeerWorld {
 public:
  BulletWorld(const slime::peers::PeerBall& ball, const slime::peers::PeerScene& scene, double poisson, double damping)
      : step_(scene.step), world_(&dispatcher_, &broadphase_, &solver_, &configuration_, &deformableSolver_),
        gravity_(0, 0, scene.dropped ? btScalar(-9.81) : btScalar(0)), gravityForce_(gravity_),
        elasticity_(btScalar(scene.shearModulus), btScalar(2.0 * scene.shearModulus * poisson / (1.0 - 2.0 * poisson)),
                    btScalar(damping)) {
    solver_.setDeformableSolver(&deformableSolver_);
    world_.setGravity(gravity_);
    btSoftBodyWorldInfo& info = world_.getWorldInfo();
    info.m_gravity = gravity_;
    info.m_sparsesdf.Initialize();
    info.m_sparsesdf.setDefaultVoxelsz(btScalar(0.005));
    info.m_sparsesdf.Reset();
    if (scene.dropped) {
      floorShape_.setMargin(btScalar(0.001));
      btTransform floorPlace;
      floorPlace.setIdentity();
      floorPlace.setOrigin(btVector3(0, 0, -0.5));
      floorMotion_.setWorldTransform(floorPlace);
      floor_ = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, &floorMotion_, &floorShape_));
      floor_->setFriction(0.6);
      world_.addRigidBody(floor_.get());
    }
    std::vector<btVector3> positions;
    for (const glm::dvec3& p : ball.mesh.positions)
      positions.emplace_back(btScalar(p.x + scene.centre.x), btScalar(p.y + scene.centre.y), btScalar(p.z + scene.centre.z));
    std::vector<btScalar> masses(ball.masses.begin(), ball.masses.end());
    body_ = new btSoftBody(&info, static_cast<int>(positions.size()), positions.data(), masses.data());
    for (const slime::Tetrahedron& t : ball.mesh.tetrahedra)
      body_->appendTetra(static_cast<int>(t.x), static_cast<int>(t.y), static_cast<int>(t.z), static_cast<int>(t.w));
    for (const glm::u32vec2& edge : slime::tetrahedronEdges(ball.mesh.tetrahedra))
      body_->appendLink(static_cast<int>(edge.x), static_cast<int>(edge.y), nullptr, true);
    body_->initializeDmInverse();
    body_->m_tetraScratches.resize(body_->m_tetras.size());
    body_->m_tetraScratchesTn.resize(body_->m_tetras.size());
    btSoftBodyHelpers::generateBoundaryFaces(body_);
    body_->getCollisionShape()->setMargin(btScalar(0.003));
    body_->m_cfg.kKHR = 1;  // contact hardness against kinematic and rigid bodies, as Bullet's demos
    body_->m_cfg.kCHR = 1;
    body_->m_cfg.kDF = 0.6;  // friction, as the slime's
    body_->m_cfg.collisions = btSoftBody::fCollision::SDF_RD | btSoftBody::fCollision::SDF_RDN;  // nodes against the floor
    for (std::size_t i = 0; i < scene.velocities.size(); ++i) {
      const glm::dvec3& v = scene.velocities[i];
      body_->m_nodes[static_cast<int>(i)].m_v = btVector3(btScalar(v.x), btScalar(v.y), btScalar(v.z));
    }
    world_.addSoftBody(body_);
    if (scene.dropped) world_.addForce(body_, &gravityForce_);
    world_.addForce(body_, &elasticity_);
    world_.setImplicit(false);
    world_.setLineSearch(false);
  }
  ~BulletWorld() override {
    world_.removeSoftBody(body_);
    delete body_;
    if (floor_) world_.removeRigidBody(floor_.get());
  }
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  void step() override { world_.stepSimulation(btScalar(step_), 1, btScalar(step_)); }
  void positions(std::vector<glm::dvec3>& out) const override {
    out.resize(static_cast<std::size_t>(body_->m_nodes.size()));
    for (int i = 0; i < body_->m_nodes.size(); ++i) {
      const btVector3& x = body_->m_nodes[i].m_x;
      out[static_cast<std::size_t>(i)] = {x.x(), x.y(), x.z()};
    }
  }
  void velocities(std::vector<glm::dvec3>& out) const override {
    out.resize(static_cast<std::size_t>(body_->m_nodes.size()));
    for (int i = 0; i < body_->m_nodes.size(); ++i) {
      const btVector3& v = body_->m_nodes[i].m_v;
      out[static_cast<std::size_t>(i)] = {v.x(), v.y(), v.z()};
    }
  }
  const btSoftBody& body() const { return *body_; }

 private:
  double step_;
  btSoftBodyRigidBodyCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btDeformableBodySolver deformableSolver_;
  btDeformableMultiBodyConstraintSolver solver_;
  btDeformableMultiBodyDynamicsWorld world_;
  btVector3 gravity_;
  btDeformableGravityForce gravityForce_;
  btDeformableNeoHookeanForce elasticity_;
  btBoxShape floorShape_{btVector3(1, 1, 0.5)};
  btDefaultMotionState floorMotion_;
  std::unique_ptr<btRigidBody> floor_;
  btSoftBody* body_ = nullptr;
};

nlohmann::json runBody(int resolution, const Options& options, double step) {
  const slime::peers::PeerBall ball = slime::peers::makePeerBall(resolution);
  const slime::TetMesh& mesh = ball.mesh;
  const double shear = options.longTerm * options.modulus;
  const double lambda = 2.0 * shear * options.poisson / (1.0 - 2.0 * options.poisson);
  slime::peers::PeerScene scene;
  scene.shearModulus = shear;
  scene.step = step;
  scene.centre = {0.0, 0.0, kRadius + kDrop};
  BulletWorld world(ball, scene, options.poisson, 0.01);
  const btSoftBody* body = &world.body();

  int inverted = 0;
  const double restVolume = bodyVolume(*body, mesh.tetrahedra, &inverted);
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = cpuSeconds();
  const auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  long steps = 0;
  bool finite = true;
  while (steps * step < options.seconds && wall() < kMaxWallSeconds && finite) {
    world.step();
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
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--front")) {
      const slime::peers::PeerInfo peer{"bullet", false, 1.0e-4};
      return slime::peers::runFront(argc, argv, peer, [](const slime::peers::PeerBall& ball, const slime::peers::PeerScene& scene) {
        return std::unique_ptr<slime::peers::PeerWorld>(new BulletWorld(ball, scene, slime::peers::kPoisson, 0.0));
      });
    }
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

// The same slime in Bullet's btSoftBody, for `slime bench physics` to be compared with: the
// icosphere of the same level (same vertex count), radius 4 cm, mass 0.268 kg, held round by
// Bullet's volume conservation (kVC) with 4 position iterations, dropped 2 cm onto a static floor
// and stepped at a fixed 1 ms. Prints and writes (--json FILE) ms per step and the roundness at
// rest: aspect = height / width and the spread of the vertices' distances from their centroid.
//   usage: bullet_ball [--levels 4,6] [--seconds 2] [--json FILE]
#include "core/geometry/icosphere.h"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr double kRadius = 0.04, kMass = 0.268, kDrop = 0.02, kStep = 1e-3;
constexpr double kMaxWallSeconds = 30.0;  // a level that settles slower than this stops early

nlohmann::json runBall(int level, double seconds) {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, 0, -9.81));
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = btVector3(0, 0, -9.81);
  info.m_sparsesdf.Initialize();
  info.m_sparsesdf.setDefaultVoxelsz(btScalar(0.005));

  btStaticPlaneShape floorShape(btVector3(0, 0, 1), 0);
  btDefaultMotionState floorMotion;
  btRigidBody floor(btRigidBody::btRigidBodyConstructionInfo(0, &floorMotion, &floorShape));
  world.addRigidBody(&floor);

  const slime::TriangleMesh mesh = slime::makeIcosphere(level, kRadius, {0.0, 0.0, kRadius + kDrop});
  std::vector<btScalar> vertices;
  for (const glm::dvec3& p : mesh.positions) vertices.insert(vertices.end(), {btScalar(p.x), btScalar(p.y), btScalar(p.z)});
  std::vector<int> triangles;
  for (const slime::Triangle& t : mesh.triangles) triangles.insert(triangles.end(), {int(t.x), int(t.y), int(t.z)});
  btSoftBody* ball = btSoftBodyHelpers::CreateFromTriMesh(info, vertices.data(), triangles.data(),
                                                          static_cast<int>(mesh.triangles.size()), false);
  ball->m_materials[0]->m_kLST = 0.5;  // linear stiffness of the edge links
  ball->m_cfg.kVC = 20;                 // volume conservation
  ball->m_cfg.kDP = 0.005;              // damping
  ball->m_cfg.kDF = 0.6;                // friction, as the slime's
  ball->m_cfg.piterations = 4;
  ball->setPose(true, false);           // keep the volume (and the shape's pose) of the round ball
  ball->setTotalMass(kMass, true);
  // Bullet's default margins (0.25 m for soft bodies, 0.04 m for shapes) are for metre-sized objects.
  ball->getCollisionShape()->setMargin(btScalar(0.001));
  floorShape.setMargin(btScalar(0.001));
  world.addSoftBody(ball);

  const auto start = std::chrono::steady_clock::now();
  const auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  long steps = 0;
  while (steps * kStep < seconds && wall() < kMaxWallSeconds) {
    world.stepSimulation(kStep, 0, kStep);
    ++steps;
  }
  const double msPerStep = 1e3 * wall() / std::max(1L, steps);

  btVector3 low(1e30, 1e30, 1e30), high(-1e30, -1e30, -1e30), centroid(0, 0, 0);
  for (int i = 0; i < ball->m_nodes.size(); ++i) {
    const btVector3& p = ball->m_nodes[i].m_x;
    low.setMin(p);
    high.setMax(p);
    centroid += p;
  }
  centroid /= btScalar(ball->m_nodes.size());
  double sum = 0.0, sumSquares = 0.0;
  for (int i = 0; i < ball->m_nodes.size(); ++i) {
    const double r = (ball->m_nodes[i].m_x - centroid).length();
    sum += r;
    sumSquares += r * r;
  }
  const double n = ball->m_nodes.size(), mean = sum / n;
  const double width = std::max(high.x() - low.x(), high.y() - low.y());
  world.removeSoftBody(ball);
  delete ball;
  world.removeRigidBody(&floor);
  return {{"engine", "bullet btSoftBody"}, {"level", level}, {"vertices", mesh.positions.size()}, {"steps", steps},
          {"seconds", steps * kStep}, {"settled", steps * kStep >= seconds}, {"ms_per_step", msPerStep},
          {"aspect", width > 0 ? (high.z() - low.z()) / width : 0.0},
          {"radius_spread", std::sqrt(std::max(0.0, sumSquares / n - mean * mean)) / mean},
          {"min_z", low.z()}, {"position_iterations", 4}, {"volume_conservation", 20}};
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> levels{4, 6};
  double seconds = 2.0;
  std::string jsonFile;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--levels")) {
      levels.clear();
      for (const char* p = argv[i + 1]; *p; ++p)
        if (*p >= '0' && *p <= '9') levels.push_back(*p - '0');
    } else if (!std::strcmp(argv[i], "--seconds")) {
      seconds = std::atof(argv[i + 1]);
    } else if (!std::strcmp(argv[i], "--json")) {
      jsonFile = argv[i + 1];
    } else {
      std::fprintf(stderr, "usage: bullet_ball [--levels 4,6] [--seconds 2] [--json FILE]\n");
      return 2;
    }
  }
  nlohmann::json report = nlohmann::json::array();
  for (int level : levels) {
    const nlohmann::json ball = runBall(level, seconds);
    std::printf("bullet    level %d (%d vertices)  %.3f ms/step  aspect %.3f  radius spread %.4f%s\n", level,
                ball["vertices"].get<int>(), ball["ms_per_step"].get<double>(), ball["aspect"].get<double>(),
                ball["radius_spread"].get<double>(), ball["settled"].get<bool>() ? "" : "  (stopped before settling)");
    report.push_back(ball);
  }
  if (!jsonFile.empty()) std::ofstream(jsonFile) << report.dump(2) << "\n";
  return 0;
}

// The slime's own tetrahedral ball as Jolt's soft body (Jolt Physics, pinned in
// third_party/JoltPhysics/README.md), for the front's charts (issue 45 item 2; peer_front.h runs the
// oracles): the same tetrahedra and lumped masses (makeBallTetMesh, radius 4 cm, 0.268 kg), every edge
// a distance constraint and every tetrahedron a volume constraint (Jolt's tetrahedral soft body, XPBD
// with one constraint pass per substep: Jolt's "iterations" are substeps of the step), linear damping
// 0, dropped onto a static box, on one thread (JobSystemSingleThreaded).
//
// The compliances come from one shear modulus G, so that the fit to the static sag has one parameter:
//  - an edge constraint is a spring of stiffness k = 1/α (N/m). Springs along the six edges of each
//    tetrahedron, k_e = Σ_t c G V_t / L_e², store for a uniform strain ε on average over orientations
//    (⟨(ê·ε·ê)²⟩ = (2 ε:ε + (tr ε)²) / 15) the energy V_t c G (2 ε:ε + (tr ε)²) / 5; c = 2.5 makes the
//    deviatoric part G ε:ε V_t, linear elasticity's, and leaves a bulk modulus G from the springs;
//  - a volume constraint C = 6V − 6V₀ of compliance α stores C² / (2α) = K_v (ΔV)² / (2 V₀) for
//    α = 36 V₀ / K_v, with K_v = K − G, K = 2G(1 + ν) / (3(1 − 2ν)), ν = 0.4: the body's bulk modulus K.
//   usage: jolt_tets --front [--resolutions 1,2] [--steps-ms 1,2,4,8,16.7] [--iterations 1,2,4,8]
//                    [--seconds S] [--json FILE] [--target-rest-height H,...] [--slime PATH]
#include "app/bench/peers/peer_front.h"

// Jolt.h first: every other Jolt header relies on it.
#include <Jolt/Jolt.h>

#include <Jolt/Core/Factory.h>
#include <Jolt/Core/JobSystemSingleThreaded.h>
#include <Jolt/Core/TempAllocator.h>
#include <Jolt/Physics/Body/BodyCreationSettings.h>
#include <Jolt/Physics/Collision/BroadPhase/BroadPhaseLayerInterfaceTable.h>
#include <Jolt/Physics/Collision/BroadPhase/ObjectVsBroadPhaseLayerFilterTable.h>
#include <Jolt/Physics/Collision/ObjectLayerPairFilterTable.h>
#include <Jolt/Physics/Collision/Shape/BoxShape.h>
#include <Jolt/Physics/PhysicsSystem.h>
#include <Jolt/Physics/SoftBody/SoftBodyCreationSettings.h>
#include <Jolt/Physics/SoftBody/SoftBodyMotionProperties.h>
#include <Jolt/Physics/SoftBody/SoftBodySharedSettings.h>
#include <Jolt/RegisterTypes.h>

#include <glm/geometric.hpp>

#include <cstdio>
#include <string>
#include <map>
#include <memory>
#include <utility>

namespace {

using slime::peers::PeerBall;
using slime::peers::PeerScene;
using slime::peers::PeerWorld;

constexpr double kEdgeFactor = 2.5;  // c above
constexpr float kFriction = 0.6f;    // the slime's against the floor
constexpr JPH::ObjectLayer kStatic = 0, kMoving = 1;

// Jolt's shared settings of the ball for shear modulus G, as the file's comment derives them.
JPH::Ref<JPH::SoftBodySharedSettings> ballSettings(const PeerBall& ball, double shear) {
  const std::vector<glm::dvec3>& p = ball.mesh.positions;
  JPH::Ref<JPH::SoftBodySharedSettings> settings = new JPH::SoftBodySharedSettings;
  for (std::size_t i = 0; i < p.size(); ++i)
    settings->mVertices.emplace_back(JPH::Float3(float(p[i].x), float(p[i].y), float(p[i].z)), JPH::Float3(0, 0, 0),
                                     float(1.0 / ball.masses[i]));
  const double bulk = 2.0 * shear * (1.0 + slime::peers::kPoisson) / (3.0 * (1.0 - 2.0 * slime::peers::kPoisson));
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> edgeStiffness;
  for (const slime::Tetrahedron& t : ball.mesh.tetrahedra) {
    const double volume = slime::tetrahedronVolume(p[t.x], p[t.y], p[t.z], p[t.w]);
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const double length = glm::distance(p[t[a]], p[t[b]]);
        edgeStiffness[{std::min(t[a], t[b]), std::max(t[a], t[b])}] += kEdgeFactor * shear * volume / (length * length);
      }
    settings->mVolumeConstraints.emplace_back(t.x, t.y, t.z, t.w, float(36.0 * volume / (bulk - shear)));
  }
  for (const auto& [edge, stiffness] : edgeStiffness)
    settings->mEdgeConstraints.emplace_back(edge.first, edge.second, float(1.0 / stiffness));
  settings->CalculateEdgeLengths();
  settings->CalculateVolumeConstraintVolumes();
  settings->Optimize();
  return settings;
}

// Jolt's process-wide set-up, once.
void initialiseJolt() {
  JPH::RegisterDefaultAllocator();
  JPH::Factory::sInstance = new JPH::Factory();
  JPH::RegisterTypes();
}

class JoltWorld final : public PeerWorld {
 public:
  JoltWorld(const PeerBall& ball, const PeerScene& scene)
      : step_(float(scene.step)) {
    layers_.MapObjectToBroadPhaseLayer(kStatic, JPH::BroadPhaseLayer(0));
    layers_.MapObjectToBroadPhaseLayer(kMoving, JPH::BroadPhaseLayer(0));
    pairs_.EnableCollision(kMoving, kStatic);
    // The table copies the layers' pairs when it is made, so it comes after them.
    objectVsBroadPhase_ = std::make_unique<JPH::ObjectVsBroadPhaseLayerFilterTable>(layers_, 1, pairs_, 2);
    system_.Init(16, 0, 64, 64, layers_, *objectVsBroadPhase_, pairs_);
    system_.SetGravity(JPH::Vec3(0, 0, scene.dropped ? -9.81f : 0.0f));
    JPH::BodyInterface& bodies = system_.GetBodyInterface();
    if (scene.dropped) {
      JPH::BodyCreationSettings floor(new JPH::BoxShape(JPH::Vec3(1, 1, 0.5f)), JPH::RVec3(0, 0, -0.5f),
                                      JPH::Quat::sIdentity(), JPH::EMotionType::Static, kStatic);
      floor.mFriction = kFriction;
      bodies.CreateAndAddBody(floor, JPH::EActivation::DontActivate);
    }
    JPH::SoftBodyCreationSettings soft(ballSettings(ball, scene.shearModulus),
                                       JPH::RVec3(float(scene.centre.x), float(scene.centre.y), float(scene.centre.z)),
                                       JPH::Quat::sIdentity(), kMoving);
    soft.mNumIterations = JPH::uint32(scene.iterations);
    soft.mLinearDamping = 0.0f;  // the oracles measure the solver's own damping
    soft.mFriction = kFriction;
    soft.mRestitution = 0.0f;
    soft.mAllowSleeping = false;
    body_ = bodies.CreateSoftBody(soft);
    bodies.AddBody(body_->GetID(), JPH::EActivation::Activate);
    if (!scene.velocities.empty()) {
      JPH::Array<JPH::SoftBodyVertex>& vertices = motion().GetVertices();
      for (std::size_t i = 0; i < vertices.size(); ++i)
        vertices[i].mVelocity = JPH::Vec3(float(scene.velocities[i].x), float(scene.velocities[i].y), float(scene.velocities[i].z));
    }
    system_.OptimizeBroadPhase();
  }

  void step() override { system_.Update(step_, 1, &temporary_, &jobs_); }

  void positions(std::vector<glm::dvec3>& out) const override {
    const JPH::RMat44 transform = body_->GetCenterOfMassTransform();
    const JPH::Array<JPH::SoftBodyVertex>& vertices = motion().GetVertices();
    out.resize(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const JPH::RVec3 x = transform * vertices[i].mPosition;
      out[i] = {x.GetX(), x.GetY(), x.GetZ()};
    }
  }

  void velocities(std::vector<glm::dvec3>& out) const override {
    const JPH::RMat44 transform = body_->GetCenterOfMassTransform();
    const JPH::Array<JPH::SoftBodyVertex>& vertices = motion().GetVertices();
    out.resize(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const JPH::Vec3 v = transform.Multiply3x3(vertices[i].mVelocity);
      out[i] = {v.GetX(), v.GetY(), v.GetZ()};
    }
  }

 private:
  JPH::SoftBodyMotionProperties& motion() const {
    return *static_cast<JPH::SoftBodyMotionProperties*>(body_->GetMotionProperties());
  }

  float step_;
  JPH::TempAllocatorImpl temporary_{32 * 1024 * 1024};
  JPH::JobSystemSingleThreaded jobs_{JPH::cMaxPhysicsJobs};
  // Both layers in one broad-phase layer; the ball meets the floor.
  JPH::BroadPhaseLayerInterfaceTable layers_{2, 1};
  JPH::ObjectLayerPairFilterTable pairs_{2};
  std::unique_ptr<JPH::ObjectVsBroadPhaseLayerFilterTable> objectVsBroadPhase_;  // made from the two above
  JPH::PhysicsSystem system_;
  JPH::Body* body_ = nullptr;
};

}  // namespace

int main(int argc, char** argv) {
  bool front = false;
  for (int i = 1; i < argc; ++i) front = front || std::string(argv[i]) == "--front";
  if (!front) {
    std::fprintf(stderr, "jolt_tets: it measures the front's points only; run it with --front (the file's head "
                         "lists the options)\n");
    return 2;
  }
  initialiseJolt();
  const slime::peers::PeerInfo peer{"jolt", true, 1.0e-4};
  return slime::peers::runFront(argc, argv, peer, [](const PeerBall& ball, const PeerScene& scene) {
    return std::unique_ptr<PeerWorld>(new JoltWorld(ball, scene));
  });
}

#include "render/trace/embree_scene.h"

#include "render/trace/embree_util.h"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace slime {
namespace {

// A refitted BVH degrades as the mesh deforms (SPEC §10: ≈ 0.65–0.7× on a squashed slime): rebuild
// when the bounding radius has changed by this fraction since the last build, or after this many refits.
constexpr float kRebuildRadiusChange = 0.2f;
constexpr int kRebuildAfterRefits = 600;

// The rays' 8 floats each (origin, direction, tNear, tFar) into the packet's 8 lanes of each: an
// 8 × 8 transpose in AVX2 builds.
static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, direction) == 3 * sizeof(float) &&
                  offsetof(Ray, tNear) == 6 * sizeof(float) && offsetof(Ray, tFar) == 7 * sizeof(float),
              "Ray is read as 8 consecutive floats");
void toPacket(const Ray* rays, RTCRay8& packet) {
#if defined(__AVX2__)
  __m256 r[8], t[8], u[8];
  for (int i = 0; i < 8; ++i) r[i] = _mm256_loadu_ps(&rays[i].origin.x);
  for (int i = 0; i < 8; i += 2) {
    t[i] = _mm256_unpacklo_ps(r[i], r[i + 1]);
    t[i + 1] = _mm256_unpackhi_ps(r[i], r[i + 1]);
  }
  for (int i = 0; i < 8; i += 4) {
    u[i] = _mm256_shuffle_ps(t[i], t[i + 2], 0x44);
    u[i + 1] = _mm256_shuffle_ps(t[i], t[i + 2], 0xEE);
    u[i + 2] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0x44);
    u[i + 3] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0xEE);
  }
  float* columns[8] = {packet.org_x, packet.org_y, packet.org_z, packet.dir_x,
                       packet.dir_y, packet.dir_z, packet.tnear, packet.tfar};
  for (int j = 0; j < 4; ++j) {
    _mm256_store_ps(columns[j], _mm256_permute2f128_ps(u[j], u[j + 4], 0x20));
    _mm256_store_ps(columns[j + 4], _mm256_permute2f128_ps(u[j], u[j + 4], 0x31));
  }
#else
  for (int i = 0; i < 8; ++i) {
    packet.org_x[i] = rays[i].origin.x;
    packet.org_y[i] = rays[i].origin.y;
    packet.org_z[i] = rays[i].origin.z;
    packet.dir_x[i] = rays[i].direction.x;
    packet.dir_y[i] = rays[i].direction.y;
    packet.dir_z[i] = rays[i].direction.z;
    packet.tnear[i] = rays[i].tNear;
    packet.tfar[i] = rays[i].tFar;
  }
#endif
}

}  // namespace

EmbreeScene::EmbreeScene(int threads) {
  // No start_threads: with a thread limit below the core count Embree 3.13.5 can deadlock (SPEC §10).
  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) + ",set_affinity=0" : "set_affinity=0";
  device_ = rtcNewDevice(config.c_str());
  if (!device_) throw std::runtime_error("Embree: cannot create a device (" + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  rtcSetDeviceErrorFunction(device_, recordEmbreeError, &error_);
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_LOW);

  sphere_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* point = static_cast<float*>(
      rtcSetNewGeometryBuffer(sphere_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  if (point) point[0] = point[1] = point[2] = point[3] = 0.0f;
  rtcCommitGeometry(sphere_);
  sphereId_ = rtcAttachGeometry(scene_, sphere_);
  rtcDisableGeometry(sphere_);
  rtcCommitScene(scene_);

  nonSupportingScene_ = rtcNewScene(device_);
  rtcSetSceneFlags(nonSupportingScene_, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(nonSupportingScene_, RTC_BUILD_QUALITY_LOW);
  nonSupporting_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(nonSupporting_, RTC_BUILD_QUALITY_LOW);
  rtcAttachGeometry(nonSupportingScene_, nonSupporting_);
  rtcDisableGeometry(nonSupporting_);
  rtcCommitScene(nonSupportingScene_);
  throwOnError("creating the scene");
}

EmbreeScene::~EmbreeScene() {
  if (mesh_) rtcReleaseGeometry(mesh_);
  if (sphere_) rtcReleaseGeometry(sphere_);
  if (nonSupporting_) rtcReleaseGeometry(nonSupporting_);
  if (scene_) rtcReleaseScene(scene_);
  if (nonSupportingScene_) rtcReleaseScene(nonSupportingScene_);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::throwOnError(const char* during) {
  if (error_.empty()) return;
  const std::string message = error_ + " (while " + during + ")";
  error_.clear();
  throw std::runtime_error(message);
}

void EmbreeScene::attachMesh(const SlimeGeometry& geometry) {
  if (mesh_) {
    rtcDetachGeometry(scene_, meshId_);
    rtcReleaseGeometry(mesh_);
    mesh_ = nullptr;
  }
  if (geometry.triangles.empty()) return;
  mesh_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(mesh_, RTC_BUILD_QUALITY_REFIT);
  // Shared buffers: the positions array carries one padding vertex (Embree reads 16 bytes at a time).
  rtcSetSharedGeometryBuffer(mesh_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, geometry.positions.data(), 0,
                             sizeof(glm::vec3), geometry.vertexCount());
  rtcSetSharedGeometryBuffer(mesh_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, geometry.triangles.data(), 0,
                             sizeof(Triangle), geometry.triangles.size());
  rtcCommitGeometry(mesh_);
  meshId_ = rtcAttachGeometry(scene_, mesh_);
}

void EmbreeScene::update(const SlimeGeometry& geometry, bool topologyChanged) {
  const bool newMesh = topologyChanged || !mesh_;
  if (newMesh) {
    attachMesh(geometry);
    builtRadius_ = geometry.boundRadius;
    refitsSinceBuild_ = 0;
    ++rebuilds_;
  } else {
    const bool drifted = std::abs(geometry.boundRadius - builtRadius_) > kRebuildRadiusChange * builtRadius_;
    if (drifted || ++refitsSinceBuild_ >= kRebuildAfterRefits) {
      // Touching the index buffer makes Embree build this mesh's BVH from scratch.
      rtcUpdateGeometryBuffer(mesh_, RTC_BUFFER_TYPE_INDEX, 0);
      builtRadius_ = geometry.boundRadius;
      refitsSinceBuild_ = 0;
      ++rebuilds_;
    }
    rtcUpdateGeometryBuffer(mesh_, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(mesh_);
  }

  if (geometry.analyticSphere) {
    auto* point = static_cast<float*>(rtcGetGeometryBufferData(sphere_, RTC_BUFFER_TYPE_VERTEX, 0));
    point[0] = geometry.sphereCenter.x;
    point[1] = geometry.sphereCenter.y;
    point[2] = geometry.sphereCenter.z;
    point[3] = geometry.sphereRadius;
    rtcUpdateGeometryBuffer(sphere_, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(sphere_);
  }
  if (geometry.analyticSphere != sphereEnabled_) {
    sphereEnabled_ = geometry.analyticSphere;
    if (sphereEnabled_) rtcEnableGeometry(sphere_); else rtcDisableGeometry(sphere_);
  }
  if (mesh_) {
    if (geometry.analyticSphere) rtcDisableGeometry(mesh_); else rtcEnableGeometry(mesh_);
  }
  rtcCommitScene(scene_);
  throwOnError("refitting the slime");
  buildNonSupporting(geometry);
  geometry_ = &geometry;
  if (newMesh) exitWalk_.connect(geometry.triangles);
  if (!geometry.analyticSphere) exitWalk_.map(geometry);
  lightGrid_.stale = eyeGrid_.stale = true;
}

void EmbreeScene::ApexGrid::prepare(const SlimeGeometry& geometry, const glm::vec3& apex, bool wanted) {
  if (!wanted) {
    grid.clear();
    stale = true;
    return;
  }
  if (!stale && apex == grid.apex()) return;
  grid.build(geometry, apex, facingApexOnly);
  stale = false;
}

void EmbreeScene::prepareLight(const SlimeGeometry& geometry, const glm::vec3& light, bool wanted) {
  lightGrid_.prepare(geometry, light, wanted);
}

void EmbreeScene::prepareEye(const SlimeGeometry& geometry, const glm::vec3& eye, bool wanted) {
  eyeGrid_.prepare(geometry, eye, wanted);
}

bool EmbreeScene::lightCrossings8(const Ray* rays, const bool* active, SegmentCrossings* crossings) const {
  if (!lightGrid_.serves()) return false;
  for (int i = 0; i < 8; ++i) {
    if (active[i]) lightGrid_.grid.crossings(rays[i], crossings[i]);
    else crossings[i].count = 0;
  }
  return true;
}

bool EmbreeScene::primaryHits8(const Ray* rays, const bool* active, SlimeHit* hits) const {
  if (!eyeGrid_.serves()) return false;
  for (int i = 0; i < 8; ++i) hits[i] = active[i] ? eyeGrid_.grid.nearest(rays[i]) : SlimeHit{};
  return true;
}

bool EmbreeScene::supportingExits(const Ray* rays, const glm::vec3* exitPoints, const bool* active, SlimeHit* hits) const {
  if (!geometry_ || geometry_->analyticSphere) return false;
  exitWalk_.supportingExits(*geometry_, rays, exitPoints, active, hits);
  return true;
}

void EmbreeScene::buildNonSupporting(const SlimeGeometry& geometry) {
  nonSupportingPrimitives_ = &geometry.nonSupportingPrimitives;
  const bool any = !geometry.analyticSphere && !geometry.nonSupportingTriangles.empty();
  if (any) {
    rtcSetSharedGeometryBuffer(nonSupporting_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, geometry.positions.data(), 0,
                               sizeof(glm::vec3), geometry.vertexCount());
    rtcSetSharedGeometryBuffer(nonSupporting_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               geometry.nonSupportingTriangles.data(), 0, sizeof(Triangle),
                               geometry.nonSupportingTriangles.size());
    rtcCommitGeometry(nonSupporting_);
    rtcEnableGeometry(nonSupporting_);
  } else {
    rtcDisableGeometry(nonSupporting_);
  }
  rtcCommitScene(nonSupportingScene_);
  throwOnError("building the non-supporting triangles");
}

SlimeHit EmbreeScene::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayHit;
  toEmbreeRay(ray, rayHit.ray);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rayHit);
  SlimeHit hit;
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.t = rayHit.ray.tfar;
  hit.primitive = rayHit.hit.geomID == sphereId_ ? 0u : rayHit.hit.primID;
  hit.u = rayHit.hit.u;
  hit.v = rayHit.hit.v;
  return hit;
}

void EmbreeScene::intersect8(const Ray* rays, const bool* active, SlimeHit* hits) const {
  intersect8In(scene_, nullptr, rays, active, hits);
}

void EmbreeScene::intersectNonSupporting8(const Ray* rays, const bool* active, SlimeHit* hits) const {
  intersect8In(nonSupportingScene_, nonSupportingPrimitives_, rays, active, hits);
}

void EmbreeScene::intersect8In(RTCScene scene, const std::vector<std::uint32_t>* primitives, const Ray* rays,
                               const bool* active, SlimeHit* hits) const {
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 packet;
  for (int i = 0; i < 8; ++i) {
    valid[i] = active[i] ? -1 : 0;
    packet.ray.time[i] = 0.0f;
    packet.ray.mask[i] = 0xFFFFFFFFu;
    packet.ray.id[i] = static_cast<unsigned>(i);
    packet.ray.flags[i] = 0;
    packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
  }
  toPacket(rays, packet.ray);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect8(valid, scene, &context, &packet);
  for (int i = 0; i < 8; ++i) {
    hits[i] = SlimeHit{};
    if (!active[i] || packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
    hits[i].t = packet.ray.tfar[i];
    hits[i].primitive = primitives                       ? (*primitives)[packet.hit.primID[i]]
                        : packet.hit.geomID[i] == sphereId_ ? 0u
                                                            : packet.hit.primID[i];
    hits[i].u = packet.hit.u[i];
    hits[i].v = packet.hit.v[i];
  }
}

}  // namespace slime

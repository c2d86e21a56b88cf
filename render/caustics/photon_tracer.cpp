// Photons from the point light through the slime to the floor (photon_tracer.h).
#include "render/caustics/photon_tracer.h"

#include "render/caustics/wavefront.h"
#include "render/trace/optics.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

// A branch is followed while its weight (largest channel) is at least this: an eighth of the
// Whitted tracer's threshold, so that what is cut off stays well below the power oracle's 2 %.
constexpr float kMinPhotonWeight = kMinRayWeight / 8.0f;
// Crossings of the surface one photon may make, all its branches together.
constexpr int kMaxCrossings = 16;

// One photon's branch: a ray, its weight, whether it runs inside the jelly.
struct Branch {
  Ray ray;
  glm::vec3 weight{1.0f};
  bool inside = false;
};

// A number in [0, 1) from the photon's index and its crossing (PCG's output hash, O'Neill 2014): the
// same photon takes the same path every frame.
float uniformHash(std::uint64_t index, int crossing) {
  std::uint64_t x = index * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(crossing) * 0xBF58476D1CE4E5B9ull;
  x ^= x >> 31;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 29;
  return static_cast<float>(x >> 40) * (1.0f / 16777216.0f);
}

}  // namespace

PhotonTally& PhotonTally::operator+=(const PhotonTally& o) {
  emitted += o.emitted;
  intercepted += o.intercepted;
  reflected += o.reflected;
  landed += o.landed;
  escaped += o.escaped;
  dropped += o.dropped;
  return *this;
}

glm::vec3 PhotonCone::direction(std::uint64_t index) const {
  // R2: the plastic number ρ (ρ³ = ρ + 1); (s, t) = frac(0.5 + i (1/ρ, 1/ρ²)).
  constexpr double kA = 0.7548776662466927, kB = 0.5698402909980532;
  const double i = static_cast<double>(index);
  // frac(x) = x − ⌊x⌋, exact for x ≥ 0 as fmod(x, 1) is, and several times cheaper than the libm call.
  const double x = 0.5 + i * kA, y = 0.5 + i * kB;
  const double s = x - std::floor(x), t = y - std::floor(y);
  const double cosTheta = 1.0 - s * (1.0 - static_cast<double>(cosHalfAngle));
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double phi = 6.283185307179586 * t;
  return glm::normalize(static_cast<float>(cosTheta) * axis + static_cast<float>(sinTheta * std::cos(phi)) * u +
                        static_cast<float>(sinTheta * std::sin(phi)) * v);
}

PhotonCone photonCone(const SlimeGeometry& geometry, const glm::vec3& light) {
  PhotonCone cone;
  cone.apex = light;
  if (geometry.boundRadius <= 0.0f && !geometry.analyticSphere) return cone;
  const glm::vec3 toCenter = geometry.boundCenter - light;
  const float distance = glm::length(toCenter);
  const float radius = geometry.boundRadius * 1.0001f + 1e-6f;  // mayHit's slack
  cone.axis = distance > 0.0f ? toCenter / distance : glm::vec3(0.0f, 0.0f, -1.0f);
  const glm::vec3 helper = std::abs(cone.axis.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  cone.u = glm::normalize(glm::cross(helper, cone.axis));
  cone.v = glm::cross(cone.axis, cone.u);
  if (distance <= radius) {
    cone.cosHalfAngle = -1.0f;  // the light inside the bounds: every direction
  } else {
    const double sine = static_cast<double>(radius) / distance;
    cone.cosHalfAngle = static_cast<float>(std::sqrt(1.0 - sine * sine));
  }
  cone.solidAngle = 6.283185307179586 * (1.0 - static_cast<double>(cone.cosHalfAngle));
  return cone;
}

glm::vec3 PhotonTracer::shadingFacing(const SlimeHit& hit, const glm::vec3& outward, const glm::vec3& direction,
                                        bool entering) const {
  // As the eye's rays (whitted_tracer.cpp): with smooth normals the hit triangle's vertex normals
  // interpolated by its barycentrics (the facet's own where that sum vanishes), facing the ray; an
  // interpolated normal behind a silhouette gives way to the geometric one.
  glm::vec3 smooth = outward;
  if (parameters_.smoothNormals && !geometry_.analyticSphere && hit.primitive < geometry_.triangles.size()) {
    const Triangle& triangle = geometry_.triangles[hit.primitive];
    const glm::vec3 n = (1.0f - hit.u - hit.v) * geometry_.normals[triangle.x] + hit.u * geometry_.normals[triangle.y] +
                        hit.v * geometry_.normals[triangle.z];
    const float length = glm::length(n);
    if (length > 1e-6f && std::isfinite(length)) smooth = n / length;
  }
  const glm::vec3 facing = entering ? smooth : -smooth;
  return glm::dot(facing, direction) >= 0.0f ? (entering ? outward : -outward) : facing;
}

float PhotonTracer::surfaceTransmission(float cosine, bool entering, float& reflectedShare) const {
  // The Whitted tracer's weights (whitted_tracer.h): fresnel: transmitted (1 − F)·k_t entering,
  // (1 − F) leaving, reflected F; seed: transmitted k_t, reflected nothing (its k_s is a highlight).
  // Total internal reflection: all of it reflected.
  const ShadingParameters& p = parameters_;
  const float fresnel = entering ? fresnelDielectric(cosine, 1.0f, p.ior) : fresnelDielectric(cosine, p.ior, 1.0f);
  if (fresnel >= 1.0f) {
    reflectedShare = 1.0f;
    return 0.0f;
  }
  if (p.optics != OpticsMode::Fresnel) {
    reflectedShare = 0.0f;
    return p.transmission;
  }
  reflectedShare = fresnel;
  return (1.0f - fresnel) * (entering ? p.transmission : 1.0f);
}

namespace {

// Where a photon's straight line from the light meets the floor (z = 0); `ray` heads downwards.
glm::vec3 straightLanding(const Ray& ray) {
  return ray.origin + (std::max(0.0f, ray.origin.z) / -ray.direction.z) * ray.direction;
}

}  // namespace

void PhotonTracer::trace(const PhotonCone& cone, std::uint64_t first, std::uint64_t count,
                         std::vector<PhotonLanding>& landings, PhotonTally& tally, std::vector<PhotonLanding>* straight) const {
  if (cone.empty()) return;
  for (std::uint64_t i = first; i < first + count; ++i) {
    const Ray ray{cone.apex, cone.direction(i), 0.0f, kInfinity};
    tally.emitted += 1.0;
    const double intercepted = tally.intercepted;
    tracePhoton(ray, i, landings, tally);
    if (straight && ray.direction.z < 0.0f) {
      const glm::vec3 point = straightLanding(ray);
      straight->push_back(PhotonLanding{point.x, point.y, glm::vec3(tally.intercepted == intercepted ? 1.0f : 0.0f)});
    }
  }
}

void PhotonTracer::tracePhoton(const Ray& fromLight, std::uint64_t index, std::vector<PhotonLanding>& landings,
                               PhotonTally& tally) const {
  const ShadingParameters& p = parameters_;
  if (!geometry_.mayHit(fromLight)) return;
  Branch stack[kMaxCrossings + 1];
  int size = 0;
  stack[size++] = Branch{fromLight, glm::vec3(1.0f), false};
  int crossings = 0;
  bool first = true;
  const auto land = [&](const Ray& ray, float t, const glm::vec3& weight) {
    glm::vec3 point = ray.origin + t * ray.direction;
    // n = 1: Snell bends nothing and nothing is reflected, the photon lands where its straight line
    // from the light does; taken from that line, not through the crossings' offsets and rounding
    // (so a slime of index 1 leaves the map's ratio exactly 1: caustic_map.h).
    if (p.ior == 1.0f && fromLight.direction.z < 0.0f)
      point = straightLanding(fromLight);
    landings.push_back(PhotonLanding{point.x, point.y, weight});
    tally.landed += glm::dvec3(weight);
  };
  while (size > 0) {
    Branch branch = stack[--size];
    Ray& ray = branch.ray;
    // The floor: t = −o_z / d_z (an origin below it, after an exit through the contact, meets it at once).
    const float tFloor = ray.direction.z < 0.0f ? std::max(0.0f, ray.origin.z) / -ray.direction.z : kInfinity;
    SlimeHit hit;
    // Out of a supporting triangle nothing of the slime is ahead (whitted_tracer.h): no query.
    if (branch.inside || first || geometry_.mayHit(ray)) hit = intersector_.intersect(ray);
    const bool contact = branch.inside && hit.valid() && ray.direction.z < 0.0f &&
                         ray.origin.z + hit.t * ray.direction.z <= kContactHeight;
    if (!hit.valid() || hit.t > tFloor || contact) {
      if (first) return;  // missed the slime: direct light, the shadow rays' business
      if (branch.inside && !hit.valid() && tFloor == kInfinity) {
        tally.dropped += glm::dvec3(branch.weight);  // lost inside (a leak in the mesh)
        continue;
      }
      const glm::vec3 weight = branch.inside ? branch.weight * beerLambert(p.slimeAbsorption, tFloor) : branch.weight;
      if (tFloor == kInfinity) tally.escaped += glm::dvec3(weight);
      else land(ray, tFloor, weight);
      continue;
    }
    if (first) tally.intercepted += 1.0;
    const glm::vec3 point = ray.origin + hit.t * ray.direction;
    const glm::vec3 outward = geometry_.geometricNormal(hit, point);
    const bool entering = glm::dot(ray.direction, outward) < 0.0f;
    glm::vec3 weight = branch.weight;
    if (!entering) weight *= beerLambert(p.slimeAbsorption, hit.t);
    const glm::vec3 facing = shadingFacing(hit, outward, ray.direction, entering);
    const float cosine = std::abs(glm::dot(ray.direction, facing));
    float reflectedShare = 0.0f;
    const float transmitted = surfaceTransmission(cosine, entering, reflectedShare);
    ++crossings;
    const bool wasFirst = first;
    first = false;
    const bool canBranch = crossings < kMaxCrossings && size + 2 <= kMaxCrossings;
    // Transmitted: Snell about the shading normal (shadingFacing).
    if (transmitted > 0.0f) {
      const glm::vec3 w = weight * transmitted;
      const std::optional<glm::vec3> along = refract(ray.direction, facing, entering ? 1.0f : p.ior, entering ? p.ior : 1.0f);
      if (along && largest(w) >= kMinPhotonWeight && canBranch) {
        const bool leavesForGood = !entering && geometry_.supports(hit.primitive);
        Ray next{offsetRayOrigin(point, outward, *along), *along, 0.0f, kInfinity};
        if (leavesForGood) {  // above a supporting triangle's plane: no slime ahead, the floor or away
          const float t = next.direction.z < 0.0f ? std::max(0.0f, next.origin.z) / -next.direction.z : kInfinity;
          if (t == kInfinity) tally.escaped += glm::dvec3(w);
          else land(next, t, w);
        } else {
          stack[size++] = Branch{next, w, entering};
        }
      } else if (along) {
        tally.dropped += glm::dvec3(w);
      }
    }
    // Reflected: at the first crossing the slime's own reflection (not the caustic's); inside, followed.
    const glm::vec3 r = weight * reflectedShare;
    if (wasFirst || entering) {
      tally.reflected += glm::dvec3(r);
      continue;
    }
    // A partial reflection (F of a few per cent) survives Russian roulette with probability F and
    // its weight divided by F: unbiased, and only one photon in 1/F pays for the extra queries.
    // Total internal reflection (F = 1) always goes on.
    glm::vec3 kept = r;
    if (reflectedShare < 1.0f) {
      const float survive = std::max(reflectedShare, 1e-6f);
      if (uniformHash(index, crossings) >= survive) continue;
      kept = r / survive;
    }
    if (largest(kept) >= kMinPhotonWeight && canBranch) {
      const glm::vec3 along = reflect(ray.direction, facing);
      stack[size++] = Branch{Ray{offsetRayOrigin(point, outward, along), along, 0.0f, kInfinity}, kept, true};
    } else {
      tally.dropped += glm::dvec3(kept);
    }
  }
}

namespace {

// A path's hash after one more crossing (its outcome: 1 transmitted, 2 reflected; the piece crossed).
std::uint64_t extendPath(std::uint64_t path, std::uint64_t outcome, std::uint64_t piece) {
  std::uint64_t x = (path ^ (outcome + 4 * piece)) * 0x9E3779B97F4A7C15ull;
  x ^= x >> 29;
  return x == kDirectPath ? 1 : x;
}

}  // namespace

void PhotonTracer::traceVertex(const Ray& fromLight, WavefrontVertex& vertex, PhotonTally& tally) const {
  const ShadingParameters& p = parameters_;
  tally.emitted += 1.0;
  vertex.count = 0;
  vertex.straight = fromLight.direction.z < 0.0f;
  if (vertex.straight) {
    const glm::vec3 point = straightLanding(fromLight);
    vertex.sx = point.x, vertex.sy = point.y;
  }
  const auto direct = [&] {
    if (vertex.straight) vertex.branches[vertex.count++] = WavefrontBranch{kDirectPath, vertex.sx, vertex.sy, glm::vec3(1.0f)};
  };
  if (!geometry_.mayHit(fromLight)) return direct();
  struct PathBranch {
    Branch branch;
    std::uint64_t path;
  };
  PathBranch stack[kMaxCrossings + 1];
  int size = 0;
  stack[size++] = PathBranch{Branch{fromLight, glm::vec3(1.0f), false}, 0x243F6A8885A308D3ull};
  int crossings = 0;
  bool first = true;
  const auto land = [&](const Ray& ray, float t, const glm::vec3& weight, std::uint64_t path) {
    glm::vec3 point = ray.origin + t * ray.direction;
    if (p.ior == 1.0f && vertex.straight) point = glm::vec3(vertex.sx, vertex.sy, 0.0f);  // as tracePhoton
    tally.landed += glm::dvec3(weight);
    if (vertex.count < kMaxWavefrontBranches) vertex.branches[vertex.count++] = WavefrontBranch{path, point.x, point.y, weight};
    else tally.dropped += glm::dvec3(weight);
  };
  const auto pieceOf = [&](std::uint32_t primitive) -> std::uint64_t {
    const auto& starts = geometry_.pieceTriangleStarts;
    if (geometry_.analyticSphere || starts.size() < 2) return 0;
    return static_cast<std::uint64_t>(std::upper_bound(starts.begin(), starts.end(), primitive) - starts.begin());
  };
  while (size > 0) {
    const PathBranch top = stack[--size];
    const Branch& branch = top.branch;
    const Ray& ray = branch.ray;
    const float tFloor = ray.direction.z < 0.0f ? std::max(0.0f, ray.origin.z) / -ray.direction.z : kInfinity;
    SlimeHit hit;
    if (branch.inside || first || geometry_.mayHit(ray)) hit = intersector_.intersect(ray);
    const bool contact = branch.inside && hit.valid() && ray.direction.z < 0.0f &&
                         ray.origin.z + hit.t * ray.direction.z <= kContactHeight;
    if (!hit.valid() || hit.t > tFloor || contact) {
      if (first) return direct();
      if (branch.inside && !hit.valid() && tFloor == kInfinity) {
        tally.dropped += glm::dvec3(branch.weight);
        continue;
      }
      const glm::vec3 weight = branch.inside ? branch.weight * beerLambert(p.slimeAbsorption, tFloor) : branch.weight;
      if (tFloor == kInfinity) tally.escaped += glm::dvec3(weight);
      else land(ray, tFloor, weight, top.path);
      continue;
    }
    if (first) tally.intercepted += 1.0;
    const glm::vec3 point = ray.origin + hit.t * ray.direction;
    const glm::vec3 outward = geometry_.geometricNormal(hit, point);
    const bool entering = glm::dot(ray.direction, outward) < 0.0f;
    const glm::vec3 facing = shadingFacing(hit, outward, ray.direction, entering);
    glm::vec3 weight = branch.weight;
    if (!entering) weight *= beerLambert(p.slimeAbsorption, hit.t);
    const float cosine = std::abs(glm::dot(ray.direction, facing));
    float reflectedShare = 0.0f;
    const float transmitted = surfaceTransmission(cosine, entering, reflectedShare);
    ++crossings;
    const bool wasFirst = first;
    first = false;
    const bool canBranch = crossings < kMaxCrossings && size + 2 <= kMaxCrossings;
    const std::uint64_t piece = pieceOf(hit.primitive);
    if (transmitted > 0.0f) {
      const glm::vec3 w = weight * transmitted;
      const std::optional<glm::vec3> along = refract(ray.direction, facing, entering ? 1.0f : p.ior, entering ? p.ior : 1.0f);
      const std::uint64_t path = extendPath(top.path, 1, piece);
      if (along && largest(w) >= minVertexWeight_ && canBranch) {
        const bool leavesForGood = !entering && geometry_.supports(hit.primitive);
        Ray next{offsetRayOrigin(point, outward, *along), *along, 0.0f, kInfinity};
        if (leavesForGood) {
          const float t = next.direction.z < 0.0f ? std::max(0.0f, next.origin.z) / -next.direction.z : kInfinity;
          if (t == kInfinity) tally.escaped += glm::dvec3(w);
          else land(next, t, w, path);
        } else {
          stack[size++] = PathBranch{Branch{next, w, entering}, path};
        }
      } else if (along) {
        tally.dropped += glm::dvec3(w);
      }
    }
    const glm::vec3 r = weight * reflectedShare;
    if (wasFirst || entering) {
      tally.reflected += glm::dvec3(r);
      continue;
    }
    if (largest(r) >= minVertexWeight_ && canBranch) {
      const glm::vec3 along = reflect(ray.direction, facing);
      stack[size++] = PathBranch{Branch{Ray{offsetRayOrigin(point, outward, along), along, 0.0f, kInfinity}, r, true},
                                 extendPath(top.path, 2, piece)};
    } else {
      tally.dropped += glm::dvec3(r);
    }
  }
}

}  // namespace slime

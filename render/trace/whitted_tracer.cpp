#include "render/trace/whitted_tracer.h"

#include "render/simd/lanes.h"
#include "render/trace/optics.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace slime {
namespace {

// How far beyond the slime's bounding sphere a reversed query starts (findHits), metres; beyond
// kMaxReverseDistance (a diverged mesh) the query runs forward as usual.
constexpr float kReverseMargin = 1e-4f;
constexpr float kMaxReverseDistance = 1e3f;


// The plane z = 0 seen from above: t = −o_z / d_z (a ray starting below it hits it at once).
float floorDistance(const Ray& ray) {
  if (ray.direction.z >= 0.0f) return kInfinity;
  const float t = std::max(0.0f, ray.origin.z) / -ray.direction.z;
  return t <= ray.tFar ? t : kInfinity;
}

// A ray inside the jelly that reaches its surface within kContactHeight of the floor meets the floor
// there (the contact patch, optics.h): shaded as the floor seen through the jelly, never as an exit.
bool meetsFloorInContact(const Ray& ray, bool inside, float t) {
  return inside && ray.direction.z < 0.0f && ray.origin.z + t * ray.direction.z <= kContactHeight;
}

}  // namespace

struct WhittedTracer::Wavefront {
  std::vector<PendingRay> current, next;  // this generation's rays and their children
  std::vector<FloorShading> floors;       // per ray of `current`: its floor's shading, when it sees the floor
  std::vector<PendingShadow> shadows;     // the packet's shadow rays, traced last
};

namespace {

// One wavefront per tracing thread, kept from packet to packet and frame to frame: once its lists
// have grown to the largest tree seen, tracing allocates nothing.
WhittedTracer::Wavefront& threadWavefront() {
  thread_local WhittedTracer::Wavefront wavefront;
  return wavefront;
}

}  // namespace

glm::vec3 WhittedTracer::tracePrimary(const Ray& ray, const SlimeHit& hit, TraceCounters& counters,
                                      FloorShading* floorCache) const {
  glm::vec3 color;
  tracePrimaries(&ray, &hit, 1, counters, floorCache, &color);
  return color;
}

void WhittedTracer::tracePrimaries(const Ray* rays, const SlimeHit* hits, int count, TraceCounters& counters,
                                   FloorShading* floorCache, glm::vec3* colors, bool outOfReach) const {
  Wavefront& wavefront = threadWavefront();
  wavefront.current.clear();
  wavefront.next.clear();
  wavefront.shadows.clear();
  // Most pixels see only the floor or the sky: shaded at once, only their shadow rays may wait. The
  // floor's pattern is looked up for the wavefront's floor pixels together (floorShadings).
  FloorShading packetShadings[kMaxPrimaries];
  FloorShading* shadings = floorCache ? floorCache : packetShadings;
  float tFloors[kMaxPrimaries];
  bool needed[kMaxPrimaries] = {};
  for (int i = 0; i < kMaxPrimaries; ++i) {
    tFloors[i] = kInfinity;
    if (i >= count) continue;
    tFloors[i] = hits[i].valid() ? kInfinity : floorDistance(rays[i]);
    if (tFloors[i] == kInfinity) continue;
    if (floorCache && floorCache[i].filled) ++counters.cachedFloorPixels;
    else needed[i] = true;
  }
  for (int first = 0; first < count; first += kFloorBatch)
    floorShadings(rays + first, tFloors + first, tFloors + first, needed + first, shadings + first);
  if (outOfReach && !(parameters_.floorSpecular > 0.0f)) {
    // Floor or sky only, and no slime's shadow: no query, no wavefront, and the very sums of the
    // general path below (shadeFloorWith, its shadow ray counted but not traced), so a pixel shaded
    // here equals one shaded there bit for bit (the footprint's invariant test demands it).
    for (int i = 0; i < count; ++i) {
      ++counters.rays.primary;
      colors[i] = glm::vec3(0.0f);
      if (tFloors[i] == kInfinity) colors[i] = sky(rays[i].direction);
      else shadeFloorWith(rays[i], tFloors[i], shadings[i], Path{}, glm::vec3(1.0f), i, wavefront, counters, colors, true);
    }
    return;
  }
  for (int i = 0; i < count; ++i) {
    ++counters.rays.primary;
    colors[i] = glm::vec3(0.0f);
    if (!hits[i].valid()) {
      if (tFloors[i] == kInfinity) colors[i] = sky(rays[i].direction);
      else shadeFloorWith(rays[i], tFloors[i], shadings[i], Path{}, glm::vec3(1.0f), i, wavefront, counters, colors);
      continue;
    }
    PendingRay& primary = wavefront.current.emplace_back();  // written in place (see shadeSlimes8)
    primary.ray = rays[i];
    primary.hit = hits[i];
    primary.hitKnown = true;
    primary.pixel = i;
  }
  wavefront.current.insert(wavefront.current.end(), wavefront.next.begin(), wavefront.next.end());
  // Generation by generation: the queries of all the packet's rays of one depth, then their shading,
  // which adds what is known now to the pixels and queues the next generation and the shadow rays.
  while (!wavefront.current.empty()) {
    findHits(wavefront.current, counters);
    lookUpFloors(wavefront.current, wavefront.floors);
    wavefront.next.clear();
    // The rays that hit the slime are shaded 8 at a time, the others one by one.
    const PendingRay* slimeHits[8];
    int hitCount = 0;
    for (std::size_t r = 0; r < wavefront.current.size(); ++r) {
      const PendingRay& ray = wavefront.current[r];
      if (ray.kind != Kind::Environment && ray.hit.valid() && ray.hit.t <= floorDistance(ray.ray) &&
          !meetsFloorInContact(ray.ray, ray.path.inside, ray.hit.t)) {
        slimeHits[hitCount++] = &ray;
        if (hitCount == 8) {
          shadeSlimes8(slimeHits, hitCount, wavefront, counters, colors);
          hitCount = 0;
        }
        continue;
      }
      shade(ray, wavefront.floors[r], wavefront, counters, floorCache, colors);
    }
    if (hitCount > 0) shadeSlimes8(slimeHits, hitCount, wavefront, counters, colors);
    std::swap(wavefront.current, wavefront.next);
  }
  traceShadows(wavefront.shadows, counters, colors);
}

void WhittedTracer::findHits(std::vector<PendingRay>& rays, TraceCounters& counters) const {
  // The intersector's packet: rays from outside, and chords from inside the walk left (asked back
  // from beyond the bounding sphere), each with its check of the non-supporting triangles.
  Ray packet[8], checks[8];
  bool active[8] = {};
  bool checked[8] = {};  // the ray also asks for its first non-supporting crossing on its way out
  std::size_t members[8] = {};
  float reversedFrom[8] = {};  // > 0: the query runs back from this far along the ray (a chord from inside)
  int size = 0, checkCount = 0;
  const auto flush = [&] {
    SlimeHit found[8], crossings[8];
    intersector_.intersect8(packet, active, found);
    if (checkCount > 0) {
      // A crossing with the non-supporting triangles counts only before the last crossing, just found.
      for (int k = 0; k < size; ++k)
        if (checked[k] && found[k].valid()) checks[k].tFar = std::min(checks[k].tFar, reversedFrom[k] - found[k].t + kRayOffset);
      intersector_.intersectNonSupporting8(checks, checked, crossings);
    }
    counters.slimeQueries += static_cast<std::uint64_t>(size + checkCount);
    for (int k = 0; k < size; ++k) {
      const Ray& ray = rays[members[k]].ray;
      SlimeHit& hit = rays[members[k]].hit;
      hit = found[k];
      if (checked[k] && crossings[k].valid()) {
        hit = crossings[k];  // it leaves through a non-supporting triangle (see below)
      } else if (reversedFrom[k] > 0.0f) {
        if (hit.valid()) hit.t = reversedFrom[k] - hit.t;
        else hit = intersector_.intersect(ray);  // grazing: ask the usual way
      }
      reversedFrom[k] = 0.0f;
      checked[k] = false;
    }
    for (bool& a : active) a = false;
    size = checkCount = 0;
  };
  const bool convex = geometry_.isConvex(), backwards = geometry_.fewNonSupporting();
  const auto ask = [&](std::size_t r, float beyond) {  // into the intersector's packet
    const Ray& ray = rays[r].ray;
    packet[size] = ray;
    if (beyond > 0.0f) {
      packet[size] = Ray{ray.origin + beyond * ray.direction, -ray.direction, 0.0f, beyond - kRayOffset};
      reversedFrom[size] = beyond;
      checks[size] = Ray{ray.origin, ray.direction, ray.tNear, std::min(ray.tFar, beyond)};
      if (!convex && geometry_.mayCrossNonSupporting(checks[size])) {
        checked[size] = true;
        ++checkCount;
      }
    }
    active[size] = true;
    members[size] = r;
    if (++size == 8) flush();
  };
  // The walkers' batch: chords from inside, kExitRays at a time; and the checks of those it settled.
  constexpr int kWalkers = SlimeIntersector::kExitRays;
  Ray walkers[kWalkers], walkedChecks[8];
  glm::vec3 exitPoints[kWalkers];
  float walkerBeyond[kWalkers] = {};
  bool walking[kWalkers] = {}, walkedChecked[8] = {};
  std::size_t walkerMembers[kWalkers] = {}, walkedMembers[8] = {};
  int walkerCount = 0, walkedCount = 0;
  const auto flushChecks = [&] {
    SlimeHit crossings[8];
    intersector_.intersectNonSupporting8(walkedChecks, walkedChecked, crossings);
    counters.slimeQueries += static_cast<std::uint64_t>(walkedCount);
    for (int k = 0; k < walkedCount; ++k) {
      if (crossings[k].valid()) rays[walkedMembers[k]].hit = crossings[k];
      walkedChecked[k] = false;
    }
    walkedCount = 0;
  };
  const auto walk = [&] {  // the batch's chords: found by the walk, or into the intersector's packet
    SlimeHit exits[kWalkers];
    if (!intersector_.supportingExits(walkers, exitPoints, walking, exits))
      for (SlimeHit& exit : exits) exit = SlimeHit{};
    for (int k = 0; k < walkerCount; ++k) {
      const std::size_t r = walkerMembers[k];
      if (!exits[k].valid()) {
        ask(r, walkerBeyond[k]);
      } else {
        ++counters.slimeQueries;  // a query answered by the walk, as a grid's answer counts one
        rays[r].hit = exits[k];
        const Ray& ray = rays[r].ray;
        const Ray check{ray.origin, ray.direction, ray.tNear, exits[k].t + kRayOffset};
        if (!convex && geometry_.mayCrossNonSupporting(check)) {
          walkedChecks[walkedCount] = check;
          walkedChecked[walkedCount] = true;
          walkedMembers[walkedCount] = r;
          if (++walkedCount == 8) flushChecks();
        }
      }
      walking[k] = false;
    }
    walkerCount = 0;
  };
  for (std::size_t r = 0; r < rays.size(); ++r) {
    PendingRay& ray = rays[r];
    if (ray.hitKnown) continue;
    ray.hitKnown = true;
    ray.hit = SlimeHit{};
    // A ray leaving through a supporting triangle cannot meet the slime again; others only if they
    // reach its bounds.
    if (ray.path.leavesSlime || !geometry_.mayHit(ray.ray)) continue;
    const float beyond = ray.path.inside && backwards ? geometry_.boundExitDistance(ray.ray) + kReverseMargin : 0.0f;
    if (!(beyond > 0.0f && beyond < kMaxReverseDistance)) {
      ask(r, 0.0f);
      continue;
    }
    // A ray inside the slime that leaves it through a supporting triangle is then above that
    // triangle's plane, with all the slime below: it never comes back, and where it leaves is its
    // only crossing with a supporting triangle. The walk over the surface (render/slime/exit_walk.h)
    // finds it most of the time without a query; else it is the ray's last crossing, the first one
    // met by the ray coming back from beyond the bounding sphere, a query from outside the jelly
    // (about twice as fast in Embree as one from inside, across it).
    // A ray that leaves through a non-supporting triangle may come back, but it has crossed nothing
    // before (had it left through a supporting one first, it could not have come back): its first
    // crossing with the non-supporting triangles, asked beside, from a far smaller set, is where it
    // leaves. Convex: there are none, and no second query.
    walkers[walkerCount] = Ray{ray.ray.origin, ray.ray.direction, std::max(ray.ray.tNear, kRayOffset), std::min(ray.ray.tFar, beyond)};
    exitPoints[walkerCount] = ray.ray.origin + beyond * ray.ray.direction;
    walkerBeyond[walkerCount] = beyond;
    walking[walkerCount] = true;
    walkerMembers[walkerCount] = r;
    if (++walkerCount == kWalkers) walk();
  }
  if (walkerCount > 0) walk();
  if (size > 0) flush();
  if (walkedCount > 0) flushChecks();
}

void WhittedTracer::lookUpFloors(const std::vector<PendingRay>& rays, std::vector<FloorShading>& floors) const {
  floors.assign(rays.size(), FloorShading{});
  Ray packet[kFloorBatch];
  float t[kFloorBatch], distances[kFloorBatch];
  bool needed[kFloorBatch] = {};
  std::size_t members[kFloorBatch] = {};
  int size = 0;
  const auto flush = [&] {
    FloorShading found[kFloorBatch];
    floorShadings(packet, t, distances, needed, found);
    for (int k = 0; k < size; ++k) floors[members[k]] = found[k];
    for (bool& n : needed) n = false;
    size = 0;
  };
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const PendingRay& ray = rays[r];
    if (ray.kind == Kind::Primary) continue;  // a primary's floor goes through the renderer's cache
    const float tFloor = floorDistance(ray.ray);
    if (tFloor == kInfinity ||
        (ray.hit.valid() && ray.hit.t <= tFloor && !meetsFloorInContact(ray.ray, ray.path.inside, ray.hit.t)))
      continue;
    packet[size] = ray.ray;
    t[size] = tFloor;
    distances[size] = ray.path.travelled + tFloor;
    needed[size] = true;
    members[size] = r;
    if (++size == kFloorBatch) flush();
  }
  if (size > 0) flush();
}

void WhittedTracer::shade(const PendingRay& ray, const FloorShading& floor, Wavefront& wavefront, TraceCounters& counters,
                          FloorShading* floorCache, glm::vec3* colors) const {
  const float tFloor = floorDistance(ray.ray);
  if (ray.kind == Kind::Environment) {  // the floor (unshadowed, looked up with the generation's) or the sky
    glm::vec3 ambient = floor.ambient;
    if (tFloor != kInfinity && !skyOcclusion_.empty())
      ambient *= skyOcclusion_.visibility(ray.ray.origin + tFloor * ray.ray.direction);
    const glm::vec3 seen = tFloor == kInfinity ? sky(ray.ray.direction)
                                               : glm::mix(ambient + floor.lit, parameters_.skyHorizon, floor.haze);
    colors[ray.pixel] += ray.factor * seen;
  } else if (tFloor == kInfinity) {
    colors[ray.pixel] += ray.factor * sky(ray.ray.direction);
  } else if (floor.filled) {
    shadeFloorWith(ray.ray, tFloor, floor, ray.path, ray.factor, ray.pixel, wavefront, counters, colors);
  } else {
    shadeFloor(ray.ray, tFloor, ray.path, ray.factor, ray.pixel, wavefront, counters,
               ray.kind == Kind::Primary && floorCache ? floorCache + ray.pixel : nullptr, colors);
  }
}

void WhittedTracer::shadeSlimes8(const PendingRay* const* pending, int count, Wavefront& wavefront, TraceCounters& counters,
                                 glm::vec3* colors) const {
  // shade() of up to 8 rays that hit the slime, as lanes (render/simd/lanes.h): the formulas run for all
  // of them at once, only the queueing of children stays ray by ray.
  //   I = local Phong (entering) + w_r I_reflected + w_t I_refracted, times Beer–Lambert from inside.
  const ShadingParameters& p = parameters_;
  constexpr int N = 8;
  float origin[3][N], direction[3][N], distance[N];
  for (int i = 0; i < N; ++i) {
    const PendingRay& ray = *pending[std::min(i, count - 1)];  // unused lanes repeat the last ray
    for (int c = 0; c < 3; ++c) {
      origin[c][i] = ray.ray.origin[c];
      direction[c][i] = ray.ray.direction[c];
    }
    distance[i] = ray.hit.t;
  }
  const Lanes t = Lanes::load(distance);
  const Lanes3 d{Lanes::load(direction[0]), Lanes::load(direction[1]), Lanes::load(direction[2])};
  const StoredLanes3 points(Lanes3{Lanes::load(origin[0]), Lanes::load(origin[1]), Lanes::load(origin[2])} + t * d);
  // The outward geometric normals, and the unit shading normals: with smooth normals the hit
  // triangle's vertex normals interpolated by its barycentrics and normalised (the facet's own where
  // that sum is zero or not finite), else the geometric ones.
  const bool interpolated = p.smoothNormals && !geometry_.analyticSphere;
  float normals[3][N], corners[3][3][N], us[N], vs[N];  // corners[vertex][axis][lane]
  for (int i = 0; i < N; ++i) {
    const PendingRay& ray = *pending[std::min(i, count - 1)];
    const glm::vec3 outward = geometry_.geometricNormal(ray.hit, points[i]);
    for (int c = 0; c < 3; ++c) normals[c][i] = outward[c];
    if (!interpolated) continue;
    const Triangle& triangle = geometry_.triangles[ray.hit.primitive];
    const std::uint32_t vertices[3] = {triangle.x, triangle.y, triangle.z};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) corners[k][c][i] = geometry_.normals[vertices[k]][c];
    us[i] = ray.hit.u;
    vs[i] = ray.hit.v;
  }
  const Lanes3 outward{Lanes::load(normals[0]), Lanes::load(normals[1]), Lanes::load(normals[2])};
  Lanes3 smooth = outward;
  if (interpolated) {
    const auto corner = [&](int k) { return Lanes3{Lanes::load(corners[k][0]), Lanes::load(corners[k][1]), Lanes::load(corners[k][2])}; };
    const Lanes u = Lanes::load(us), v = Lanes::load(vs);
    const Lanes3 n = (Lanes(1.0f) - u - v) * corner(0) + u * corner(1) + v * corner(2);
    const Lanes length = sqrt(dot(n, n));
    const LaneMask usable = (length > Lanes(1e-6f)) && (length < Lanes(INFINITY));  // else the facet's own
    smooth = select(usable, Lanes3{n.x / length, n.y / length, n.z / length}, outward);
  }

  // Normals facing the incoming ray: geometric (for offsets) and shading (for optics); an
  // interpolated normal behind a silhouette gives way to the geometric one.
  const LaneMask entering = dot(d, outward) < 0.0f;
  const Lanes3 facing = select(entering, outward, -outward);
  const Lanes3 turned = select(entering, smooth, -smooth);
  const Lanes3 normal = select(dot(turned, d) >= 0.0f, facing, turned);
  const Lanes cosIncident = -dot(d, normal);
  const Lanes etaFrom = select(entering, 1.0f, p.ior), etaTo = select(entering, p.ior, 1.0f);

  // A ray that reaches the surface from inside has crossed the jelly: Beer–Lambert over its length.
  float absorbed[3][N];
  for (int c = 0; c < 3; ++c) {
    exp(select(entering, 0.0f, -p.slimeAbsorption[c] * t)).store(absorbed[c]);
  }

  // Local Phong where the ray enters: I = k_a I_a C + T_light I_l (k_d (N·L) C + k_s (R·V)^n), with
  // Phong's lobe R = reflect(−L, N), V = −d.
  const Lanes3 point{Lanes::load(points.x), Lanes::load(points.y), Lanes::load(points.z)};
  const Lanes3 toLightUnnormalized =
      Lanes3{Lanes(p.lightPosition.x), Lanes(p.lightPosition.y), Lanes(p.lightPosition.z)} - point;
  const Lanes3 toLight = (1.0f / sqrt(dot(toLightUnnormalized, toLightUnnormalized))) * toLightUnnormalized;
  const Lanes cosLight = dot(normal, toLight);
  const LaneMask lit = entering && cosLight > 0.0f && dot(facing, toLight) > 0.0f;
  const Lanes3 mirrored = -toLight - (-2.0f * cosLight) * normal;
  const Lanes lobeCosine = -dot(mirrored, d);

  // Snell's law (refract()): no transmitted ray under total internal reflection.
  const Lanes eta = etaFrom / etaTo;
  const Lanes sin2Transmitted = eta * eta * max(1.0f - cosIncident * cosIncident, 0.0f);
  const LaneMask refractsLanes = !(sin2Transmitted > 1.0f);
  const Lanes cosTransmittedRay = sqrt(max(1.0f - sin2Transmitted, 0.0f));
  const Lanes3 transmittedLanes = eta * d + (eta * cosIncident - cosTransmittedRay) * normal;
  // A transmitted ray on the incoming side (a smooth normal far from the facet's): refract about the
  // facet instead, below, ray by ray (rare).
  const LaneMask reversed = refractsLanes && dot(transmittedLanes, facing) >= 0.0f;

  // fresnelDielectric(cos θi, η_from, η_to): 1 under total internal reflection.
  const Lanes cosine = min(max(cosIncident, 0.0f), 1.0f);
  const Lanes sinTransmitted = eta * sqrt(max(1.0f - cosine * cosine, 0.0f));
  const Lanes cosTransmitted = sqrt(max(1.0f - sinTransmitted * sinTransmitted, 0.0f));
  const Lanes rs = (etaFrom * cosine - etaTo * cosTransmitted) / (etaFrom * cosine + etaTo * cosTransmitted);
  const Lanes rp = (etaTo * cosine - etaFrom * cosTransmitted) / (etaTo * cosine + etaFrom * cosTransmitted);
  const Lanes fresnelLanes = select(sinTransmitted < 1.0f, 0.5f * (rs * rs + rp * rp), 1.0f);

  const StoredLanes3 facings(facing), shadingNormals(normal), lightDirections(toLight), transmissions(transmittedLanes);
  float cosLights[N], lobeCosines[N], fresnels[N];
  cosLight.store(cosLights);
  lobeCosine.store(lobeCosines);
  fresnelLanes.store(fresnels);

  // Ray by ray: the light, the children.
  for (int i = 0; i < count; ++i) {
    const PendingRay& ray = *pending[i];
    const Path& path = ray.path;
    glm::vec3& pixel = colors[ray.pixel];
    const glm::vec3 point = points[i], facing = facings[i], normal = shadingNormals[i];
    const glm::vec3 direction = ray.ray.direction;
    const bool enters = entering[i];
    bool refracted = refractsLanes[i];
    glm::vec3 transmitted = transmissions[i];
    if (reversed[i]) {
      const std::optional<glm::vec3> again = refract(direction, facing, enters ? 1.0f : p.ior, enters ? p.ior : 1.0f);
      refracted = again.has_value();
      if (again) transmitted = *again;
    }
    const float fresnel = refracted ? fresnels[i] : 1.0f;
    const glm::vec3 inside = enters ? glm::vec3(1.0f) : glm::vec3(absorbed[0][i], absorbed[1][i], absorbed[2][i]);
    if (enters && p.shading == ShadingModel::Classic) {  // the jelly's own light: the seed's Phong terms
      pixel += ray.factor * (p.ambient * p.ambientLight * p.slimeColor);
      if (lit[i]) {
        // (R·V)^n; cos^n < 2^-12 (invisible) once n (1 − cos) ≳ 8.3: no pow there.
        const float cosine = lobeCosines[i];
        const float lobe = cosine <= 0.0f || p.shininess * (1.0f - cosine) > 8.5f ? 0.0f : std::pow(cosine, p.shininess);
        const glm::vec3 toLight = lightDirections[i];
        const glm::vec3 light = ray.factor * p.lightColor * (p.diffuse * cosLights[i] * p.slimeColor + p.specular * lobe);
        // Towards the light out of a supporting triangle, nothing of the slime is in the way.
        if (p.shadows) addLight(offsetRayOrigin(point, facing, toLight), light, ray.pixel, geometry_.supports(ray.hit.primitive), false, wavefront, counters, colors);
        else pixel += light;
      }
    }

    float reflectWeight = 0.0f, refractWeight = 0.0f;
    if (p.optics == OpticsMode::Fresnel) {
      reflectWeight = fresnel;
      refractWeight = (1.0f - fresnel) * (enters ? p.transmission : 1.0f);
    } else {
      reflectWeight = p.specular;
      refractWeight = refracted ? p.transmission : 0.0f;
      if (!refracted) reflectWeight += p.transmission;
    }
    const glm::vec3 weight = path.weight * inside;
    // A child written in place in the next generation: one built aside and copied in stalls on
    // reading back its just-written fields (store forwarding), a measurable cost at this rate.
    const auto spawn = [&](Kind kind, const glm::vec3& along, const glm::vec3& childWeight, bool childInside, bool leaves,
                           const glm::vec3& factor) {
      PendingRay& child = wavefront.next.emplace_back();
      child.ray = Ray{offsetRayOrigin(point, facing, along), along, 0.0f, kInfinity};
      child.path = Path{path.segment + 1, childWeight, path.travelled + ray.hit.t, childInside, leaves};
      child.factor = factor;
      child.pixel = ray.pixel;
      child.kind = kind;
      child.hitKnown = kind == Kind::Environment;
    };
    if (path.segment < p.depth) {
      if (reflectWeight > 0.0f && visibleThroughput(weight * reflectWeight, p.brightest, pixel)) {
        glm::vec3 reflected = reflect(direction, normal);
        if (glm::dot(reflected, facing) <= 0.0f) reflected = reflect(direction, facing);
        ++counters.rays.reflection;
        spawn(Kind::Reflection, reflected, weight * reflectWeight, !enters, enters && geometry_.supports(ray.hit.primitive),
              ray.factor * inside * reflectWeight);
      }
      if (refracted && refractWeight > 0.0f && visibleThroughput(weight * refractWeight, p.brightest, pixel)) {
        ++counters.rays.refraction;
        spawn(Kind::Refraction, transmitted, weight * refractWeight, enters, !enters && geometry_.supports(ray.hit.primitive),
              ray.factor * inside * refractWeight);
      }
    } else if (!enters && refracted && refractWeight > 0.0f) {
      // Out of segments on the way out of the jelly: what lies beyond is the analytic floor or sky,
      // looked up with the next generation's floors (no query, no shadow, no mirror).
      ++counters.rays.refraction;
      spawn(Kind::Environment, transmitted, glm::vec3(1.0f), false, false, ray.factor * inside * refractWeight);
    } else if (!enters && !refracted && reflectWeight > 0.0f) {
      // Out of segments under total internal reflection: the light it keeps leaves the jelly somewhere
      // after more reflections; it is taken as the floor or sky along the reflected ray, not as black.
      glm::vec3 reflected = reflect(direction, normal);
      if (glm::dot(reflected, facing) <= 0.0f) reflected = reflect(direction, facing);
      ++counters.rays.reflection;
      spawn(Kind::Environment, reflected, glm::vec3(1.0f), false, false, ray.factor * inside * reflectWeight);
    }
  }
}

void WhittedTracer::shadeFloor(const Ray& ray, float t, const Path& path, const glm::vec3& rayFactor, int pixel,
                               Wavefront& wavefront, TraceCounters& counters, FloorShading* floorCache,
                               glm::vec3* colors) const {
  glm::vec3 point = ray.origin + t * ray.direction;
  point.z = 0.0f;
  FloorShading fresh;
  if (!floorCache || !floorCache->filled) {
    fresh = floorShading(point, ray.direction, path.travelled + t);
    if (floorCache) *floorCache = fresh;
  } else {
    ++counters.cachedFloorPixels;
  }
  shadeFloorWith(ray, t, floorCache ? *floorCache : fresh, path, rayFactor, pixel, wavefront, counters, colors);
}

void WhittedTracer::shadeFloorWith(const Ray& ray, float t, const FloorShading& shading, const Path& path,
                                   const glm::vec3& rayFactor, int pixel, Wavefront& wavefront, TraceCounters& counters,
                                   glm::vec3* colors, bool unshadowed) const {
  const ShadingParameters& p = parameters_;
  glm::vec3 point = ray.origin + t * ray.direction;
  point.z = 0.0f;
  const float distance = path.travelled + t;
  // colour = mix(ambient + T_light lit + k_s I_mirror, horizon, haze), seen under the jelly (the
  // contact patch) through Beer–Lambert absorption; each term goes to the pixel with its factor.
  const glm::vec3 factor = path.inside ? rayFactor * beerLambert(p.slimeAbsorption, t) : rayFactor;
  const glm::vec3 nearFactor = factor * (1.0f - shading.haze);  // what the haze leaves of the floor
  // The ambient, less the sky the slime hides from this point (not kept in the floor's cache, which
  // outlives the slime's moves).
  const glm::vec3 ambient = skyOcclusion_.empty() ? shading.ambient : shading.ambient * skyOcclusion_.visibility(point);
  colors[pixel] += nearFactor * ambient + factor * (shading.haze * p.skyHorizon);
  if (shading.lit != glm::vec3(0.0f)) {  // else the light is below the floor, or black
    if (p.shadows) {
      addLight(point + glm::vec3(0.0f, 0.0f, kRayOffset), nearFactor * shading.lit, pixel, unshadowed, true, wavefront, counters,
               colors);
    } else {
      colors[pixel] += nearFactor * shading.lit;
    }
  }
  if (path.segment < p.depth && p.floorSpecular > 0.0f &&
      visibleThroughput(path.weight * p.floorSpecular, p.brightest, colors[pixel])) {
    // The varnish mirrors what is above: the reflected ray (d_x, d_y, −d_z).
    ++counters.rays.reflection;
    PendingRay& child = wavefront.next.emplace_back();  // written in place (see shadeSlimes8)
    child.pixel = pixel;
    child.kind = Kind::Reflection;
    child.path = Path{path.segment + 1, path.weight * p.floorSpecular, distance, path.inside, false};
    child.factor = nearFactor * p.floorSpecular;
    child.ray = Ray{point + glm::vec3(0.0f, 0.0f, kRayOffset), {ray.direction.x, ray.direction.y, -ray.direction.z}, 0.0f,
                    kInfinity};
  }
}

void WhittedTracer::addLight(const glm::vec3& origin, const glm::vec3& multiplier, int pixel, bool unshadowed, bool fromFloor,
                             Wavefront& wavefront, TraceCounters& counters, glm::vec3* colors) const {
  ++counters.rays.shadow;
  if (unshadowed) {
    colors[pixel] += multiplier;
    return;
  }
  const glm::vec3 toLight = parameters_.lightPosition - origin;
  const float distance = glm::length(toLight);
  const Ray ray{origin, toLight / distance, 0.0f, distance};
  if (!(distance > 0.0f) || !geometry_.mayHit(ray)) {
    colors[pixel] += multiplier;
    return;
  }
  PendingShadow& shadow = wavefront.shadows.emplace_back();  // written in place (see shadeSlimes8)
  shadow.ray = ray;
  shadow.multiplier = multiplier;
  shadow.pixel = pixel;
  shadow.fromFloor = fromFloor;
}

}  // namespace slime

// Caustics' oracles (render/caustics/): (a) power: what leaves a ball through it equals what it
// intercepts times its Fresnel and Beer–Lambert transmittance, summed over the internal reflections
// in closed form; (b) a ball lens: the wavefront map's peak on the floor lies at the paraxial focus
// f = nR / (2 (n − 1)) from the centre, and its profile and its brightest millimetre match an
// independent brute-force light tracer (random photons, 100 times as many, a histogram); (c) on the
// settled clear and green slimes, the brightest millimetre of the gain, where it lies and the gain over
// the caustic match the photon tracer's histogram of 25 times as many photons.
#include "render_fixture.h"

#include "render/caustics/caustic_map.h"
#include "render/caustics/caustics.h"
#include "render/caustics/photon_tracer.h"
#include "render/caustics/wavefront.h"
#include "render/image/image_io.h"
#include "render/trace/brute_tracer.h"
#include "render/trace/embree_scene.h"
#include "render/trace/optics.h"

#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <cmath>
#include <mutex>
#include <random>
#include <tuple>

namespace slime::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The analytic sphere of radius R at `center`, Embree's, with the shading constants of `settings`.
struct Ball {
  Settings settings = defaultSettings();
  SlimeGeometry geometry;
  EmbreeScene embree{0};
  ShadingParameters parameters;
  // analytic = false: the icosphere's triangles alone, of radius R × scale.
  Ball(const glm::dvec3& center, const glm::dvec3& light, const glm::dvec3& color, double absorption,
       bool analytic = true, double scale = 1.0) {
    settings.slime.shape = "sphere";
    settings.slime.position = center;
    settings.slime.color = color;
    settings.slime.absorption = absorption;
    settings.slime.transmission = 1.0;
    settings.light.position = light;
    const TriangleMesh mesh = makeIcosphere(2, settings.slime.radius * scale, center);
    const bool topology = geometry.update(mesh.positions, mesh.triangles);
    geometry.setAnalyticSphere(analytic, static_cast<float>(settings.slime.radius));
    embree.update(geometry, topology);
    parameters = makeShadingParameters(settings, 100);
  }
};

// The wavefront map (wavefront.h) of a grid of side `side` (one level) over the cone, all traced.
CausticMap wavefrontMap(const SlimeGeometry& geometry, const SlimeIntersector& intersector, const ShadingParameters& parameters,
                        int side) {
  const PhotonCone cone = photonCone(geometry, parameters.lightPosition);
  const PhotonTracer tracer(geometry, intersector, parameters);
  const WavefrontGrid grid(side, 1);
  std::vector<WavefrontVertex> vertices;
  PhotonTally tally;
  traceWavefront(tracer, cone, grid, 0, grid.vertices(), vertices, tally);
  CausticMap map;
  map.buildWavefront(grid, 0, vertices, cone, shadowRegion(cone, geometry.boundCenter, geometry.boundRadius));
  return map;
}

// Per unit intensity, the power a ball of radius R and index n at distance D from a point light
// sends out through its surface: over the cone of directions that meet it (impact parameter
// b = D sin ψ, sin θi = b / R), each ray enters with 1 − F, crosses a chord L = 2R cos θt losing
// exp(−σL), and at each of its exits leaves 1 − F (the same F: the angles inside are all θt),
//   P = ∫ (1 − F)² e^{−σL} / (1 − F e^{−σL}) dΩ   (the internal reflections' geometric series).
double ballTransmittedPower(double distance, double radius, double n, double sigma) {
  const double psiMax = std::asin(radius / distance);
  const int steps = 20000;
  double sum = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double psi = (k + 0.5) / steps * psiMax;
    const double b = distance * std::sin(psi);
    const double sinI = std::min(1.0, b / radius), cosI = std::sqrt(1.0 - sinI * sinI);
    const double sinT = sinI / n, cosT = std::sqrt(1.0 - sinT * sinT);
    const double rs = (cosI - n * cosT) / (cosI + n * cosT), rp = (n * cosI - cosT) / (n * cosI + cosT);
    const double f = 0.5 * (rs * rs + rp * rp);
    const double a = std::exp(-sigma * 2.0 * radius * cosT);
    sum += (1.0 - f) * (1.0 - f) * a / (1.0 - f * a) * 2.0 * kPi * std::sin(psi) * (psiMax / steps);
  }
  return sum;
}

TEST(Caustics, PowerThroughABallMatchesFresnelAndBeerLambert) {
  const glm::dvec3 color{0.5, 0.7, 0.9};
  Ball ball({0.0, 0.0, 0.04}, {0.1, 0.05, 0.5}, color, 20.0);
  const PhotonCone cone = photonCone(ball.geometry, ball.parameters.lightPosition);
  const PhotonTracer tracer(ball.geometry, ball.embree, ball.parameters);
  std::vector<PhotonLanding> landings;
  PhotonTally tally;
  tracer.trace(cone, 0, 40000, landings, tally);
  const double distance = glm::length(glm::dvec3(ball.parameters.lightPosition) - glm::dvec3(0.0, 0.0, 0.04));
  for (int c = 0; c < 3; ++c) {
    const double sigma = ball.parameters.slimeAbsorption[c];
    const double expected = ballTransmittedPower(distance, ball.settings.slime.radius, ball.settings.slime.ior, sigma);
    const double traced = (tally.landed[c] + tally.escaped[c]) * cone.solidAngle / tally.emitted;
    EXPECT_NEAR(traced / expected, 1.0, 0.02) << "channel " << c << ": traced " << traced << ", expected " << expected;
    EXPECT_GT(tally.landed[c], 0.9 * (tally.landed[c] + tally.escaped[c]));  // nearly all of it reaches the floor
  }
  // The wavefront map keeps the power: its irradiance integrated over the floor is what the photons
  // brought to it (a flux oracle for the triangles' spreading).
  const CausticMap map = wavefrontMap(ball.geometry, ball.embree, ball.parameters, 200);
  const float cell = map.cellSize() / 2.0f;
  glm::dvec3 integral(0.0);
  for (float y = -0.2f; y < 0.2f; y += cell)
    for (float x = -0.2f; x < 0.2f; x += cell) integral += glm::dvec3(map.irradiance(x, y)) * double(cell) * double(cell);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(integral[c] / (tally.landed[c] * cone.solidAngle / tally.emitted), 1.0, 0.02) << "channel " << c;
    std::printf("channel %d: the map's power over the photons' %.4f\n", c, integral[c] / (tally.landed[c] * cone.solidAngle / tally.emitted));
  }
}

// A ball of radius R lit from far along unit direction d (from the light), its centre at height
// f |d_z| so that its paraxial focus c + f d lies on the floor.
struct Lens {
  glm::dvec3 direction, center, focus;
  double focal = 0.0;
};
Lens lensOnTheFloor(const glm::dvec3& direction, double radius, double n) {
  Lens lens;
  lens.direction = glm::normalize(direction);
  lens.focal = n * radius / (2.0 * (n - 1.0));
  lens.center = glm::dvec3(0.0, 0.0, lens.focal * -lens.direction.z);
  lens.focus = lens.center + lens.focal * lens.direction;
  return lens;
}

// The floor point of the map's largest irradiance, searched on a grid of `step` around `around`.
glm::dvec2 peakOf(const CausticMap& map, const glm::dvec2& around, double halfWidth, double step) {
  glm::dvec2 best = around;
  float bestValue = -1.0f;
  for (double y = around.y - halfWidth; y <= around.y + halfWidth; y += step)
    for (double x = around.x - halfWidth; x <= around.x + halfWidth; x += step) {
      const float value = map.irradiance(static_cast<float>(x), static_cast<float>(y)).x;
      if (value > bestValue) bestValue = value, best = {x, y};
    }
  return best;
}

void expectPeakAtTheParaxialFocus(const glm::dvec3& direction) {
  const double radius = defaultSettings().slime.radius, n = defaultSettings().slime.ior;
  const Lens lens = lensOnTheFloor(direction, radius, n);
  const glm::dvec3 light = lens.center - 50.0 * lens.direction;  // far: the rays all but parallel
  Ball ball(lens.center, light, {1.0, 1.0, 1.0}, 0.0);
  const CausticMap map = wavefrontMap(ball.geometry, ball.embree, ball.parameters, 316);
  const glm::dvec2 peak = peakOf(map, {lens.focus.x, lens.focus.y}, 0.01, 2e-5);
  std::printf("peak %.4f mm from the paraxial focus, cell %.4f mm\n", 1e3 * glm::length(peak - glm::dvec2(lens.focus.x, lens.focus.y)),
              1e3 * map.cellSize());
  // Within one cell of the map (its kernel's half width) of the paraxial focus.
  EXPECT_LT(glm::length(peak - glm::dvec2(lens.focus.x, lens.focus.y)), map.cellSize())
      << "peak (" << peak.x << ", " << peak.y << "), focus (" << lens.focus.x << ", " << lens.focus.y << "), cell "
      << map.cellSize();
}

TEST(Caustics, BallLensPeaksAtTheParaxialFocusFromAbove) { expectPeakAtTheParaxialFocus({0.0, 0.0, -1.0}); }
TEST(Caustics, BallLensPeaksAtTheParaxialFocusFromTheSide) { expectPeakAtTheParaxialFocus({0.5, 0.2, -0.8}); }

// The brute-force light tracer: random photons into the ball (uniform in the cone), Snell and
// Fresnel chosen at random at each crossing (Russian roulette), to the floor; the irradiance in
// rings about the axis, per unit intensity.
// With `cells`: also the irradiance in kCells × kCells square cells of kCellWidth, the middle one
// centred on the focus.
constexpr int kCells = 41;
constexpr double kCellWidth = 0.001;
std::vector<double> bruteForceRings(const Lens& lens, double radius, double n, const glm::dvec3& light,
                                    std::int64_t photons, double ringWidth, int rings, std::uint32_t seed,
                                    std::vector<double>* cells = nullptr) {
  if (cells) cells->assign(kCells * kCells, 0.0);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const glm::dvec3 axis = glm::normalize(lens.center - light);
  const double distance = glm::length(lens.center - light), cosAlpha = std::sqrt(1.0 - radius * radius / (distance * distance));
  const double solidAngle = 2.0 * kPi * (1.0 - cosAlpha);
  const glm::dvec3 u = glm::normalize(glm::cross(std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0), axis));
  const glm::dvec3 v = glm::cross(axis, u);
  std::vector<double> power(rings, 0.0);
  const auto sphereExit = [&](const glm::dvec3& o, const glm::dvec3& d) {  // far root from inside
    const glm::dvec3 oc = o - lens.center;
    const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
    return -b + std::sqrt(std::max(0.0, b * b - c));
  };
  const auto fresnel = [](double cosI, double from, double to) {
    const double sinT = from / to * std::sqrt(std::max(0.0, 1.0 - cosI * cosI));
    if (sinT >= 1.0) return 1.0;
    const double cosT = std::sqrt(1.0 - sinT * sinT);
    const double rs = (from * cosI - to * cosT) / (from * cosI + to * cosT), rp = (to * cosI - from * cosT) / (to * cosI + from * cosT);
    return 0.5 * (rs * rs + rp * rp);
  };
  for (std::int64_t k = 0; k < photons; ++k) {
    const double cosTheta = 1.0 - uniform(random) * (1.0 - cosAlpha), phi = 2.0 * kPi * uniform(random);
    const double sinTheta = std::sqrt(1.0 - cosTheta * cosTheta);
    glm::dvec3 d = cosTheta * axis + sinTheta * std::cos(phi) * u + sinTheta * std::sin(phi) * v;
    const glm::dvec3 oc = light - lens.center;
    const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius, disc = b * b - c;
    if (disc < 0.0) continue;
    glm::dvec3 p = light + (-b - std::sqrt(disc)) * d;
    glm::dvec3 normal = (p - lens.center) / radius;
    double cosI = -glm::dot(d, normal);
    if (uniform(random) < fresnel(cosI, 1.0, n)) continue;  // reflected away
    const auto refracted = [](const glm::dvec3& dir, const glm::dvec3& nrm, double eta) {
      const double ci = -glm::dot(nrm, dir), s2 = eta * eta * (1.0 - ci * ci);
      return eta * dir + (eta * ci - std::sqrt(1.0 - s2)) * nrm;
    };
    d = refracted(d, normal, 1.0 / n);
    bool out = false;
    for (int bounce = 0; bounce < 32 && !out; ++bounce) {
      p += sphereExit(p, d) * d;
      normal = (p - lens.center) / radius;
      cosI = glm::dot(d, normal);
      if (uniform(random) < fresnel(cosI, n, 1.0)) {
        d = d - 2.0 * glm::dot(d, normal) * normal;
      } else {
        d = refracted(d, -normal, n);
        out = true;
      }
    }
    if (!out || d.z >= 0.0) continue;
    const glm::dvec3 floor = p + (-p.z / d.z) * d;
    const int ring = static_cast<int>(glm::length(glm::dvec2(floor.x - lens.focus.x, floor.y - lens.focus.y)) / ringWidth);
    if (ring < rings) power[ring] += solidAngle / static_cast<double>(photons);
    const int i = static_cast<int>(std::floor((floor.x - lens.focus.x) / kCellWidth + 0.5 * kCells)),
              j = static_cast<int>(std::floor((floor.y - lens.focus.y) / kCellWidth + 0.5 * kCells));
    if (cells && i >= 0 && j >= 0 && i < kCells && j < kCells)
      (*cells)[static_cast<std::size_t>(j) * kCells + i] += solidAngle / static_cast<double>(photons) / (kCellWidth * kCellWidth);
  }
  for (int r = 0; r < rings; ++r) power[r] /= kPi * ringWidth * ringWidth * ((r + 1.0) * (r + 1.0) - r * r);
  return power;
}

// The map's mean over the square cell of width `width` centred at `centre` (of `value`: irradiance or gain), 8 × 8 points.
template <class Value>
double cellMean(const Value& value, const glm::dvec2& centre, double width) {
  double sum = 0.0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i)
      sum += value(static_cast<float>(centre.x + ((i + 0.5) / 8.0 - 0.5) * width), static_cast<float>(centre.y + ((j + 0.5) / 8.0 - 0.5) * width));
  return sum / 64.0;
}

TEST(Caustics, BallLensProfileMatchesABruteForceLightTracer) {
  const double radius = defaultSettings().slime.radius, n = defaultSettings().slime.ior;
  const Lens lens = lensOnTheFloor({0.0, 0.0, -1.0}, radius, n);
  const glm::dvec3 light = lens.center - 50.0 * lens.direction;
  Ball ball(lens.center, light, {1.0, 1.0, 1.0}, 0.0);
  constexpr int kSide = 141;  // 142² = 20,164 vertices
  const CausticMap map = wavefrontMap(ball.geometry, ball.embree, ball.parameters, kSide);
  // Rings 2 mm wide out to 2 cm, the centre's ring left out (its spike is the peak's test below).
  constexpr double kRing = 0.002;
  constexpr int kRings = 10;
  std::vector<double> cells;
  const std::vector<double> brute = bruteForceRings(lens, radius, n, light, 100 * (kSide + 1) * (kSide + 1), kRing, kRings, 7, &cells);
  double largestError = 0.0, largestRelative = 0.0, scale = 0.0;
  for (int r = 1; r < kRings; ++r) scale = std::max(scale, brute[r]);
  for (int r = 1; r < kRings; ++r) {
    double mean = 0.0;  // the map averaged over the ring
    const int samples = 2000;
    for (int k = 0; k < samples; ++k) {
      const double radial = (r + (k % 20 + 0.5) / 20.0) * kRing, angle = 2.0 * kPi * (k / 20 + 0.5) / (samples / 20);
      mean += map.irradiance(static_cast<float>(lens.focus.x + radial * std::cos(angle)),
                             static_cast<float>(lens.focus.y + radial * std::sin(angle))).x *
              radial;
    }
    mean /= samples * (r + 0.5) * kRing;  // area-weighted over the ring
    largestError = std::max(largestError, std::abs(mean - brute[r]) / scale);
    largestRelative = std::max(largestRelative, std::abs(mean - brute[r]) / brute[r]);
    std::printf("ring %d: map %.4g brute %.4g\n", r, mean, brute[r]);
  }
  EXPECT_LT(largestError, 0.01) << "largest ring error, relative to the largest ring";
  EXPECT_LT(largestRelative, 0.04) << "largest ring error, relative to the ring";
  // The brightest 1 mm cell: the brute force's against the map's (its mean over each cell).
  std::size_t bruteBest = 0, mapBest = 0;
  std::vector<double> mapped(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const glm::dvec2 centre(lens.focus.x + (static_cast<double>(k % kCells) - kCells / 2) * kCellWidth,
                            lens.focus.y + (static_cast<double>(k / kCells) - kCells / 2) * kCellWidth);
    mapped[k] = cellMean([&](float x, float y) { return map.irradiance(x, y).x; }, centre, kCellWidth);
    if (cells[k] > cells[bruteBest]) bruteBest = k;
    if (mapped[k] > mapped[mapBest]) mapBest = k;
  }
  const double apart = kCellWidth * glm::length(glm::dvec2(static_cast<double>(bruteBest % kCells) - static_cast<double>(mapBest % kCells),
                                                           static_cast<double>(bruteBest / kCells) - static_cast<double>(mapBest / kCells)));
  std::printf("brightest 1 mm cell: map %.4g, brute %.4g (%.3f), %.1f mm apart\n", mapped[mapBest], cells[bruteBest],
              mapped[mapBest] / cells[bruteBest], 1e3 * apart);
  EXPECT_NEAR(mapped[mapBest] / cells[bruteBest], 1.0, 0.25);
  EXPECT_LE(apart, 0.002 + 1e-9);
}

// A settled slime's caustic (the clear slime lit from low at the side, or the default green one)
// against the photon tracer's histogram: the gain g (all the light that arrived over the light with
// no slime) in 1 mm cells, the reference from kReferencePerVertex times as many photons as the
// finished map has vertices (each photon's landings, and its straight line's, counted in its cell;
// a cell counts where at least that many straight lines land). 25: the reference's brightest cell
// holds about 44,000 of the clear slime's photons and 5,300 of the green's (0.5 % and 1.4 % noise
// against the peak's 25 % tolerance); the RMS over the caustic's cells, 0.12 and 0.020 stop (0.075
// and 0.016 with 100 times as many: the reference's own noise in cells of a few dozen photons),
// against its 0.5 limit. A quarter of 100's time (4.8 s and 2.7 s here, from 18 s and 10 s).
constexpr std::uint64_t kReferencePerVertex = 25;
struct SceneCaustic {
  double mapPeak = 0.0, referencePeak = 0.0, apart = 0.0, rmsStops = 0.0;
  int cells = 0;
};
SceneCaustic compareSceneCaustic(const Settings& settings) {
  const TriangleMesh mesh = settledMesh(settings);
  SlimeGeometry geometry;
  EmbreeScene embree{0};
  const bool topology = geometry.update(mesh.positions, mesh.triangles);
  embree.update(geometry, topology);
  const ShadingParameters parameters = makeShadingParameters(settings, 100);
  Caustics caustics;
  const CausticMap* map = caustics.update(settings, parameters, geometry, embree, nullptr);
  EXPECT_NE(map, nullptr);
  SceneCaustic result;
  if (!map) return result;
  // The reference: photons [0, 100 V) of the R2 sequence.
  const PhotonCone cone = photonCone(geometry, parameters.lightPosition);
  const PhotonTracer tracer(geometry, embree, parameters);
  const FloorRegion region = shadowRegion(cone, geometry.boundCenter, geometry.boundRadius);
  const int columns = static_cast<int>(std::ceil((region.high.x - region.low.x) / kCellWidth));
  const int rows = static_cast<int>(std::ceil((region.high.y - region.low.y) / kCellWidth));
  std::vector<double> arrived(static_cast<std::size_t>(columns) * rows, 0.0), straight(arrived.size(), 0.0);
  const auto cellOf = [&](const PhotonLanding& l) -> long {
    const int i = static_cast<int>(std::floor((l.x - region.low.x) / kCellWidth)), j = static_cast<int>(std::floor((l.y - region.low.y) / kCellWidth));
    return i >= 0 && j >= 0 && i < columns && j < rows ? static_cast<long>(j) * columns + i : -1;
  };
  const std::uint64_t photons = kReferencePerVertex * caustics.photons();
  constexpr std::uint64_t kChunk = 1 << 16;
  std::mutex sums;
  tbb::parallel_for(std::uint64_t{0}, (photons + kChunk - 1) / kChunk, [&](std::uint64_t chunk) {
    std::vector<PhotonLanding> landings, straightLandings;
    PhotonTally tally;
    const std::uint64_t first = chunk * kChunk;
    tracer.trace(cone, first, std::min(kChunk, photons - first), landings, tally, &straightLandings);
    const std::lock_guard<std::mutex> lock(sums);
    for (const PhotonLanding& l : landings)
      if (const long c = cellOf(l); c >= 0) arrived[static_cast<std::size_t>(c)] += l.weight.y;  // green: the green slime's caustic
    for (const PhotonLanding& l : straightLandings)
      if (const long c = cellOf(l); c >= 0) straight[static_cast<std::size_t>(c)] += 1.0, arrived[static_cast<std::size_t>(c)] += l.weight.y;
  });
  // Taken once more after the workers: ThreadSanitizer does not see TBB's join, but it sees the mutex's
  // hand-over from the last worker that added to the sums.
  const std::lock_guard<std::mutex> summed(sums);
  const glm::vec3 light = parameters.lightPosition;
  std::size_t referenceBest = 0, mapBest = 0;
  std::vector<double> mapped(arrived.size(), 0.0), reference(arrived.size(), 0.0);
  for (std::size_t k = 0; k < arrived.size(); ++k) {
    if (straight[k] < kReferencePerVertex) continue;  // cells the cone barely reaches
    reference[k] = arrived[k] / straight[k];
    const glm::dvec2 centre(region.low.x + (static_cast<double>(k % columns) + 0.5) * kCellWidth,
                            region.low.y + (static_cast<double>(k / columns) + 0.5) * kCellWidth);
    mapped[k] = cellMean([&](float x, float y) { return map->gain(glm::vec3(x, y, 0.0f), light).y; }, centre, kCellWidth);
    if (reference[k] > reference[referenceBest]) referenceBest = k;
    if (mapped[k] > mapped[mapBest]) mapBest = k;
  }
  result.mapPeak = mapped[mapBest];
  result.referencePeak = reference[referenceBest];
  result.apart = kCellWidth * glm::length(glm::dvec2(static_cast<double>(referenceBest % columns) - static_cast<double>(mapBest % columns),
                                                     static_cast<double>(referenceBest / columns) - static_cast<double>(mapBest / columns)));
  // The caustic's region: the cells where the reference's gain exceeds the unblocked light's.
  double squares = 0.0;
  for (std::size_t k = 0; k < arrived.size(); ++k) {
    if (!(reference[k] > 1.0)) continue;
    const double stops = std::log2(std::max(mapped[k], 1e-6) / reference[k]);
    squares += stops * stops;
    ++result.cells;
  }
  result.rmsStops = result.cells > 0 ? std::sqrt(squares / result.cells) : 0.0;
  std::printf("%llu vertices, %llu photons: brightest 1 mm cell's gain %.3g against %.3g (%.3f), %.1f mm apart; "
              "RMS log2 gain over %d caustic cells %.3f stop; the reference's brightest: %.0f photons\n",
              static_cast<unsigned long long>(caustics.photons()), static_cast<unsigned long long>(photons), result.mapPeak,
              result.referencePeak, result.mapPeak / result.referencePeak, 1e3 * result.apart, result.cells, result.rmsStops,
              arrived[referenceBest]);
  return result;
}

void expectTheReferencesCaustic(const SceneCaustic& c) {
  EXPECT_NEAR(c.mapPeak / c.referencePeak, 1.0, 0.25) << "brightest 1 mm cell's gain " << c.mapPeak << " against " << c.referencePeak;
  EXPECT_LE(c.apart, 0.002 + 1e-9) << "brightest cells apart";
  EXPECT_GT(c.cells, 5);
  EXPECT_LE(c.rmsStops, 0.5) << "RMS log2 gain over the caustic";
}

TEST(Caustics, ClearSlimesCausticKeepsThePeakAndTheCusp) {
  Settings settings = defaultSettings();
  settings.slime.color = {1.0, 1.0, 1.0};
  settings.slime.absorption = 0.0;
  settings.slime.transmission = 1.0;
  settings.light.position = {0.25, -0.05, 0.12};
  expectTheReferencesCaustic(compareSceneCaustic(settings));
}

TEST(Caustics, GreenSlimesCausticKeepsThePeakAndTheCusp) {
  Settings settings = defaultSettings();
  expectTheReferencesCaustic(compareSceneCaustic(settings));
}

// Through the renderer: a clear slime lit from low at the side focuses light into its shadow, so
// with caustics some floor pixels there are brighter than without (where the straight shadow ray
// drew a tinted shadow never brighter than full light), and no pixel is NaN.
TEST(Caustics, RendererBrightensTheClearSlimesShadow) {
  Settings settings = smallScene(96, 72);
  settings.slime.color = {1.0, 1.0, 1.0};
  settings.slime.absorption = 0.0;
  settings.slime.transmission = 1.0;
  settings.light.position = {0.25, -0.05, 0.12};
  RenderStats off, on;
  settings.render.caustics = false;
  const Image without = renderScene(settings, &off);
  settings.render.caustics = true;
  const Image with = renderScene(settings, &on);
  EXPECT_EQ(on.nonFinitePixels, 0u);
  EXPECT_EQ(on.causticPhotons, Caustics::finishedVertices(static_cast<std::uint64_t>(settings.render.photons)));  // finished
  EXPECT_EQ(off.causticPhotons, 0u);
  const std::vector<std::uint8_t> a = toSrgb8(without), b = toSrgb8(with);
  int brighter = 0;
  for (std::size_t i = 0; i < a.size(); i += 3) brighter += b[i] > a[i] + 20;
  EXPECT_GE(brighter, 5) << "pixels brighter by more than 20/255 with caustics";
}

// The clear slime lit from low at the side (RendererBrightensTheClearSlimesShadow), caustics on, the
// smallest budget: the finished map's grid is 129² = 16,641 vertices.
Settings clearSlimeLitFromTheSide(int width, int height) {
  Settings settings = smallScene(width, height);
  settings.slime.color = {1.0, 1.0, 1.0};
  settings.slime.absorption = 0.0;
  settings.slime.transmission = 1.0;
  settings.light.position = {0.25, -0.05, 0.12};
  settings.render.caustics = true;
  settings.render.photons = 1000;
  return settings;
}

// Pixels whose colours are not bit for bit the same.
int differingPixels(const Image& a, const Image& b) {
  if (a.pixels.size() != b.pixels.size()) return -1;
  int count = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) count += a.pixels[i] != b.pixels[i];
  return count;
}

// A plain render (a snapshot, a test) draws the finished map whatever the renderer drew before: a
// second, third frame of one renderer equals a fresh renderer's first, bit for bit.
TEST(Caustics, PlainRenderDoesNotDependOnEarlierFrames) {
  const Settings settings = clearSlimeLitFromTheSide(64, 48);
  const TriangleMesh mesh = restingMesh(settings);
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  Image first, second, third;
  first.resize(64, 48), second.resize(64, 48), third.resize(64, 48);
  const RenderStats a = renderer.render(settings, first);
  const RenderStats b = renderer.render(settings, second);
  Settings lower = settings;  // the light moved and back: the map starts again, and ends the same
  lower.light.position.z = 0.1;
  renderer.render(lower, third);
  const RenderStats c = renderer.render(settings, third);
  const std::uint64_t finished = Caustics::finishedVertices(static_cast<std::uint64_t>(settings.render.photons));
  EXPECT_EQ(a.causticPhotons, finished);
  EXPECT_EQ(b.causticPhotons, finished);
  EXPECT_EQ(c.causticPhotons, finished);
  EXPECT_EQ(differingPixels(first, second), 0);
  EXPECT_EQ(differingPixels(first, third), 0);
  const Image fresh = renderMesh(settings, mesh);
  EXPECT_EQ(differingPixels(first, fresh), 0);
}

// The viewer's progressive map: a moving grid of about half a budget in a frame that starts it, then
// the still grid, k/16 of its vertices in the k-th frame while nothing changes, coarse to fine, so its
// 16th frame is the plain render's finished map; a change starts it again.
TEST(Caustics, ProgressiveMapEndsAtThePlainRendersFinishedMap) {
  const Settings settings = clearSlimeLitFromTheSide(48, 36);
  const TriangleMesh mesh = restingMesh(settings);
  Renderer renderer(settings);
  renderer.setProgressiveCaustics(true);
  renderer.updateSlime({mesh});
  Image image;
  image.resize(48, 36);
  const auto budget = static_cast<std::uint64_t>(settings.render.photons);
  const std::uint64_t moving = Caustics::movingVertices(budget);  // the moving grid's coarse level
  EXPECT_LE(moving, budget / Caustics::kMovingDivisor);
  RenderStats stats = renderer.render(settings, image);
  const std::uint64_t refined = stats.causticPhotons;  // and the finer vertices of its squares at the outline
  EXPECT_GT(refined, moving);
  EXPECT_LT(refined, 4 * moving);
  const Image early = image;
  stats = renderer.render(settings, image);
  EXPECT_EQ(stats.causticPhotons, Caustics::stillTarget(budget, 2));
  for (int frame = 2; frame < Caustics::kStillBudgets; ++frame) stats = renderer.render(settings, image);
  EXPECT_EQ(stats.causticPhotons, Caustics::finishedVertices(budget));
  EXPECT_GT(differingPixels(early, image), 0);  // the map refined
  EXPECT_EQ(differingPixels(image, renderMesh(settings, mesh)), 0);
  Settings moved = settings;
  moved.light.position.x = 0.24;
  stats = renderer.render(moved, image);
  EXPECT_GT(stats.causticPhotons, moving);
  EXPECT_LT(stats.causticPhotons, 4 * moving);
}

// A moving frame traces the moving grid's coarse level and, in each coarse square whose corners do
// not take the same paths (the outline, the edge of total internal reflection), the finer level's
// vertices, and spreads those squares as four: the map equals the one built from the same vertices
// by CausticMap alone, and it lies closer to the finished map than the coarse level's alone does.
// (Without the refinement the default slime's shadow, rendered, is 36.6–36.9 dB from the finished
// map's against 38.3–39.2 with it: MovingMapImageIsCloseToTheFinishedMap.)
TEST(Caustics, MovingFramesRefineTheSquaresWhosePathsDiffer) {
  const glm::dvec3 light{0.1, 0.05, 0.5}, color{0.5, 0.7, 0.9};
  Ball ball({0.0, 0.0, 0.04}, light, color, 20.0, false);
  Settings settings = ball.settings;
  settings.render.photons = 4000;
  const auto budget = static_cast<std::uint64_t>(settings.render.photons);
  const int side = Caustics::movingSide(budget / Caustics::kMovingDivisor);
  const WavefrontGrid grid(2 * side, 2);
  const PhotonCone cone = photonCone(ball.geometry, ball.parameters.lightPosition);
  const PhotonTracer tracer(ball.geometry, ball.embree, ball.parameters, Caustics::kMovingVertexWeight);
  // Every vertex of the finer level traced: the refinement picks from them.
  std::vector<WavefrontVertex> all;
  PhotonTally tally;
  traceWavefront(tracer, cone, grid, 0, grid.vertices(), all, tally);
  std::vector<std::uint8_t> refined(static_cast<std::size_t>(side) * side, 0);
  int squares = 0;
  for (int row = 0; row < side; ++row)
    for (int column = 0; column < side; ++column)
      squares += refined[static_cast<std::size_t>(row) * side + column] = needsFinerVertices(grid, all, 2 * column, 2 * row, 2);
  EXPECT_GT(squares, 0);
  EXPECT_LT(squares, side * side / 2);
  const FloorRegion region = shadowRegion(cone, ball.geometry.boundCenter, ball.geometry.boundRadius);
  CausticMap expected, coarse, fine;
  expected.beginWavefront(grid, 0, all, cone, region, CausticMap::kFineCells, &refined);
  expected.spreadWavefront(nullptr, CausticMap::kAllTraced);
  coarse.buildWavefront(grid, 0, all, cone, region, nullptr, CausticMap::kFineCells);
  fine.buildWavefront(grid, 1, all, cone, region, nullptr, CausticMap::kFineCells);
  Caustics caustics;
  const CausticMap* map = caustics.update(settings, ball.parameters, ball.geometry, ball.embree, nullptr, /*progressive=*/true);
  ASSERT_NE(map, nullptr);
  // The coarse level's vertices and each refined square's finer ones (its edges' midpoints, its centre) once.
  std::vector<std::uint8_t> needed(grid.vertices(), 0);
  for (int row = 0; row < side; ++row)
    for (int column = 0; column < side; ++column)
      if (refined[static_cast<std::size_t>(row) * side + column])
        for (const auto& [x, y] : {std::pair{1, 0}, {0, 1}, {1, 1}, {2, 1}, {1, 2}}) needed[grid.rank(2 * column + x, 2 * row + y)] = 1;
  EXPECT_EQ(caustics.lastTraced(), grid.levelEnd(0) + static_cast<std::uint64_t>(std::count(needed.begin(), needed.end(), 1)));
  // The gain over a grid of floor points about the shadow: equal maps give equal gains everywhere.
  int differing = 0;
  double refinedError = 0.0, coarseError = 0.0;
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 40; ++i) {
      const glm::vec3 point(-0.1f + 0.25f * i / 40.0f, -0.12f + 0.24f * j / 40.0f, 0.0f);
      const glm::vec3 shown = map->gain(point, glm::vec3(light)), truth = fine.gain(point, glm::vec3(light));
      differing += shown != expected.gain(point, glm::vec3(light));
      refinedError += glm::length(shown - truth);
      coarseError += glm::length(coarse.gain(point, glm::vec3(light)) - truth);
    }
  EXPECT_EQ(differing, 0);
  EXPECT_LT(refinedError, 0.8 * coarseError) << refinedError << " against " << coarseError;
}

// The viewer's moving frames against the full trace (`slime view --check-every`, issue 43's aim 38 dB
// mean): the settled default slime, lifted and stretched as a hand holds it, at the window test's
// view, its first progressive frame (the refined moving map) against the plain render's finished map,
// in 8-bit sRGB. Measured 39.2 and 38.3 dB; the moving grid's coarse level alone (needsFinerVertices
// always false) 36.9 and 36.6 dB, a fail.
double psnrDb(const Image& a, const Image& b) {
  const std::vector<std::uint8_t> x = toSrgb8(a), y = toSrgb8(b);
  double sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += (double(x[i]) - y[i]) * (double(x[i]) - y[i]);
  return 10.0 * std::log10(255.0 * 255.0 / std::max(1e-12, sum / static_cast<double>(x.size())));
}

TEST(Caustics, MovingMapImageIsCloseToTheFinishedMap) {
  const Settings settings = smallScene(230, 270);
  const TriangleMesh settled = settledMesh(settings);
  TriangleMesh lifted = settled;
  for (auto& p : lifted.positions) p.z = 1.3 * p.z + 0.01;
  for (const auto& [name, mesh, least] : {std::tuple{"settled", settled, 38.5}, std::tuple{"lifted", lifted, 37.8}}) {
    Renderer renderer(settings);
    renderer.setProgressiveCaustics(true);
    renderer.updateSlime({mesh});
    Image moving;
    moving.resize(settings.camera.width, settings.camera.height);
    renderer.render(settings, moving);
    const Image finished = renderMesh(settings, mesh);
    const double db = psnrDb(moving, finished);
    EXPECT_GE(db, least) << name;
    if (db < least) writePng(differenceImage(moving, finished), outputPath(std::string("moving_map_") + name + "_diff.png"));
  }
}

// The viewer's frame budget (Caustics::setFrameBudget): render.photons goes up to 10⁷ a frame, seconds
// of tracing. With a budget, a progressive update traces kFirstPhotons before it knows the rate and at
// least kFewestPhotons after, never the whole budget of a large render.photons in one frame, and the
// still map still ends at the finished map, vertex for vertex. (Without the budget every frame traced
// its whole share: a moving grid of 5,929 and the next 2/16 of the still grid's 385,641 here.)
TEST(Caustics, AFrameBudgetSpreadsTheMapOverFramesAndItStillEndsAtTheFinishedMap) {
  const glm::dvec3 light{0.1, 0.05, 0.5}, color{0.5, 0.7, 0.9};
  Ball ball({0.0, 0.0, 0.04}, light, color, 20.0, false);
  Settings settings = ball.settings;
  settings.render.photons = 30000;  // a moving frame's coarse 3,000, refined about twice, over kFirstPhotons
  Caustics budgeted;
  budgeted.setFrameBudget(1e-9);  // less than any trace: the fewest photons a frame
  const auto update = [&](Caustics& caustics, bool progressive) {
    return caustics.update(settings, ball.parameters, ball.geometry, ball.embree, nullptr, progressive);
  };
  ASSERT_NE(update(budgeted, true), nullptr);
  // The coarse grid within kFirstPhotons / 2, and its refinement.
  const std::uint64_t coarse = Caustics::movingVertices(Caustics::kMovingDivisor * Caustics::kFirstPhotons / 2);
  EXPECT_LT(coarse, Caustics::movingVertices(static_cast<std::uint64_t>(settings.render.photons)));
  EXPECT_GT(budgeted.lastTraced(), coarse);
  EXPECT_LT(budgeted.lastTraced(), 2 * coarse);
  // Each of the still grid's levels is shown in turn, coarse to fine, though a frame traces past a
  // level's end before its squares are spread (the map skipped the first two levels so before).
  std::uint64_t frames = 1, largest = 0;
  std::vector<int> levels;
  while (!budgeted.converged() && frames < 5000) {
    update(budgeted, true);
    largest = std::max(largest, budgeted.lastTraced());
    if (levels.empty() || levels.back() != budgeted.shownLevel()) levels.push_back(budgeted.shownLevel());
    ++frames;
  }
  EXPECT_EQ(levels, (std::vector<int>{-1, 0, 1, 2}));
  EXPECT_EQ(largest, Caustics::kFewestPhotons);
  ASSERT_TRUE(budgeted.converged()) << "after " << frames << " frames";
  EXPECT_EQ(budgeted.photons(), Caustics::finishedVertices(static_cast<std::uint64_t>(settings.render.photons)));
  Caustics plain;
  const CausticMap* finished = update(plain, false);
  const CausticMap* spread = update(budgeted, true);
  ASSERT_NE(finished, nullptr);
  ASSERT_NE(spread, nullptr);
  int differing = 0;
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 40; ++i) {
      const glm::vec3 point(-0.1f + 0.25f * i / 40.0f, -0.12f + 0.24f * j / 40.0f, 0.0f);
      differing += finished->gain(point, glm::vec3(light)) != spread->gain(point, glm::vec3(light));
    }
  EXPECT_EQ(differing, 0);
}

// The map's gain is a ratio of what arrived over what would have arrived unblocked, each over its own
// photons: a slime of index 1 that absorbs and reflects nothing lets every photon through on its
// straight line, so its "shadow" is no shadow at all, even at the outline where the kernel straddles it
// (Invariant.InvisibleSlimeLeavesTheImageUnchanged with caustics on).
TEST(Caustics, InvisibleSlimeCastsNoShadowWithCaustics) {
  Settings settings = invisibleSlimeScene();
  settings.render.caustics = true;
  settings.render.photons = 1000;
  RenderStats stats;
  const Image withSlime = renderScene(settings, &stats);
  const Image without = renderMesh(settings, TriangleMesh{});
  EXPECT_GT(stats.causticPhotons, 0u);
  const ImageDifference d = compareImages(withSlime, without, 1.0);
  EXPECT_EQ(d.fractionAbove, 0.0) << "largest difference " << d.largest << "/255";
  if (d.fractionAbove > 0.0) writePng(differenceImage(withSlime, without), outputPath("invisible_slime_caustics_diff.png"));
}

}  // namespace
}  // namespace slime::testing

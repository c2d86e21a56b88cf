#include "app/bench/peers/peer_front.h"

#include "app/bench/material/modal_fit.h"
#include "core/bulk/lamb_sphere.h"

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <type_traits>

namespace slime::peers {

namespace {

using nlohmann::json;

constexpr double kGravity = 9.81;
constexpr double kModeSpeed = 0.01;       // m/s, the largest initial speed of a mode run (small: linear)
constexpr double kModePeriods = 8.0;      // Lamb periods simulated per mode run
constexpr double kMinimumSeconds = 0.4;   // a drop lands after 64 ms; the cost needs ≥ 0.3 s of contact
constexpr double kSlimeSimSeconds = 4.0;  // `slime sim` for the target rest height
constexpr double kShearGuess = 480.0;     // Pa: the default slime's long-term G∞ = 0.4 × 1200, where the fit starts

struct FrontOptions {
  std::vector<int> resolutions{1, 2};
  std::vector<double> stepsMs{1.0, 2.0, 4.0, 8.0, 16.7};
  std::vector<int> iterations{1, 2, 4, 8};
  double seconds = 1.0;
  std::string json;
  std::vector<double> targetRestHeights;  // per resolution; empty: from `slime sim`
  std::string slime;                      // the slime program; empty: next to this one, ../slime
};

double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

std::string processorName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model, family, number;
  const auto value = [&](const std::string& key, std::string& out) {
    if (out.empty() && line.rfind(key, 0) == 0 && line.find(':') != std::string::npos)
      out = line.substr(line.find(':') + 2);
  };
  while (std::getline(cpuinfo, line)) {
    value("model name", model);
    value("cpu family", family);
    value("model\t", number);
  }
  std::ostringstream name;
  name << (model.empty() ? "unknown processor" : model) << " (family " << family << " model " << number << ", "
       << sysconf(_SC_NPROCESSORS_ONLN) << " cores online)";
  return name.str();
}

// The height of the nodes' bounding box; false if any node is not finite, the body has flown apart or
// (on a floor) fallen through it.
bool bodyHeight(const std::vector<glm::dvec3>& positions, bool floor, double& height) {
  double low = std::numeric_limits<double>::infinity(), high = -low, spread = 0.0;
  glm::dvec3 lowest(low), highest(-low);
  for (const glm::dvec3& p : positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    lowest = glm::min(lowest, p);
    highest = glm::max(highest, p);
  }
  low = lowest.z;
  high = highest.z;
  spread = glm::length(highest - lowest);
  height = high - low;
  return spread < 20.0 * kRadius && (!floor || low > -kRadius);
}

struct DropResult {
  bool diverged = false;
  double cost = 0.0;        // thread CPU ms per simulated ms
  double restHeight = 0.0;  // m
};

DropResult measureDrop(const PeerFactory& factory, const PeerBall& ball, double shear, double step, int iterations,
                       double seconds) {
  PeerScene scene;
  scene.shearModulus = shear;
  scene.step = step;
  scene.iterations = iterations;
  scene.dropped = true;
  scene.centre = {0.0, 0.0, kRadius + kDrop};
  std::unique_ptr<PeerWorld> world = factory(ball, scene);
  DropResult result;
  std::vector<glm::dvec3> positions;
  const long steps = std::lround(std::ceil(seconds / step - 1e-9));
  double cpu = 0.0, heightSum = 0.0;
  long heightSamples = 0, taken = 0;
  for (long k = 1; k <= steps; ++k) {
    const double start = threadCpuSeconds();
    world->step();
    cpu += threadCpuSeconds() - start;
    taken = k;
    world->positions(positions);
    double height = 0.0;
    if (!bodyHeight(positions, true, height)) {
      result.diverged = true;
      break;
    }
    if (2 * k > steps) {
      heightSum += height;
      ++heightSamples;
    }
  }
  result.cost = cpu / (static_cast<double>(taken) * step);  // s per s = ms per ms, over the steps taken
  result.restHeight = heightSamples > 0 ? heightSum / static_cast<double>(heightSamples) : 0.0;
  return result;
}

struct ModeResult {
  bool diverged = false;
  std::optional<double> hz, dampingRatio;
};

ModeResult measureMode(const PeerFactory& factory, const PeerBall& ball, double shear, double step, int iterations,
                       bool spheroidal) {
  const double eta = lambRoot(2, spheroidal, kPoisson);
  const double theoryHz = eta * std::sqrt(shear / ball.density()) / (2.0 * std::numbers::pi * kRadius);
  const std::vector<glm::dvec3> shape =
      lambModeShape(ball.mesh.positions, ball.masses, glm::dvec3(0.0), kRadius, spheroidal, eta, kPoisson);
  PeerScene scene;
  scene.shearModulus = shear;
  scene.step = step;
  scene.iterations = iterations;
  scene.dropped = false;
  for (const glm::dvec3& s : shape) scene.velocities.push_back(kModeSpeed * s);
  std::unique_ptr<PeerWorld> world = factory(ball, scene);
  const long steps = std::lround(std::ceil(kModePeriods / theoryHz / step));
  std::vector<double> times, amplitudes, rates;
  std::vector<glm::dvec3> positions, velocities;
  ModeResult result;
  for (long k = 1; k <= steps; ++k) {
    world->step();
    world->positions(positions);
    world->velocities(velocities);
    double height = 0.0;
    if (!bodyHeight(positions, false, height)) {
      result.diverged = true;
      return result;
    }
    times.push_back(k * step);
    amplitudes.push_back(massProjection(positions, &ball.mesh.positions, shape, ball.masses));
    rates.push_back(massProjection(velocities, nullptr, shape, ball.masses));
  }
  const double hz = zeroCrossingFrequency(times, amplitudes);
  if (hz > 0.0) {
    result.hz = hz;
    result.dampingRatio = energyDampingRatio(times, amplitudes, rates, 2.0 * std::numbers::pi * hz);
  }
  return result;
}

// The shear modulus whose drop rests at `target`: bisection on ln G (rest height grows with G) at the
// grid's shortest step and most iterations, from 480 Pa (doubled while it diverges), the step halved
// while the fit's drops diverge.
struct Fit {
  double shear = 0.0, restHeight = 0.0, step = 0.0;
  int iterations = 1, drops = 0;
  std::string tried;  // "G Pa: height m" (or "diverged") of each drop, for the message when no G fits
};

Fit fitShear(const PeerFactory& factory, const PeerInfo& peer, const PeerBall& ball, double target, double step,
             int iterations, double seconds) {
  for (; step >= peer.stableStepFloor; step *= 0.5) {
    Fit fit;
    fit.step = step;
    fit.iterations = iterations;
    const auto height = [&](double shear, bool& diverged) {
      ++fit.drops;
      const DropResult drop = measureDrop(factory, ball, shear, step, iterations, seconds);
      diverged = diverged || drop.diverged;
      char line[96];
      std::snprintf(line, sizeof line, drop.diverged ? "%s%.0f Pa: diverged" : "%s%.0f Pa: %.4f m",
                    fit.tried.empty() ? "" : ", ", shear, drop.restHeight);
      fit.tried += line;
      return drop.restHeight;
    };
    bool diverged = false;
    double low = kShearGuess, high = kShearGuess;
    double lowHeight = height(low, diverged);
    // A soft guess that flies apart (Jolt's ball at resolution 3) starts again stiffer.
    for (int k = 0; k < 4 && diverged; ++k) diverged = false, lowHeight = height(low *= 2.0, diverged);
    high = low;
    double highHeight = lowHeight;
    for (int k = 0; k < 12 && !diverged && lowHeight > target; ++k) lowHeight = height(low *= 0.5, diverged);
    for (int k = 0; k < 12 && !diverged && highHeight < target; ++k) highHeight = height(high *= 2.0, diverged);
    if (!diverged && lowHeight <= target && highHeight >= target) {
      if (high == low) low *= 0.5, lowHeight = height(low, diverged);  // the guess rests at the target exactly
      while (!diverged && high / low > 1.003) {
        const double middle = std::sqrt(low * high), middleHeight = height(middle, diverged);
        (middleHeight < target ? low : high) = middle;
        (middleHeight < target ? lowHeight : highHeight) = middleHeight;
      }
      if (!diverged) {
        const bool lowCloser = std::abs(lowHeight - target) < std::abs(highHeight - target);
        fit.shear = lowCloser ? low : high;
        fit.restHeight = lowCloser ? lowHeight : highHeight;
        return fit;
      }
    }
    std::printf("  fit at step %.4g ms, %d iterations: %s, halving the step (%s)\n", 1e3 * step, iterations,
                diverged ? "a drop diverged" : "no modulus from 1/4096 to 4096 times the guess rests there",
                fit.tried.c_str());
  }
  return {};
}

// The default slime's rest height at `resolution`, viscosity off: the mean height over the last half of
// a `slime sim` run, as the peers' own rest height is taken.
double slimeRestHeight(const std::string& slime, int resolution) {
  const std::string report =
      (std::filesystem::temp_directory_path() / ("peer_front_slime_" + std::to_string(getpid()) + ".json")).string();
  const std::string command = "'" + slime + "' sim --seconds " + std::to_string(kSlimeSimSeconds) +
                              " --set slime.viscosity=0 --set slime.resolution=" + std::to_string(resolution) +
                              " --report '" + report + "' > /dev/null";
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "peer front: `%s` failed; give --target-rest-height or --slime\n", command.c_str());
    return 0.0;
  }
  std::ifstream in(report);
  const json run = json::parse(in, nullptr, false);
  std::filesystem::remove(report);
  double sum = 0.0;
  int samples = 0;
  if (run.is_object() && run.contains("series"))
    for (const json& sample : run["series"])
      if (sample.value("t", 0.0) > 0.5 * kSlimeSimSeconds) sum += sample.value("height", 0.0), ++samples;
  if (samples == 0) std::fprintf(stderr, "peer front: %s has no height series after %g s\n", report.c_str(), 0.5 * kSlimeSimSeconds);
  return samples > 0 ? sum / samples : 0.0;
}

template <typename Number>
bool parseList(const char* text, double low, double high, std::vector<Number>& out) {
  out.clear();
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(value) || value < low || value > high) return false;
    if (std::is_integral_v<Number> && value != std::floor(value)) return false;
    out.push_back(static_cast<Number>(value));
  }
  return !out.empty();
}

bool parseNumber(const char* text, double low, double high, double& out) {
  std::vector<double> one;
  if (!parseList(text, low, high, one) || one.size() != 1) return false;
  out = one[0];
  return true;
}

std::string defaultSlime(const char* program) {
  std::error_code error;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) self = program;
  return (self.parent_path().parent_path() / "slime").string();
}

}  // namespace

PeerBall makePeerBall(int resolution) {
  PeerBall ball;
  ball.mesh = makeBallTetMesh(resolution, kRadius, glm::dvec3(0.0));
  std::vector<double> share(ball.mesh.positions.size(), 0.0);
  for (const Tetrahedron& t : ball.mesh.tetrahedra) {
    const std::vector<glm::dvec3>& p = ball.mesh.positions;
    const double volume = tetrahedronVolume(p[t.x], p[t.y], p[t.z], p[t.w]);
    for (int corner = 0; corner < 4; ++corner) share[t[corner]] += 0.25 * volume;
    ball.restVolume += volume;
  }
  for (double s : share) ball.masses.push_back(kMass * s / ball.restVolume);
  return ball;
}

int runFront(int argc, char** argv, const PeerInfo& peer, const PeerFactory& factory) {
  FrontOptions options;
  const std::string usage =
      "usage: " + std::string(argv[0]) +
      " --front [--resolutions 1,2 (each 1 to 4)] [--steps-ms 1,2,4,8,16.7 (each 0.01 to 50)]\n"
      "         [--iterations 1,2,4,8 (each 1 to 64)] [--seconds S (0.4 to 60, each drop)] [--json FILE]\n"
      "         [--target-rest-height H,... (m, 0.01 to 0.08, one per resolution; default: from `slime sim`)]\n"
      "         [--slime PATH (the slime program; default: ../slime beside this one)]\n";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--front")) continue;
    if (i + 1 >= argc) {
      std::fprintf(stderr, "%s: %s needs a value\n%s", argv[0], argv[i], usage.c_str());
      return 2;
    }
    const char* value = argv[++i];
    bool ok = true;
    if (!std::strcmp(argv[i - 1], "--resolutions")) ok = parseList(value, kMinBodyResolution, kMaxBodyResolution, options.resolutions);
    else if (!std::strcmp(argv[i - 1], "--steps-ms")) ok = parseList(value, 0.01, 50.0, options.stepsMs);
    else if (!std::strcmp(argv[i - 1], "--iterations")) ok = parseList(value, 1, 64, options.iterations);
    else if (!std::strcmp(argv[i - 1], "--seconds")) ok = parseNumber(value, kMinimumSeconds, 60.0, options.seconds);
    else if (!std::strcmp(argv[i - 1], "--json")) options.json = value;
    else if (!std::strcmp(argv[i - 1], "--target-rest-height")) ok = parseList(value, 0.01, 2.0 * kRadius, options.targetRestHeights);
    else if (!std::strcmp(argv[i - 1], "--slime")) options.slime = value;
    else ok = false;
    if (!ok) {
      std::fprintf(stderr, "%s: bad option %s %s\n%s", argv[0], argv[i - 1], value, usage.c_str());
      return 2;
    }
  }
  if (!options.targetRestHeights.empty() && options.targetRestHeights.size() != options.resolutions.size()) {
    std::fprintf(stderr, "%s: --target-rest-height has %zu heights for %zu resolutions; give one per resolution\n",
                 argv[0], options.targetRestHeights.size(), options.resolutions.size());
    return 2;
  }
  if (options.slime.empty()) options.slime = defaultSlime(argv[0]);
  if (!peer.iterates) options.iterations = {1};

  json points = json::array();
  for (std::size_t r = 0; r < options.resolutions.size(); ++r) {
    const int resolution = options.resolutions[r];
    const PeerBall ball = makePeerBall(resolution);
    const double target = options.targetRestHeights.empty() ? slimeRestHeight(options.slime, resolution)
                                                            : options.targetRestHeights[r];
    if (target <= 0.0) return 1;
    const double fitStep = 1e-3 * *std::min_element(options.stepsMs.begin(), options.stepsMs.end());
    const int fitIterations = *std::max_element(options.iterations.begin(), options.iterations.end());
    const Fit fit = fitShear(factory, peer, ball, target, fitStep, fitIterations, options.seconds);
    if (fit.shear <= 0.0) {
      // No stiffness rests the peer's ball at the slime's height without flying apart: every point of
      // this resolution is diverged, its modulus and measures null.
      std::printf("%s resolution %d (%zu nodes): no stiffness rests the ball at %.5f m without diverging; "
                  "its points are marked diverged\n", peer.name.c_str(), resolution, ball.mesh.positions.size(), target);
      for (double stepMs : options.stepsMs)
        for (int iterations : options.iterations)
          points.push_back({{"resolution", resolution}, {"step_ms", stepMs}, {"iterations", iterations},
                            {"cost_ms_per_ms", json()}, {"shear_modulus_pa", json()}, {"density_kg_m3", ball.density()},
                            {"radius_m", kRadius}, {"poisson", kPoisson}, {"spheroidal_hz", json()},
                            {"torsional_hz", json()}, {"damping_ratio", json()}, {"rest_height_m", json()},
                            {"diverged", true}});
      continue;
    }
    std::printf("%s resolution %d (%zu nodes): target rest height %.5f m; fitted G %.1f Pa rests at %.5f m "
                "(step %.3g ms, %d iterations, %d drops)\n",
                peer.name.c_str(), resolution, ball.mesh.positions.size(), target, fit.shear, fit.restHeight,
                1e3 * fit.step, fit.iterations, fit.drops);
    std::fflush(stdout);
    for (double stepMs : options.stepsMs) {
      for (int iterations : options.iterations) {
        const double step = 1e-3 * stepMs;
        const DropResult drop = measureDrop(factory, ball, fit.shear, step, iterations, options.seconds);
        const ModeResult spheroidal = measureMode(factory, ball, fit.shear, step, iterations, true);
        const ModeResult torsional = measureMode(factory, ball, fit.shear, step, iterations, false);
        const bool diverged = drop.diverged || spheroidal.diverged || torsional.diverged;
        const auto orNull = [&](const std::optional<double>& value) { return value && !diverged ? json(*value) : json(); };
        // The jiggle's damping: the larger of the two modes' (the worse one), as measured.
        std::optional<double> damping = spheroidal.dampingRatio;
        if (torsional.dampingRatio) damping = std::max(damping.value_or(-1e9), *torsional.dampingRatio);
        points.push_back({{"resolution", resolution}, {"step_ms", stepMs}, {"iterations", iterations},
                          {"cost_ms_per_ms", drop.cost}, {"shear_modulus_pa", fit.shear},
                          {"density_kg_m3", ball.density()}, {"radius_m", kRadius}, {"poisson", kPoisson},
                          {"spheroidal_hz", orNull(spheroidal.hz)}, {"torsional_hz", orNull(torsional.hz)},
                          {"damping_ratio", orNull(damping)},
                          {"rest_height_m", drop.diverged ? json() : json(drop.restHeight)}, {"diverged", diverged}});
        const json& point = points.back();
        std::printf("  step %5.2f ms  iterations %d  cost %.4f ms/ms  spheroidal %s Hz  torsional %s Hz  damping %s  "
                    "rest height %s m%s\n",
                    stepMs, iterations, drop.cost, point["spheroidal_hz"].dump().c_str(), point["torsional_hz"].dump().c_str(),
                    point["damping_ratio"].dump().c_str(), point["rest_height_m"].dump().c_str(), diverged ? "  DIVERGED" : "");
        std::fflush(stdout);
      }
    }
  }
  const json report = {{"peer", peer.name}, {"processor", processorName()}, {"points", points}};
  if (!options.json.empty()) {
    std::ofstream out(options.json);
    out << report.dump(2) << "\n";
    if (!out) {
      std::fprintf(stderr, "%s: cannot write %s\n", argv[0], options.json.c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace slime::peers

// Shared by the torture runs of both models (torture_membrane_test.cpp, torture_bulk_test.cpp):
// one run driven in-process through Simulation and the scenario player, as `slime sim --scenario`
// does, sampled at every step, and the queries the checks ask of it.
#pragma once

#include "core/hands/grab.h"
#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace slime::fixture {

inline constexpr double kSeconds = 7.0;

inline glm::dvec3 centroid(const std::vector<glm::dvec3>& positions, const std::vector<std::uint32_t>* indices = nullptr) {
  glm::dvec3 sum(0.0);
  if (indices == nullptr) {
    for (const glm::dvec3& p : positions) sum += p;
    return sum / static_cast<double>(positions.size());
  }
  for (std::uint32_t i : *indices) sum += positions[i];
  return sum / static_cast<double>(indices->size());
}

// The bulk body's centre of mass (its nodes do not weigh the same).
inline glm::dvec3 centreOfMass(const Simulation& simulation) {
  const std::vector<glm::dvec3>& x = simulation.state().positions;
  const std::vector<double>& w = simulation.bulkBody().freeInverseMasses;
  glm::dvec3 sum(0.0);
  double mass = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sum += x[i] / w[i];
    mass += 1.0 / w[i];
  }
  return sum / mass;
}

// What a run did, step by step, and how it ended.
struct Sample {
  double time;
  bool grabbing;
  glm::dvec3 grabbed;  // membrane: centroid of the grabbed points; bulk: where the grabbed surface is
  glm::dvec3 target;   // the grab target (when grabbing)
  glm::dvec3 hand;     // bulk: the force the hand exerts, N
  glm::dvec3 body;     // membrane: centroid of all points; bulk: centre of mass
  double height;       // of the drawn surface (SlimeMetrics)
  double lowestZ;      // of the drawn surface after this step
  double grabbedMass;  // bulk: of the grabbed nodes, kg
  // bulk: what the sticky floor has taken from the body since the start (FloorAdhesion::momentumTaken,
  // displacementTaken), kg·m/s and kg·m
  glm::dvec3 contactMomentum{0.0}, contactDisplacement{0.0};
  std::size_t invertedElements = 0;  // bulk: tetrahedra with det Ds ≤ 0 after this step
  // Of the simulated points (the bulk's nodes; the membrane's drawn points): whether the body gave way
  // under a press, which the drawn surface's smooth map blurs by millimetres on resolution 1's elements.
  double bodyHeight = 0.0;
};

struct TortureResult {
  Settings settings;
  std::vector<Sample> samples;
  SlimeMetrics final;
  double lowestZ = std::numeric_limits<double>::infinity();  // drawn vertices and simulated points, every step
  bool nonFinite = false;    // a NaN/inf position after a step (the guard's rollback included)
  bool nanReported = false;  // the guard saw a NaN and rolled back
  std::size_t rollbacks = 0;
  std::string divergences;
};

inline TortureResult simulate(const std::string& model, const std::string& integrator, const std::string& overrides,
                       const std::string& scenario) {
  Settings settings = defaultSettings();
  applyOverride(settings, "slime.model=" + model);
  applyOverride(settings, "sim.integrator=" + integrator);
  // Level 3 (642 vertices) keeps the 40 tortures quick; the torture is in the motion, not the mesh size.
  applyOverride(settings, "slime.level=3");
  std::istringstream words(overrides);
  for (std::string assignment; words >> assignment;) applyOverride(settings, assignment);
  validateSettings(settings);
  Simulation simulation(settings);
  std::optional<ScenarioPlayer> player;
  if (!scenario.empty())
    player.emplace(loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/" + scenario + ".json"));
  TortureResult result;
  result.settings = settings;
  const bool bulk = simulation.bulk();
  const auto steps = static_cast<std::int64_t>(std::llround(kSeconds / settings.sim.dt));
  while (simulation.stepCount() < steps && simulation.divergences().size() <= 20) {
    if (player) player->advanceTo(simulation.time(), simulation, settings);
    simulation.step();
    double lowest = std::numeric_limits<double>::infinity();
    for (const glm::dvec3& p : simulation.positions()) {
      if (!std::isfinite(p.x + p.y + p.z)) result.nonFinite = true;
      lowest = std::min(lowest, p.z);
    }
    result.lowestZ = std::min(result.lowestZ, lowest);
    double bodyLow = std::numeric_limits<double>::infinity(), bodyHigh = -bodyLow;
    for (const glm::dvec3& p : simulation.state().positions) {  // the bulk's nodes (the membrane's: the same)
      if (!std::isfinite(p.x + p.y + p.z)) result.nonFinite = true;
      result.lowestZ = std::min(result.lowestZ, p.z);
      bodyLow = std::min(bodyLow, p.z);
      bodyHigh = std::max(bodyHigh, p.z);
    }
    Sample sample{simulation.time(), simulation.grabbing(), glm::dvec3(0.0), simulation.grabTarget(),
                  simulation.handForce(), glm::dvec3(0.0), simulation.metrics().height, lowest, 0.0};
    sample.invertedElements = simulation.invertedElements();
    sample.bodyHeight = bodyHigh - bodyLow;
    if (bulk) {
      sample.body = centreOfMass(simulation);
      if (sample.grabbing) sample.grabbed = simulation.grabbedPoint();
      for (std::uint32_t i : simulation.grabbedIndices()) sample.grabbedMass += 1.0 / simulation.bulkBody().freeInverseMasses[i];
      sample.contactMomentum = simulation.adhesion().momentumTaken();
      sample.contactDisplacement = simulation.adhesion().displacementTaken();
    } else {
      sample.body = centroid(simulation.positions());
      if (sample.grabbing) sample.grabbed = centroid(simulation.positions(), &simulation.grabbedIndices());
    }
    result.samples.push_back(sample);
  }
  result.final = simulation.metrics();
  result.rollbacks = simulation.divergences().size();
  for (const DivergenceEvent& e : simulation.divergences()) {
    result.nanReported |= e.what.find("NaN") != std::string::npos;
    result.divergences += std::to_string(e.time) + " s: " + e.what + "\n";
  }
  return result;
}

// The last sample at or before t (the samples are in time order; after a rollback time repeats, and
// the latest pass through t is the one that counts).
inline const Sample& at(const TortureResult& run, double t) {
  const Sample* found = &run.samples.front();
  for (const Sample& s : run.samples)
    if (s.time <= t + 1e-9) found = &s;
  return *found;
}

// The first and the last sample of the grab that starts at `from` (the player fires it before the
// step that starts at `from`).
inline const Sample& firstGrabbed(const TortureResult& run, double from) {
  for (const Sample& s : run.samples)
    if (s.time > from && s.grabbing) return s;
  return run.samples.back();
}

inline const Sample& lastGrabbed(const TortureResult& run, double from) {
  const Sample* last = &firstGrabbed(run, from);
  for (const Sample* s = last; s != run.samples.data() + run.samples.size() && s->grabbing; ++s) last = s;
  return *last;
}

inline double largestHeight(const TortureResult& run, double from, double to) {
  double largest = 0.0;
  for (const Sample& s : run.samples)
    if (s.time >= from && s.time <= to) largest = std::max(largest, s.height);
  return largest;
}

inline double smallestBodyHeight(const TortureResult& run, double from, double to) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Sample& s : run.samples)
    if (s.time >= from && s.time <= to) smallest = std::min(smallest, s.bodyHeight);
  return smallest;
}

inline double smallestHeight(const TortureResult& run, double from, double to) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Sample& s : run.samples)
    if (s.time >= from && s.time <= to) smallest = std::min(smallest, s.height);
  return smallest;
}

// The checks that the scenario's event happened, each in the scenario's own terms.
using EventCheck = std::function<void(const TortureResult& run, const TortureResult& rest)>;


struct Torture {
  const char* name;
  const char* scenario;   // tests/scenarios/<scenario>.json
  const char* overrides;  // settings besides the model, the integrator and the level
  EventCheck happened;
};

inline void expectNoNanAndAboveTheFloor(const TortureResult& run, const TortureResult& rest) {
  EXPECT_FALSE(run.nonFinite);
  EXPECT_FALSE(run.nanReported) << run.divergences;
  EXPECT_GE(run.lowestZ, 0.0);
  EXPECT_FALSE(rest.nonFinite || rest.nanReported) << rest.divergences;
}

}  // namespace slime::fixture

// The table of every setting: its dotted key, where it lives in Settings, and what values are allowed.
// One table serves the scene-file reader, `--set` overrides, scenario "set" events, validation and
// the JSON writer, so a new setting is added in exactly one place (forEachField below).
#pragma once

#include "core/settings.h"

#include <glm/vec3.hpp>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace slime {

// The allowed closed interval of a number (each component of a vector) and its unit for messages.
struct Limits {
  double min;
  double max;
  std::string_view unit;
};

// The allowed words of a string setting; empty means any text (e.g. a file path).
using Choices = std::vector<std::string_view>;

// Calls visit(key, field, limits-or-choices) for every setting of `settings`, in a fixed order.
// field is a double&, int&, bool&, std::string& or glm::dvec3&; ints and numbers get Limits,
// strings get Choices, bools get nothing (std::monostate-like `Choices{}`).
template <class Visitor, class S>
void forEachField(S& s, Visitor&& visit) {
  // Camera
  visit("camera.position", s.camera.position, Limits{-100.0, 100.0, "m"});
  visit("camera.yaw", s.camera.yaw, Limits{-360.0, 360.0, "degrees"});
  visit("camera.pitch", s.camera.pitch, Limits{-89.0, 89.0, "degrees"});
  visit("camera.fov", s.camera.fov, Limits{1.0, 170.0, "degrees"});
  visit("camera.width", s.camera.width, Limits{1, 8192, "pixels"});
  visit("camera.height", s.camera.height, Limits{1, 8192, "pixels"});
  // Light
  visit("light.position", s.light.position, Limits{-100.0, 100.0, "m"});
  visit("light.color", s.light.color, Limits{0.0, 100.0, "linear RGB intensity"});
  visit("light.ambient", s.light.ambient, Limits{0.0, 10.0, "linear RGB intensity"});
  // Floor
  visit("floor.pattern", s.floor.pattern, Choices{"planks", "tiles", "checker", "image"});
  visit("floor.scale", s.floor.scale, Limits{0.001, 100.0, "m"});
  visit("floor.colorA", s.floor.colorA, Limits{0.0, 1.0, "linear RGB"});
  visit("floor.colorB", s.floor.colorB, Limits{0.0, 1.0, "linear RGB"});
  visit("floor.image", s.floor.image, Choices{});
  visit("floor.diffuse", s.floor.diffuse, Limits{0.0, 1.0, ""});
  visit("floor.specular", s.floor.specular, Limits{0.0, 1.0, ""});
  // Slime: shape and physics
  visit("slime.shape", s.slime.shape, Choices{"mesh", "sphere"});
  visit("slime.model", s.slime.model, Choices{"bulk", "membrane"});
  visit("slime.radius", s.slime.radius, Limits{0.005, 1.0, "m"});
  visit("slime.level", s.slime.level, Limits{0, 7, "subdivision level"});
  visit("slime.resolution", s.slime.resolution, Limits{1, 4, "body shell level"});
  visit("slime.autoLevel", s.slime.autoLevel, Choices{});
  // Mass and stiffness are bounded so that the stiffest, lightest slime still keeps its volume within
  // 1 % and costs at most ~100 substeps per 10 ms step (the step count grows as sqrt(k/m)).
  visit("slime.mass", s.slime.mass, Limits{0.01, 100.0, "kg"});
  visit("slime.stiffness", s.slime.stiffness, Limits{1.0, 1000.0, "N/m"});
  visit("slime.damping", s.slime.damping, Limits{0.0, 100.0, "N·s/m"});
  visit("slime.pressure", s.slime.pressure, Limits{0.0, 100.0, "relative"});
  visit("slime.friction", s.slime.friction, Limits{0.0, 10.0, "Coulomb coefficient"});
  visit("slime.rolling", s.slime.rolling, Limits{0.0, 1000.0, "1/s"});
  // The bulk material: moduli from a soft jelly to a stiff rubber; τ from a fast to a near-solid gel.
  visit("slime.modulus", s.slime.modulus, Limits{50.0, 1.0e5, "Pa"});
  visit("slime.longTerm", s.slime.longTerm, Limits{0.01, 1.0, "of the modulus"});
  visit("slime.relaxation", s.slime.relaxation, Limits{0.01, 1000.0, "s"});
  visit("slime.poisson", s.slime.poisson, Limits{0.0, 0.49, ""});
  visit("slime.viscosity", s.slime.viscosity, Limits{0.0, 100.0, "Pa·s"});
  visit("slime.position", s.slime.position, Limits{-100.0, 100.0, "m"});
  // Slime: optics
  visit("slime.color", s.slime.color, Limits{0.0, 1.0, "linear RGB"});
  visit("slime.transmission", s.slime.transmission, Limits{0.0, 1.0, ""});
  visit("slime.absorption", s.slime.absorption, Limits{0.0, 10000.0, "1/m"});
  visit("slime.ior", s.slime.ior, Limits{1.0, 3.0, ""});
  visit("slime.specular", s.slime.specular, Limits{0.0, 1.0, ""});
  visit("slime.diffuse", s.slime.diffuse, Limits{0.0, 1.0, ""});
  visit("slime.ambient", s.slime.ambient, Limits{0.0, 1.0, ""});
  visit("slime.shininess", s.slime.shininess, Limits{1.0, 10000.0, "Phong exponent"});
  // Render
  visit("render.depth", s.render.depth, Limits{1, 16, "bounces"});
  visit("render.spp", s.render.spp, Limits{1, 64, "samples per pixel"});
  visit("render.threads", s.render.threads, Limits{0, 256, "threads (0 = all cores)"});
  visit("render.normals", s.render.normals, Choices{"smooth", "flat"});
  visit("render.optics", s.render.optics, Choices{"fresnel", "seed"});
  visit("render.backend", s.render.backend, Choices{"embree", "brute"});
  visit("render.scale", s.render.scale, Limits{0.1, 1.0, "of the window size"});
  visit("render.shadows", s.render.shadows, Choices{});
  // Simulation
  visit("sim.dt", s.sim.dt, Limits{1e-6, 0.01, "s"});
  visit("sim.integrator", s.sim.integrator,
        Choices{"explicit_euler", "symplectic_euler", "rk4", "implicit_euler", "xpbd"});
  visit("sim.substeps", s.sim.substeps, Limits{1, 1000, "substeps"});
  visit("sim.gravity", s.sim.gravity, Limits{0.0, 100.0, "m/s^2"});
  visit("sim.timeScale", s.sim.timeScale, Limits{0.01, 10.0, "simulated s per wall s"});
  visit("sim.paused", s.sim.paused, Choices{});
}

}  // namespace slime

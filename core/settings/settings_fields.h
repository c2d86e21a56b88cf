// The table of every setting: its dotted key, where it lives in Settings, and what values are allowed.
// One table serves the scene-file reader, `--set` overrides, scenario "set" events, validation and
// the JSON writer, so a new setting is added in exactly one place (forEachField below).
#pragma once

#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <initializer_list>
#include <string>
#include <string_view>
#include <type_traits>
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

// Calls visit(key, field, limits-or-choices, help) for every setting of `settings`, in a fixed order.
// field is a double&, int&, bool&, std::string& or glm::dvec3&; ints and numbers get Limits,
// strings get Choices, bools get nothing (std::monostate-like `Choices{}`). help is the setting's
// one-line meaning (`slime settings`, the viewer's tooltips); visitors that take three arguments get
// no help, and a line of the table without one passes an empty help (settings_test flags it).
template <class Visitor, class S>
void forEachField(S& s, Visitor&& visitor) {
  const auto visit = [&visitor](std::string_view key, auto& field, const auto& allowed, std::string_view help = {}) {
    if constexpr (std::is_invocable_v<Visitor&, std::string_view, decltype(field), decltype(allowed), std::string_view>)
      visitor(key, field, allowed, help);
    else
      visitor(key, field, allowed);
  };
  // Camera
  visit("camera.position", s.camera.position, Limits{-100.0, 100.0, "m"}, "eye position");
  visit("camera.yaw", s.camera.yaw, Limits{-360.0, 360.0, "degrees"},
        "heading: 0 looks along +x, 90 along +y");
  visit("camera.pitch", s.camera.pitch, Limits{-89.0, 89.0, "degrees"}, "elevation: positive looks up");
  visit("camera.fov", s.camera.fov, Limits{1.0, 170.0, "degrees"}, "vertical field of view");
  visit("camera.width", s.camera.width, Limits{1, 8192, "pixels"}, "image width (the viewer: its window's)");
  visit("camera.height", s.camera.height, Limits{1, 8192, "pixels"},
        "image height (the viewer: its window's)");
  // Light
  visit("light.position", s.light.position, Limits{-100.0, 100.0, "m"}, "position of the point light");
  visit("light.color", s.light.color, Limits{0.0, 100.0, "linear RGB intensity"},
        "intensity I_l of the point light per channel");
  visit("light.ambient", s.light.ambient, Limits{0.0, 10.0, "linear RGB intensity"},
        "ambient intensity I_a per channel");
  // Floor
  visit("floor.pattern", s.floor.pattern, Choices{"planks", "tiles", "checker", "image"},
        "the floor's texture");
  visit("floor.scale", s.floor.scale, Limits{0.001, 100.0, "m"},
        "size of one tile, plank width or checker cell");
  visit("floor.colorA", s.floor.colorA, Limits{0.0, 1.0, "linear RGB"}, "first colour of the pattern");
  visit("floor.colorB", s.floor.colorB, Limits{0.0, 1.0, "linear RGB"}, "second colour of the pattern");
  visit("floor.image", s.floor.image, Choices{}, "PNG file used when floor.pattern is image");
  visit("floor.diffuse", s.floor.diffuse, Limits{0.0, 1.0, ""}, "k_d of the floor");
  visit("floor.specular", s.floor.specular, Limits{0.0, 1.0, ""},
        "k_s of the floor: highlight and mirror image (0 = matte)");
  // Slime: shape and physics
  visit("slime.shape", s.slime.shape, Choices{"mesh", "sphere"},
        "mesh (the simulated icosphere) or sphere (analytic reference)");
  visit("slime.model", s.slime.model, Choices{"bulk", "membrane"},
        "bulk (viscoelastic tetrahedral body) or membrane (the seed's skin of springs around a fill)");
  visit("slime.radius", s.slime.radius, Limits{0.005, 1.0, "m"}, "rest radius of the ball");
  visit("slime.level", s.slime.level, Limits{0, 7, "subdivision level"},
        "drawn icosphere subdivision level: 20*4^level faces (or auto); 7 is not real time on 2 cores "
        "(about 2 frames a second)");
  visit("slime.resolution", s.slime.resolution, Limits{1, 4, "body shell level"},
        "bulk: the simulated body's shell level (85, 487, 3,211 or 23,059 mass points); 3 and 4 are "
        "slower than real time on one core of an AMD family 23 (the viewer's Stats say how much)");
  visit("slime.autoLevel", s.slime.autoLevel, Choices{},
        "pick the smallest level whose image error is invisible");
  // Mass and stiffness are bounded so that the stiffest, lightest slime still keeps its volume within
  // 1 % and costs at most ~100 substeps per 10 ms step (the step count grows as sqrt(k/m)).
  visit("slime.mass", s.slime.mass, Limits{0.01, 100.0, "kg"}, "total mass");
  visit("slime.stiffness", s.slime.stiffness, Limits{1.0, 1000.0, "N/m"},
        "membrane: elementary spring stiffness k_e (longer springs are softer)");
  visit("slime.damping", s.slime.damping, Limits{0.0, 100.0, "N·s/m"},
        "membrane: damper coefficient k_d along each spring");
  visit("slime.pressure", s.slime.pressure, Limits{0.0, 100.0, "relative"},
        "membrane: volume preservation strength (0 = none)");
  visit("slime.friction", s.slime.friction, Limits{0.0, 10.0, "Coulomb coefficient"},
        "Coulomb friction coefficient against the floor");
  visit("slime.rolling", s.slime.rolling, Limits{0.0, 1000.0, "1/s"},
        "membrane: rate at which the slime's rolling decays on the floor");
  visit("slime.adhesion", s.slime.adhesion, Limits{0.0, 1.0e4, "Pa"},
        "bulk: tension the floor contact holds before it peels (a sticky table; 0 = none)");
  visit("slime.selfContact", s.slime.selfContact, Choices{},
        "bulk: the slime does not pass through itself or another piece (a fold, a stack; off: it does)");
  // Touching pieces must part before the material tears (docs/physics.md, self-contact): the cling is
  // bounded by the largest shear modulus and defaults to a quarter of the default one.
  visit("slime.cling", s.slime.cling, Limits{0.0, 1.0e4, "Pa"},
        "bulk: tension touching surfaces hold before they peel, as the sticky floor's (0 = none)");
  // The bulk material: moduli from a soft jelly to a stiff rubber; τ from a fast to a near-solid gel.
  visit("slime.modulus", s.slime.modulus, Limits{50.0, 1.0e5, "Pa"},
        "bulk: instantaneous shear modulus G (the seed's stiffness slider)");
  visit("slime.longTerm", s.slime.longTerm, Limits{0.01, 1.0, "of the modulus"},
        "bulk: the part of G that never relaxes and brings the ball back (1 = purely elastic)");
  visit("slime.relaxation", s.slime.relaxation, Limits{0.01, 1000.0, "s"},
        "bulk: relaxation time of the flowing (Maxwell) part");
  visit("slime.plastic", s.slime.plastic, Choices{},
        "bulk: the long-term rest shape flows while stretched past slime.yieldStretch, so strands neck and draw "
        "out (off: it never flows)");
  visit("slime.yieldStretch", s.slime.yieldStretch, Limits{1.1, 10.0, "stretch"},
        "bulk: elastic stretch of the long-term part past which its rest shape flows (a 2 cm press is about 1.5)");
  visit("slime.flowTime", s.slime.flowTime, Limits{0.01, 1000.0, "s"},
        "bulk: time of the rest shape's flow past the yield (its viscosity is the long-term modulus times this)");
  visit("slime.recoveryTime", s.slime.recoveryTime, Limits{0.0, 1000.0, "s (0 = never)"},
        "bulk: time in which a flowed rest shape returns to the ball while below the yield");
  visit("slime.damage", s.slime.damage, Choices{},
        "bulk, with slime.plastic: a strand drawn past slime.damageStretch softens where it has flowed most, necks "
        "there and, with slime.tearing, snaps (off: it never softens)");
  visit("slime.damageStretch", s.slime.damageStretch, Limits{1.1, 100.0, "stretch"},
        "bulk: the flowed (plastic) stretch at which the long-term part starts to break; broken through at twice it");
  visit("slime.poisson", s.slime.poisson, Limits{0.0, 0.49, ""},
        "bulk: Poisson ratio of each element (the whole body keeps its volume anyway)");
  visit("slime.viscosity", s.slime.viscosity, Limits{0.0, 100.0, "Pa·s"},
        "bulk: viscosity of the dampers along the body's edges (the seed's damping slider)");
  // Tearing and merging (core/simulation/tearing.h, merging.h): bounded so that a check stays cheap.
  visit("slime.tearing", s.slime.tearing, Choices{},
        "bulk: strands snap and pieces tear off once stretched past slime.tearStretch (off: always one piece)");
  visit("slime.tearStretch", s.slime.tearStretch, Limits{1.2, 20.0, "stretch ratio"},
        "bulk: the elastic (not yet flowed) stretch at which the slime tears; a slow pull flows first and tears later");
  visit("slime.smallestPiece", s.slime.smallestPiece, Limits{0.005, 0.5, "of the slime's volume"},
        "bulk: a torn part smaller than this stays joined");
  visit("slime.maxPieces", s.slime.maxPieces, Limits{1, 32, "pieces"}, "bulk: no tear past this many pieces");
  visit("slime.mergeTime", s.slime.mergeTime, Limits{0.0, 100.0, "s"},
        "bulk: how long two pieces stay pressed together before they fuse into one (0 = never)");
  visit("slime.position", s.slime.position, Limits{-100.0, 100.0, "m"}, "start position of the centre");
  // Slime: optics
  visit("slime.color", s.slime.color, Limits{0.0, 1.0, "linear RGB"},
        "surface tint and per-channel transmittance");
  visit("slime.transmission", s.slime.transmission, Limits{0.0, 1.0, ""}, "k_t: weight of the refracted ray");
  visit("slime.absorption", s.slime.absorption, Limits{0.0, 10000.0, "1/m"},
        "Beer-Lambert k: a path of 1/k transmits exactly slime.color");
  visit("slime.ior", s.slime.ior, Limits{1.0, 3.0, ""}, "index of refraction");
  visit("slime.specular", s.slime.specular, Limits{0.0, 1.0, ""},
        "k_s: Phong highlight and reflected-ray weight");
  visit("slime.diffuse", s.slime.diffuse, Limits{0.0, 1.0, ""}, "k_d: diffuse reflection");
  visit("slime.ambient", s.slime.ambient, Limits{0.0, 1.0, ""}, "k_a: ambient reflection");
  visit("slime.shininess", s.slime.shininess, Limits{1.0, 10000.0, "Phong exponent"}, "Phong exponent n");
  // Render
  visit("render.depth", s.render.depth, Limits{1, 64, "ray segments"},
        "the most ray segments a path has (1 = primary rays only); a path stops sooner once the light it can "
        "still bring could not change an 8-bit sRGB pixel");
  visit("render.movingDepth", s.render.movingDepth, Limits{1, 64, "ray segments"},
        "viewer, while things move (the checkerboard's frames): render.depth's cap for those frames; a path totally "
        "reflected inside the jelly at the cap takes the floor or sky along its reflection");
  visit("render.spp", s.render.spp, Limits{1, 64, "samples per pixel"},
        "samples per pixel: a stratified n x n grid (1, 4, 9, ..., 64)");
  visit("render.threads", s.render.threads, Limits{0, 256, "threads (0 = all cores)"},
        "worker threads for TBB and Embree");
  visit("render.normals", s.render.normals, Choices{"smooth", "flat"}, "shading normals");
  visit("render.optics", s.render.optics, Choices{"fresnel", "seed"},
        "fresnel (dielectric) or seed (constant k_s, k_t weights)");
  visit("render.shading", s.render.shading, Choices{"classic", "physical"},
        "classic (the seed's ambient, diffuse and Phong terms on the jelly) or physical (Fresnel reflection and "
        "refraction only; colour and k_t become absorption per metre; implies render.optics=fresnel)");
  visit("render.backend", s.render.backend, Choices{"embree", "brute"},
        "embree, or brute (the seed's algorithm, the oracle)");
  visit("render.scale", s.render.scale, Limits{0.1, 1.0, "of the window size"},
        "resolution of the viewer's traced image");
  visit("render.shadows", s.render.shadows, Choices{}, "trace shadow rays to the point light");
  visit("render.caustics", s.render.caustics, Choices{},
        "caustics: light focused through the slime onto the floor, traced as photons from the light");
  visit("render.photons", s.render.photons, Limits{1000, 10000000, "photons per frame"},
        "caustic photons per frame of a still image (16 such frames gather the finished map a snapshot draws); "
        "half as many per frame while the slime or the light moves");
  visit("render.checkerboard", s.render.checkerboard, Choices{},
        "viewer, while things move: trace every other pixel of the slime's footprint, fill in the rest from "
        "their neighbours (tracing those where they disagree)");
  visit("render.checkerboardQuarter", s.render.checkerboardQuarter, Choices{},
        "with render.checkerboard: trace every other row of the checkerboard's colour only (a quarter of the "
        "footprint), fill the colour's other rows from their diagonal neighbours, then the rest as before");
  visit("render.checkerboardSixteenth", s.render.checkerboardSixteenth, Choices{},
        "with render.checkerboardQuarter: trace one pixel of each 4 x 4 block of the footprint, fill the quarter's "
        "lattice from neighbours two pixels away (diagonal, then beside), then the rest as the quarter does");
  visit("render.targetFps", s.render.targetFps, Limits{0.0, 240.0, "frames per second"},
        "viewer: trace the image smaller while moving frames miss this rate (0: always full resolution)");
  visit("render.orbitFps", s.render.orbitFps, Limits{0.0, 240.0, "frames per second"},
        "viewer: while the camera moves (every pixel changes), trace the image smaller when frames miss this rate; "
        "full resolution again the frame the camera stops (0: always full resolution)");
  // Simulation
  visit("sim.dt", s.sim.dt, Limits{1e-6, 0.02, "s"}, "fixed time step (up to 20 ms: 60 Hz and slower for the implicit steps)");
  visit("sim.integrator", s.sim.integrator,
        Choices{"auto", "explicit_euler", "symplectic_euler", "rk4", "implicit_euler", "xpbd", "projective",
                "projective_midpoint"},
        "time integrator (auto: symplectic_euler, or projective for a bulk slime whose slowest jiggle is over 30 Hz, "
        "too fast for 60 frames a second to show; projective_midpoint: the implicit midpoint rule on projective's "
        "factorisation, its jiggle kept at long steps, with the sticky floor)");
  visit("sim.substeps", s.sim.substeps, Limits{1, 1000, "substeps"},
        "substeps per step (xpbd, projective, projective_midpoint)");
  visit("sim.iterations", s.sim.iterations, Limits{1, 100, "iterations"},
        "projective, projective_midpoint: local/global iterations per substep (more: closer to the implicit step, "
        "more cost)");
  visit("sim.gravity", s.sim.gravity, Limits{0.0, 100.0, "m/s^2"}, "|g|, pointing along -z");
  // 16 N (1.6 kg-force) a hand: a child's firm pull on a toy held in both hands, well under what a
  // child's grip holds (grip strength 100-200 N at 6-10 years); a default slime's strand needs
  // G∞·A₀·(λ − λ⁻²) ≈ 12 N a hand at 5× (docs/physics.md, "Long strands"), which 10 N (a pinch's) missed.
  visit("sim.handForce", s.sim.handForce, Limits{1.0, 100.0, "N"},
        "bulk: the most force each hand (grab) pulls with, about a child's firm two-handed pull (16 N); "
        "the spring to its patch is scaled down beyond it");
  visit("sim.timeScale", s.sim.timeScale, Limits{0.01, 10.0, "simulated s per wall s"},
        "viewer: simulated seconds per wall-clock second");
  visit("sim.paused", s.sim.paused, Choices{}, "viewer: physics paused");
}

}  // namespace slime

// All parameters of a Slime run in one plain struct: camera, light, floor, slime, render, sim.
// Filled from the embedded default scene (assets/default.json), then an optional scene file, then
// `--set key=value` overrides (see settings_io.h); validated once (validateSettings). Units are SI:
// metres, kilograms, seconds; angles in degrees; colours linear RGB in [0, 1].
#pragma once

#include <glm/vec3.hpp>

#include <string>

namespace slime {

struct CameraSettings {
  glm::dvec3 position{0.0, -0.22, 0.10};  // eye position, m
  double yaw = 90.0;     // heading in degrees: 0 looks along +x, 90 along +y (counter-clockwise about +z)
  double pitch = -20.0;  // elevation in degrees: positive looks up, limited to (-90, 90)
  double fov = 45.0;     // vertical field of view, degrees
  int width = 734;       // image width in pixels
  int height = 564;      // image height in pixels
};

struct LightSettings {
  glm::dvec3 position{0.30, -0.05, 0.35}; // point light position, m (low: a long, visible shadow)
  glm::dvec3 color{1.0, 1.0, 1.0};        // point light intensity I_l per channel
  glm::dvec3 ambient{0.25, 0.25, 0.28};   // ambient intensity I_a per channel
};

struct FloorSettings {
  std::string pattern = "planks";          // tiles | planks | checker | image
  double scale = 0.10;                     // size of one tile / plank width / checker cell, m
  glm::dvec3 colorA{0.52, 0.30, 0.13};     // first pattern colour (linear RGB)
  glm::dvec3 colorB{0.34, 0.18, 0.07};     // second pattern colour (linear RGB)
  std::string image;                       // PNG path when pattern == "image"
  double diffuse = 0.8;                    // k_d of the floor
  double specular = 0.0;                   // k_s of the floor: its highlight and mirror image (0: matte, no rays)
};

struct SlimeSettings {
  std::string shape = "mesh";            // mesh (the simulated icosphere) | sphere (analytic reference)
  std::string model = "bulk";            // bulk (viscoelastic tetrahedral body) | membrane (the seed's skin)
  double radius = 0.04;                  // rest radius, m
  int level = 4;                         // drawn icosphere subdivision level 0..7: 20*4^level faces
  int resolution = 2;                    // bulk: the simulated body's shell level 1..4 (tet_mesh.h)
  bool autoLevel = false;                // slime.level=auto: smallest level whose image error is invisible
  double mass = 0.268;                   // total mass, kg (≈ 1000 kg/m^3 at radius 4 cm)
  double stiffness = 100.0;              // membrane: spring stiffness k_e, N/m (series rule k = k_e d_e / d)
  double damping = 0.1;                  // membrane: damper coefficient k_d along each spring, N·s/m
  double pressure = 3.0;                 // membrane: volume preservation strength, relative (0 = none)
  double friction = 0.6;                 // Coulomb friction coefficient against the floor
  double rolling = 5.0;                  // rolling resistance: 1/s at which the turning decays on the floor
  double adhesion = 8000.0;              // bulk: tension the floor contact holds before it peels, Pa (0 = none)
  bool selfContact = false;              // bulk: the drawn surface does not pass through itself or another piece
  double cling = 300.0;                  // bulk: tension touching surfaces hold before they peel, Pa (0 = none)
  double modulus = 1200.0;               // bulk: instantaneous shear modulus G = μ∞ + μ1, Pa (the seed's stiffness)
  double longTerm = 0.4;                 // bulk: μ∞ / G, the part of the modulus that never relaxes
  double relaxation = 0.6;               // bulk: relaxation time τ of the Maxwell branch, s
  bool plastic = false;                  // bulk: the long-term branch's rest shape flows past the yield
  double yieldStretch = 1.8;             // bulk: its yield, an isochoric uniaxial elastic stretch
  double flowTime = 0.6;                 // bulk: τ_p of that flow, s (viscosity μ∞ τ_p)
  double recoveryTime = 1.0;             // bulk: τ_r of the rest shape's return below the yield, s (0 = never)
  bool damage = false;                   // bulk: a flowed strand's crosslinks break: it softens, necks and snaps
  double damageStretch = 3.0;            // bulk: the flowed stretch at which that starts (broken through at twice it)
  double poisson = 0.4;                  // bulk: Poisson ratio ν of each element
  double viscosity = 30.0;               // bulk: viscosity η of the edge dampers, Pa·s (the seed's damping)
  bool tearing = false;                  // bulk: strands snap and pieces tear off past tearStretch (off: one piece, as before)
  double tearStretch = 2.5;              // bulk: the elastic (not yet flowed) stretch at which the slime tears
  double smallestPiece = 0.03;           // bulk: the least share of the slime's volume a torn-off piece holds
  int maxPieces = 8;                     // bulk: no tear past this many pieces
  double mergeTime = 0.3;                // bulk: s two pieces stay touching before they fuse into one (0 = never)
  glm::dvec3 position{0.0, 0.0, 0.10};   // start position of the centre, m
  glm::dvec3 color{0.25, 0.85, 0.35};    // slime colour: surface tint and per-channel transmittance
  double transmission = 0.7;             // k_t: weight of the refracted ray
  double absorption = 20.0;              // Beer–Lambert k, 1/m: a path of 1/k transmits exactly `color`
  double ior = 1.35;                     // index of refraction
  double specular = 0.4;                 // k_s: Phong highlight and reflected-ray weight
  double diffuse = 0.3;                  // k_d
  double ambient = 0.1;                  // k_a
  double shininess = 80.0;               // Phong exponent n
};

struct RenderSettings {
  int depth = 3;                     // the most ray segments a path has (1 = primary rays only); it stops
                                     // sooner once what it carries could not change an 8-bit pixel
  int movingDepth = 3;               // viewer, while things move (checkerboard frames): the cap on a path's segments
  int spp = 1;                       // samples per pixel (1, 4, 9, 16: a stratified n×n grid)
  int threads = 0;                   // worker threads for TBB and Embree, 0 = all cores
  std::string normals = "smooth";    // smooth | flat shading normals
  std::string optics = "fresnel";    // fresnel (dielectric) | seed (constant k_s / k_t weights)
  std::string shading = "classic";   // classic (the seed's Phong terms on the jelly) | physical (Fresnel and absorption only)
  std::string backend = "embree";    // embree | brute (the seed's algorithm, the oracle)
  double scale = 1.0;                // resolution scale of the viewer's traced image (0.1..1)
  double targetFps = 0.0;            // viewer: the frame rate its adaptive resolution aims for, 0 = off
  double orbitFps = 30.0;            // viewer: the same while the camera moves (every pixel changes), 0 = off
  bool shadows = true;               // trace shadow rays to the point light
  bool caustics = true;              // light focused through the slime onto the floor (photons, render/caustics/)
  int photons = 10000;               // photons shot per frame while the slime or the light moves
  bool checkerboard = true;          // viewer, while moving: half the slime's footprint traced, the rest filled in
  bool checkerboardQuarter = true;   // with checkerboard: a quarter traced, the rest filled in two passes
  bool checkerboardSixteenth = true; // with checkerboardQuarter: one pixel in 4 × 4 traced, the rest filled in four passes
};

struct SimSettings {
  double dt = 0.001;                       // fixed time step, s
  std::string integrator = "auto";  // auto (integrator_choice.h) | explicit_euler | symplectic_euler | rk4 | implicit_euler | xpbd | projective
  int substeps = 1;                        // substeps per step (xpbd, projective)
  int iterations = 1;                      // projective: local/global iterations per substep
  double gravity = 9.81;                   // |g|, m/s^2, pointing along -z
  double handForce = 16.0;                 // bulk: the most force each hand pulls with, N (a child's firm two-handed pull)
  double timeScale = 1.0;                  // simulated seconds per wall-clock second in the viewer
  bool paused = false;                     // viewer: physics paused
};

struct Settings {
  CameraSettings camera;
  LightSettings light;
  FloorSettings floor;
  SlimeSettings slime;
  RenderSettings render;
  SimSettings sim;
};

}  // namespace slime

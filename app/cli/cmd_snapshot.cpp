// `slime snapshot`: settle the slime, trace one frame, write it as a PNG, report time and rays.
#include "app/bench/render/reference_scene.h"
#include "app/cli/commands.h"
#include "app/cli/snapshot.h"
#include "app/viewer/ui_snapshot.h"
#include "core/export/mesh_exporter.h"
#include "core/geometry/camera.h"
#include "core/settings/settings_io.h"
#include "render/image/image_io.h"

#include <cstdio>
#include <memory>
#include <optional>

namespace slime {
namespace {

struct SnapshotOptions {
  SceneOptions scene;
  std::string output;
  std::string size;
  double settle = -1.0;
  std::vector<double> viewPoint, viewTarget;
  std::optional<double> fov;
  bool ui = false;  // --ui: the whole viewer, panels included, drawn headless (app/viewer/ui_snapshot.h)
  std::string gl = "auto";  // --gl: which library draws it headless
  std::string exportMesh;   // --export-mesh: the frame's surface as .ply, .obj or .glb
  std::string objUp;        // --obj-up y|z: an .obj's axes (empty: y, OBJ's convention)
  std::string linear;       // --linear: the frame's linear floats as a PFM
  std::string referenceScene;  // --reference-scene: the scene for a path tracer (scripts/reference/)
};

void runSnapshot(const SnapshotOptions& options) {
  const HeadlessApi api = headlessApiNamed(options.gl);
  if (!options.exportMesh.empty()) checkMeshPath(options.exportMesh);  // a bad path fails before the work
  const UpAxis objUp = checkObjUp(options.objUp, options.exportMesh);
  Settings settings = loadSettings(options.scene);
  if (!options.size.empty()) applyImageSize(settings, options.size);
  if (options.fov) {
    if (!(*options.fov > 1.0 && *options.fov < 179.0))
      throw SettingsError("--fov must be in (1, 179) degrees, got " + std::to_string(*options.fov));
    settings.camera.fov = *options.fov;
  }
  if (!options.viewPoint.empty()) settings.camera.position = {options.viewPoint[0], options.viewPoint[1], options.viewPoint[2]};
  if (!options.viewTarget.empty()) {
    const glm::dvec3 target{options.viewTarget[0], options.viewTarget[1], options.viewTarget[2]};
    if (target == settings.camera.position) throw SettingsError("--look-at (--vi) must differ from the eye position");
    lookAt(settings.camera, settings.camera.position, target);
  }
  validateSettings(settings);
  if (options.ui && (!options.linear.empty() || !options.referenceScene.empty()))
    throw SettingsError("--linear and --reference-scene write the traced frame's scene, not the viewer's (drop --ui)");

  if (options.ui) {
    writeUiSnapshot(settings, options.output, [&](Simulation& simulation) {
      settleForSnapshot(simulation, settings, options.settle, options.scene.scenarioFile);
      if (!options.exportMesh.empty())
        writeSurfaceMesh(options.exportMesh,
                         surfaceMeshOf(simulation.time(), simulation.surfaces()),
                         exportMaterialOf(simulation.settings().slime), objUp);
    }, api);
    if (!options.exportMesh.empty()) std::printf("wrote %s (the frame's surface)\n", options.exportMesh.c_str());
    std::printf("wrote %s (%dx%d, viewer with panels)\n", options.output.c_str(), settings.camera.width,
                settings.camera.height);
    return;
  }
  const SnapshotResult snapshot = takeSnapshot(settings, options.settle, options.scene.scenarioFile);
  writePng(snapshot.image, options.output);
  if (!options.linear.empty()) {
    writePfm(snapshot.image, options.linear);
    std::printf("wrote %s (linear floats)\n", options.linear.c_str());
  }
  if (!options.referenceScene.empty()) {
    writeReferenceScene(options.referenceScene, settings);
    std::printf("wrote %s/scene.json and the floor's tiles\n", options.referenceScene.c_str());
  }
  if (!options.exportMesh.empty()) {
    writeSurfaceMesh(options.exportMesh, snapshot.surface, exportMaterialOf(snapshot.slime), objUp);
    std::printf("wrote %s (the frame's surface: %zu vertices, %zu triangles)\n", options.exportMesh.c_str(),
                snapshot.surface.positions.size(), snapshot.surface.triangles.size());
  }
  const RayCounts& rays = snapshot.stats.rays;
  std::printf("wrote %s (%dx%d) after %.3f s simulated\n", options.output.c_str(), snapshot.image.width,
              snapshot.image.height, snapshot.simulatedSeconds);
  const SlimeMetrics& m = snapshot.metrics;
  std::printf("slime: height %.4f m, width %.4f m, min z %.2e m, max speed %.2e m/s, volume %.4f, rollbacks %zu\n",
              m.height, m.width, m.minZ, m.maxSpeed, m.volumeRatio, snapshot.divergences);
  std::printf("render %.2f ms (refit %.3f ms)\n", snapshot.stats.traceMs, snapshot.stats.refitMs);
  if (snapshot.stats.causticPhotons > 0)
    std::printf("caustics %.2f ms of it (%llu photons)\n", snapshot.stats.causticsMs,
                static_cast<unsigned long long>(snapshot.stats.causticPhotons));
  std::printf("rays %llu: primary %llu, shadow %llu, reflection %llu, refraction %llu; slime queries %llu\n",
              static_cast<unsigned long long>(rays.total()), static_cast<unsigned long long>(rays.primary),
              static_cast<unsigned long long>(rays.shadow), static_cast<unsigned long long>(rays.reflection),
              static_cast<unsigned long long>(rays.refraction),
              static_cast<unsigned long long>(snapshot.stats.slimeQueries));
}

}  // namespace

void registerSnapshotCommand(CLI::App& root, int& exitCode) {
  auto options = std::make_shared<SnapshotOptions>();
  auto* command = root.add_subcommand("snapshot", "Settle the slime, ray-trace one frame and write it as a PNG");
  command->add_option("-o,--output", options->output, "PNG file to write")->required();
  command->add_option("--size", options->size, "Image size WxH in pixels (each 1..8192), default camera.width x camera.height");
  command->add_option("--settle", options->settle, "Seconds to simulate before the frame (default: until the slime rests, at most 3 s)")
      ->check(CLI::Range(0.0, 600.0));
  command->add_option("--eye,--vp", options->viewPoint, "Eye position x y z, m")->expected(3);
  command->add_option("--look-at,--vi", options->viewTarget, "Point to look at x y z, m (sets yaw and pitch)")->expected(3);
  command->add_option("--fov", options->fov, "Vertical field of view, degrees");
  auto* ui = command->add_flag("--ui", options->ui, "Draw the whole viewer (image and panels) headless");
  command->add_option("--gl", options->gl,
                      "With --ui, the headless GL: egl, osmesa, or auto (EGL, else OSMesa; the default)")
      ->needs(ui);
  command->add_option("--export-mesh", options->exportMesh,
                      "Also write the frame's slime surface: .ply (binary), .obj (with a .mtl) or .glb, by the "
                      "extension; the .obj and .glb carry the slime's material");
  command->add_option("--obj-up", options->objUp,
                      "Up axis of an exported .obj: y (OBJ's convention, the default) or z (the simulation's)");
  command->add_option("--linear", options->linear,
                      "Also write the frame's linear RGB floats, unclamped, as a PFM (scripts/reference/ compares them)");
  command->add_option("--reference-scene", options->referenceScene,
                      "Also write DIR/scene.json and the floor's albedo tiles: the scene for a path tracer "
                      "(scripts/reference/render.sh)");
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] {
    runSnapshot(*options);
    exitCode = 0;
  });
}

}  // namespace slime

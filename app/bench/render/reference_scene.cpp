#include "app/bench/render/reference_scene.h"

#include "core/geometry/camera.h"
#include "core/settings/file_output.h"
#include "render/floor/floor_texture.h"
#include "render/image/image_io.h"
#include "render/trace/shading_parameters.h"

#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <filesystem>

namespace slime {
namespace {

nlohmann::json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
nlohmann::json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// A square of side `size` metres centred on (cx, cy), `texels` a side: each texel the pattern averaged
// over its own square (a box filter of the texel's width, as the renderer's footprint filter is).
nlohmann::json writeTile(const std::string& directory, const std::string& name, const FloorTexture& floor,
                         double cx, double cy, double size, int texels) {
  Image tile;
  tile.resize(texels, texels);
  const double texel = size / texels;
  const glm::vec2 footprint{static_cast<float>(0.5 * texel)};
  tbb::parallel_for(tbb::blocked_range<int>(0, texels), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row)
      for (int column = 0; column < texels; ++column) {
        // Row 0 is the tile's +y edge (an image's top row), column 0 its −x edge.
        const double x = cx - 0.5 * size + (column + 0.5) * texel, y = cy + 0.5 * size - (row + 0.5) * texel;
        tile.at(column, row) = floor.albedo({static_cast<float>(x), static_cast<float>(y)}, footprint);
      }
  });
  writePfm(tile, (std::filesystem::path(directory) / (name + ".pfm")).string());
  return {{"file", name + ".pfm"}, {"center", {cx, cy}}, {"size", size}, {"texels", texels}};
}

}  // namespace

void writeReferenceScene(const std::string& directory, const Settings& settings) {
  std::filesystem::create_directories(directory);
  const int width = settings.camera.width, height = settings.camera.height;
  const Camera camera = makeCamera(settings.camera, width, height);
  Settings physical = settings;
  physical.render.shading = "physical";
  const ShadingParameters p = makeShadingParameters(physical, height);
  const FloorTexture floor(settings.floor);

  nlohmann::json scene;
  scene["image"] = {{"width", width}, {"height", height}};
  scene["camera"] = {{"eye", vec(camera.position)}, {"forward", vec(camera.forward)}, {"right", vec(camera.right)},
                     {"up", vec(camera.up)}, {"tan_half_fov", camera.tanHalfFov}, {"aspect", camera.aspect}};
  scene["light"] = {{"position", vec(p.lightPosition)}, {"color", vec(p.lightColor)}, {"ambient", vec(p.ambientLight)},
                    {"floor_diffuse", p.floorDiffuse}, {"floor_specular", p.floorSpecular}};
  scene["sky"] = {{"horizon", vec(p.skyHorizon)}, {"zenith", vec(p.skyZenith)}, {"haze_distance", p.hazeDistance}};
  scene["slime"] = {{"ior", p.ior}, {"absorption_per_metre", vec(p.slimeAbsorption)}};
  // The tiles: 0.3 mm texels over the 0.6 m around the slime (a pixel there is 0.4–0.6 mm at 640×480),
  // 1 mm over 2 m and 16 mm over 32 m, then the pattern's mean.
  const double cx = settings.slime.position[0], cy = settings.slime.position[1];
  scene["floor"] = {{"tiles", {writeTile(directory, "floor_near", floor, cx, cy, 0.6, 2048),
                               writeTile(directory, "floor_mid", floor, cx, cy, 2.0, 2048),
                               writeTile(directory, "floor_far", floor, cx, cy, 32.0, 2048)}},
                    {"mean_albedo", vec(floor.meanAlbedo())}};
  writeFileAtomically((std::filesystem::path(directory) / "scene.json").string(), scene.dump(2) + "\n");
}

}  // namespace slime

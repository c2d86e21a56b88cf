#include "core/export/gltf_animation.h"

#include "core/export/export_material.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace slime {
namespace {

// Appends `values` to the one buffer as a view and an accessor of `type` (a glTF vec3 or scalar).
int addAccessor(tinygltf::Model& model, const std::vector<float>& values, int type, int target, bool bounds) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = values.size() * sizeof(float);
  view.target = target;
  data.resize(data.size() + view.byteLength);
  std::memcpy(data.data() + view.byteOffset, values.data(), view.byteLength);
  model.bufferViews.push_back(view);

  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = type;
  const std::size_t width = type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  accessor.count = values.size() / width;
  if (bounds) {  // required for POSITION and animation inputs
    accessor.minValues.assign(width, std::numeric_limits<double>::max());
    accessor.maxValues.assign(width, std::numeric_limits<double>::lowest());
    for (std::size_t i = 0; i < values.size(); ++i) {
      accessor.minValues[i % width] = std::min<double>(accessor.minValues[i % width], values[i]);
      accessor.maxValues[i % width] = std::max<double>(accessor.maxValues[i % width], values[i]);
    }
  }
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

std::vector<float> floats(const std::vector<glm::dvec3>& v, const std::vector<glm::dvec3>* minus = nullptr) {
  std::vector<float> out(v.size() * 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(v[i][c] - (minus ? (*minus)[i][c] : 0.0));
  return out;
}

tinygltf::Value number(double x) { return tinygltf::Value(x); }

tinygltf::Value colorValue(const glm::dvec3& color) {
  return tinygltf::Value(tinygltf::Value::Array{number(color.x), number(color.y), number(color.z)});
}

// The slime's material: a clear dielectric (metallic 0, smooth) tinted by its colour, letting
// `transmission` of the light through (KHR_materials_transmission), bending it by the renderer's IOR
// (KHR_materials_ior) and absorbing it along the way as the renderer does (KHR_materials_volume, whose
// attenuation export_material.h derives from slime.absorption). A reader that knows none of the
// extensions still draws a green, glossy ball from pbrMetallicRoughness.
void addMaterial(tinygltf::Model& model, const ExportMaterial& slime, double thickness) {
  tinygltf::Material material;
  material.name = "slime";
  material.pbrMetallicRoughness.baseColorFactor = {slime.color.x, slime.color.y, slime.color.z, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = slime.roughness;
  material.extensions["KHR_materials_transmission"] =
      tinygltf::Value(tinygltf::Value::Object{{"transmissionFactor", number(slime.transmission)}});
  material.extensions["KHR_materials_ior"] = tinygltf::Value(tinygltf::Value::Object{{"ior", number(slime.ior)}});
  tinygltf::Value::Object volume{{"thicknessFactor", number(thickness)}};
  if (slime.attenuationDistance > 0.0) {  // else the default: infinite, nothing absorbed
    volume["attenuationDistance"] = number(slime.attenuationDistance);
    volume["attenuationColor"] = colorValue(slime.attenuationColor);
  }
  material.extensions["KHR_materials_volume"] = tinygltf::Value(volume);
  model.materials.push_back(material);
  model.extensionsUsed = {"KHR_materials_ior", "KHR_materials_transmission", "KHR_materials_volume"};
}

}  // namespace

namespace {

// Frames [first, last] share one set of pieces and triangles: they animate as morph targets of one mesh.
struct Span {
  std::size_t first = 0, last = 0;
};

std::vector<Span> spansOf(const std::vector<SurfaceMesh>& frames) {
  std::vector<Span> spans{{0, 0}};
  for (std::size_t k = 1; k < frames.size(); ++k) {
    const SurfaceMesh& start = frames[spans.back().first];
    if (frames[k].triangles == start.triangles && frames[k].pieceVertexStarts == start.pieceVertexStarts &&
        frames[k].positions.size() == start.positions.size())
      spans.back().last = k;
    else
      spans.push_back({k, k});
  }
  return spans;
}

// The mesh of frames [span.first, span.last]: the first of them, and one morph target per frame (when
// there are several) holding p_k − p_first and n_k − n_first. Returns the mesh's index.
int addSpanMesh(tinygltf::Model& model, const std::vector<SurfaceMesh>& frames, const Span& span, const std::string& name) {
  const SurfaceMesh& first = frames[span.first];
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = 0;
  {  // indices: uint32, three per triangle
    std::vector<unsigned char>& data = model.buffers[0].data;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = first.triangles.size() * 3 * sizeof(std::uint32_t);
    view.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
    data.resize(data.size() + view.byteLength);
    std::memcpy(data.data() + view.byteOffset, first.triangles.data(), view.byteLength);
    model.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.type = TINYGLTF_TYPE_SCALAR;
    accessor.count = first.triangles.size() * 3;
    model.accessors.push_back(accessor);
    primitive.indices = static_cast<int>(model.accessors.size()) - 1;
  }
  static_assert(sizeof(Triangle) == 3 * sizeof(std::uint32_t));
  primitive.attributes["POSITION"] =
      addAccessor(model, floats(first.positions), TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  primitive.attributes["NORMAL"] =
      addAccessor(model, floats(first.normals), TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, false);

  tinygltf::Mesh mesh;
  mesh.name = name;
  const std::size_t n = span.last - span.first + 1;
  if (n > 1) {
    for (std::size_t k = span.first; k <= span.last; ++k) {
      const SurfaceMesh& frame = frames[k];
      primitive.targets.push_back(
          {{"POSITION", addAccessor(model, floats(frame.positions, &first.positions), TINYGLTF_TYPE_VEC3,
                                    TINYGLTF_TARGET_ARRAY_BUFFER, true)},
           {"NORMAL", addAccessor(model, floats(frame.normals, &first.normals), TINYGLTF_TYPE_VEC3,
                                  TINYGLTF_TARGET_ARRAY_BUFFER, false)}});
    }
    mesh.weights.assign(n, 0.0);
    mesh.weights[0] = 1.0;
  }
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  return static_cast<int>(model.meshes.size()) - 1;
}

// Appends a sampler and a channel driving `path` of node `node` to the animation.
void addChannel(tinygltf::Model& model, tinygltf::Animation& animation, const std::vector<float>& times,
                const std::vector<float>& values, int type, const char* interpolation, int node, const char* path) {
  tinygltf::AnimationSampler sampler;
  sampler.input = addAccessor(model, times, TINYGLTF_TYPE_SCALAR, 0, true);
  sampler.output = addAccessor(model, values, type, 0, false);
  sampler.interpolation = interpolation;
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
  channel.target_node = node;
  channel.target_path = path;
  animation.channels.push_back(channel);
}

}  // namespace

std::string glbBytes(const std::vector<SurfaceMesh>& frames, const ExportMaterial& material) {
  if (frames.empty()) throw std::runtime_error("glTF: no frame to write");
  const SurfaceMesh& first = frames.front();
  const std::vector<Span> spans = spansOf(frames);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "slime";
  model.buffers.emplace_back();
  addMaterial(model, material, meanChord(first));

  tinygltf::Scene scene;
  for (const Span& span : spans) {
    std::string name = "slime";
    if (spans.size() > 1) {
      char text[120];
      std::snprintf(text, sizeof text, "slime, %zu piece%s, t %.3f-%.3f s", frames[span.first].pieceCount(),
                    frames[span.first].pieceCount() == 1 ? "" : "s", frames[span.first].time, frames[span.last].time);
      name = text;
    }
    tinygltf::Node node;
    node.name = name;
    node.mesh = addSpanMesh(model, frames, span, name);
    // The simulation's z is up; glTF's y is up: a rotation of −90° about x, (x, y, z) → (x, z, −y).
    node.rotation = {-0.70710678118654752, 0.0, 0.0, 0.70710678118654752};
    if (span.first > 0) node.scale = {0.0, 0.0, 0.0};  // shown from its first frame on (the animation)
    model.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  // One animation: each span's morph weights, one-hot at its frame k's time and linear between; and,
  // where the pieces change (a tear, a merge), each span's node shown (scale 1) from its first frame's
  // time until the next span's and hidden (scale 0) otherwise, stepwise: glTF 2.0 has no visibility.
  if (frames.size() > 1) {
    tinygltf::Animation animation;
    animation.name = "slime";
    const auto at = [&](std::size_t k) { return static_cast<float>(frames[k].time - first.time); };
    for (std::size_t s = 0; s < spans.size(); ++s) {
      const Span& span = spans[s];
      const std::size_t n = span.last - span.first + 1;
      const int node = static_cast<int>(s);
      if (n > 1) {
        std::vector<float> times(n), weights(n * n, 0.0f);
        for (std::size_t k = 0; k < n; ++k) {
          times[k] = at(span.first + k);
          weights[k * n + k] = 1.0f;
        }
        addChannel(model, animation, times, weights, TINYGLTF_TYPE_SCALAR, "LINEAR", node, "weights");
      }
      if (spans.size() > 1) {
        std::vector<float> times, scales;
        const auto key = [&](float time, float scale) {
          times.push_back(time);
          scales.insert(scales.end(), {scale, scale, scale});
        };
        if (span.first > 0) key(0.0f, 0.0f);
        key(at(span.first), 1.0f);
        if (span.last + 1 < frames.size()) key(at(span.last + 1), 0.0f);
        addChannel(model, animation, times, scales, TINYGLTF_TYPE_VEC3, "STEP", node, "scale");
      }
    }
    model.animations.push_back(animation);
  }

  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, false, true)) throw std::runtime_error("glTF: tinygltf cannot write the model");
  return out.str();
}

}  // namespace slime

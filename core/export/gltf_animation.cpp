#include "core/export/gltf_animation.h"

#include "core/export/export_material.h"

#include <tiny_gltf.h>

#include <algorithm>
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

std::string glbBytes(const std::vector<SurfaceMesh>& frames, const ExportMaterial& material) {
  if (frames.empty()) throw std::runtime_error("glTF: no frame to write");
  const SurfaceMesh& first = frames.front();
  for (const SurfaceMesh& frame : frames)
    if (frame.triangles != first.triangles)
      throw std::runtime_error("glTF: the surface's triangles changed at t = " + std::to_string(frame.time) +
                               " s (slime.level or autoLevel); one .glb holds one mesh: export .ply or .obj");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "slime";
  model.buffers.emplace_back();

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  addMaterial(model, material, meanChord(first));
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
  mesh.name = "slime";
  const std::size_t n = frames.size();
  if (n > 1) {
    for (const SurfaceMesh& frame : frames) {
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

  tinygltf::Node node;
  node.name = "slime";
  node.mesh = 0;
  // The simulation's z is up; glTF's y is up: a rotation of −90° about x, (x, y, z) → (x, z, −y).
  node.rotation = {-0.70710678118654752, 0.0, 0.0, 0.70710678118654752};
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  if (n > 1) {
    std::vector<float> times(n), weights(n * n, 0.0f);
    for (std::size_t k = 0; k < n; ++k) {
      times[k] = static_cast<float>(frames[k].time - first.time);
      weights[k * n + k] = 1.0f;
    }
    tinygltf::AnimationSampler sampler;
    sampler.input = addAccessor(model, times, TINYGLTF_TYPE_SCALAR, 0, true);
    sampler.output = addAccessor(model, weights, TINYGLTF_TYPE_SCALAR, 0, false);
    sampler.interpolation = "LINEAR";
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = 0;
    channel.target_path = "weights";
    tinygltf::Animation animation;
    animation.name = "slime";
    animation.samplers.push_back(sampler);
    animation.channels.push_back(channel);
    model.animations.push_back(animation);
  }

  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, false, true)) throw std::runtime_error("glTF: tinygltf cannot write the model");
  return out.str();
}

}  // namespace slime

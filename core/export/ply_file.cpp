#include "core/export/ply_file.h"

#include <cstdint>
#include <cstring>

namespace slime {
namespace {

template <typename T>
void append(std::string& bytes, T value) {  // x86-64 and ARM64 are little-endian, as the header says
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

}  // namespace

std::string plyBytes(const SurfaceMesh& mesh) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\ncomment slime surface at t = " +
                      std::to_string(mesh.time) + " s, metres\nelement vertex " +
                      std::to_string(mesh.positions.size()) +
                      "\nproperty double x\nproperty double y\nproperty double z\n"
                      "property float nx\nproperty float ny\nproperty float nz\nelement face " +
                      std::to_string(mesh.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  bytes.reserve(bytes.size() + mesh.positions.size() * 36 + mesh.triangles.size() * 13);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) append(bytes, mesh.positions[i][c]);
    for (int c = 0; c < 3; ++c) append(bytes, static_cast<float>(mesh.normals[i][c]));
  }
  for (const Triangle& t : mesh.triangles) {
    append(bytes, std::uint8_t{3});
    for (int c = 0; c < 3; ++c) append(bytes, static_cast<std::int32_t>(t[c]));
  }
  return bytes;
}

}  // namespace slime

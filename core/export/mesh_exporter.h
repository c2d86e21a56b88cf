// Writing the slime's surface out as the simulation runs (`slime sim --export-mesh PATTERN
// --export-every S`) or once (`slime snapshot --export-mesh FILE`). The format follows the extension:
// .ply (binary, ply_file.h), .obj (obj_file.h), .glb (every frame in one animated file,
// gltf_animation.h). Each file is written whole or not at all (core/settings/file_output.h).
#pragma once

#include "core/export/surface_mesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

enum class MeshFormat { Ply, Obj, Glb };

// The format of `path` by its extension; SettingsError naming `option` and the allowed ones otherwise.
MeshFormat meshFormatOf(const std::string& path, const std::string& option = "--export-mesh");

// The format of `path`, after checking that its directory exists and takes a new file: a SettingsError
// otherwise, so that a command can refuse the path before its work.
MeshFormat checkMeshPath(const std::string& path);

// Writes one surface to `path` in the format of its extension (a .glb without animation).
void writeSurfaceMesh(const std::string& path, const SurfaceMesh& mesh);

class MeshExporter {
 public:
  // `pattern` holds one printf-style integer conversion (%d, %04d, ...; %% is a percent sign) for .ply
  // and .obj, none for .glb; frames are due every `every` s of simulated time from t = 0 (steps of `dt`)
  // up to `seconds`. Throws SettingsError for a bad pattern or interval, or a directory that cannot be
  // written, before any simulation runs.
  MeshExporter(std::string pattern, double every, double dt, double seconds);

  bool due(std::int64_t step) const { return step == nextStep_; }
  // Adds the frame at `time`: a .ply or .obj is written now, a .glb's frames are kept for finish().
  void add(double time, const std::vector<glm::dvec3>& positions, const std::vector<Triangle>& triangles);
  void finish();  // writes the .glb
  int frames() const { return frames_; }
  std::string pathOf(int frame) const;  // the file frame `frame` goes to

 private:
  std::string pattern_;
  MeshFormat format_;
  double every_, dt_;
  std::int64_t nextStep_ = 0;
  int frames_ = 0;
  std::vector<SurfaceMesh> kept_;  // .glb only
};

}  // namespace slime

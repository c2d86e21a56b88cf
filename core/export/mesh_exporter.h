// Writing the slime's surface out as the simulation runs (`slime sim --export-mesh PATTERN
// --export-every S`) or once (`slime snapshot --export-mesh FILE`). The format follows the extension:
// .ply (binary, ply_file.h), .obj with its .mtl beside it (obj_file.h: y up unless told z), .glb
// (every frame in one animated file, gltf_animation.h). The .glb and the .mtl carry the slime's
// material (export_material.h). Each file, and each .obj with its .mtl, is written whole or not at all
// (core/settings/file_output.h).
#pragma once

#include "core/export/export_material.h"
#include "core/export/obj_file.h"
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

// The .mtl that the .obj `objPath` names: the same path ending in .mtl.
std::string materialPathOf(const std::string& objPath);

// Writes one surface to `path` in the format of its extension (a .glb without animation); `objUp`
// is the axes of an .obj (a SettingsError for another format, where it would mean nothing).
void writeSurfaceMesh(const std::string& path, const SurfaceMesh& mesh, const ExportMaterial& material,
                      UpAxis objUp = UpAxis::Y);

// `--obj-up NAME` given with `--export-mesh path`: its axes, or a SettingsError when the name is not y
// or z or the path is not an .obj. An empty name (the option not given) is y.
UpAxis checkObjUp(const std::string& name, const std::string& path);

class MeshExporter {
 public:
  // `pattern` holds one printf-style integer conversion (%d, %04d, ...; %% is a percent sign) for .ply
  // and .obj, none for .glb; frames are due every `every` s of simulated time from t = 0 (steps of `dt`)
  // up to `seconds`. Throws SettingsError for a bad pattern or interval, or a directory that cannot be
  // written, before any simulation runs.
  // `objUp`: the axes of an .obj.
  MeshExporter(std::string pattern, double every, double dt, double seconds, UpAxis objUp = UpAxis::Y);

  bool due(std::int64_t step) const { return step == nextStep_; }
  // Adds the frame at `time`, every piece of it in the one file (surfaceMeshOf), with the slime's
  // material then: a .ply or .obj (and its .mtl) is written now, a .glb's frames are kept for finish().
  // In a .glb each run of frames with one set of pieces is a mesh shown over its frames (gltf_animation.h).
  void add(double time, std::span<const SurfaceView> surfaces, const ExportMaterial& material);
  void finish();  // writes the .glb, with the first frame's material
  int frames() const { return frames_; }
  std::string pathOf(int frame) const;  // the file frame `frame` goes to

 private:
  std::string pattern_;
  MeshFormat format_;
  double every_, dt_;
  UpAxis objUp_;
  std::int64_t nextStep_ = 0;
  int frames_ = 0;
  std::vector<SurfaceMesh> kept_;  // .glb only
  ExportMaterial material_;        // .glb only: the first frame's
};

}  // namespace slime

#include "core/export/mesh_exporter.h"

#include "core/export/gltf_animation.h"
#include "core/export/obj_file.h"
#include "core/export/ply_file.h"
#include "core/settings/file_output.h"
#include "core/settings/settings_io.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace slime {
namespace {

constexpr double kMostFrames = 100000;  // a run writing more is a mistake in --export-every
constexpr double kMostGlbFrames = 2000;  // the weights grow as frames²: 16 MB at 2000

std::string extensionOf(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// The position and length of the one %[0][width]d|i|u in `pattern`, or npos when there is none.
// Any other conversion, a second one, or a lone % at the end is a SettingsError.
struct Conversion {
  std::size_t at = std::string::npos, length = 0;
  bool zeroPad = false;
  int width = 0;
};

Conversion conversionIn(const std::string& pattern) {
  Conversion found;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    Conversion c;
    c.at = i;
    if (j < pattern.size() && pattern[j] == '0') {
      c.zeroPad = true;
      ++j;
    }
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) && c.width < 100)
      c.width = c.width * 10 + (pattern[j++] - '0');
    if (j >= pattern.size() || (pattern[j] != 'd' && pattern[j] != 'i' && pattern[j] != 'u') || c.width >= 100)
      throw SettingsError("--export-mesh " + pattern + ": '" + pattern.substr(i, j - i + 1) +
                          "' is not a frame number; expected one %d, %04d or the like (%% for a percent sign)");
    if (found.at != std::string::npos)
      throw SettingsError("--export-mesh " + pattern + ": more than one frame number; expected one %d or %04d");
    c.length = j - i + 1;
    found = c;
    i = j;
  }
  return found;
}

std::string expand(const std::string& pattern, const Conversion& c, int frame) {
  std::string out;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (i == c.at) {
      std::string number = std::to_string(frame);
      if (static_cast<int>(number.size()) < c.width)
        number.insert(0, static_cast<std::size_t>(c.width) - number.size(), c.zeroPad ? '0' : ' ');
      out += number;
      i += c.length - 1;
    } else {
      out += pattern[i];
      if (pattern[i] == '%') ++i;  // %% → %
    }
  }
  return out;
}

// A directory that does not exist or cannot take a new file, found before the run starts.
void checkWritable(const std::string& path, const std::string& option) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const std::string probe = (parent.empty() ? std::filesystem::path(".") : parent).string() + "/.slime-write-check";
  std::error_code error;
  if (!parent.empty() && !std::filesystem::is_directory(parent, error))
    throw SettingsError(option + " " + path + ": the directory " + parent.string() + " does not exist");
  std::ofstream(probe).put('x');
  if (!std::filesystem::remove(probe, error))
    throw SettingsError(option + " " + path + ": cannot write in " + (parent.empty() ? "." : parent.string()));
}

// Writes `mesh` to `path` in `format`, all files of it or none.
void writeMesh(MeshFormat format, const std::string& path, const SurfaceMesh& mesh, const ExportMaterial& material,
               UpAxis objUp) {
  switch (format) {
    case MeshFormat::Ply: return writeFileAtomically(path, plyBytes(mesh));
    case MeshFormat::Obj: {
      // The .mtl is renamed into place first: a reader that finds the .obj finds its material.
      const std::string materialPath = materialPathOf(path);
      return writeFilesAtomically(
          {{materialPath, mtlText(material)},
           {path, objText(mesh, objUp, std::filesystem::path(materialPath).filename().string())}});
    }
    case MeshFormat::Glb: return writeFileAtomically(path, glbBytes({mesh}, material));
  }
}

}  // namespace

MeshFormat meshFormatOf(const std::string& path, const std::string& option) {
  const std::string extension = extensionOf(path);
  if (extension == ".ply") return MeshFormat::Ply;
  if (extension == ".obj") return MeshFormat::Obj;
  if (extension == ".glb") return MeshFormat::Glb;
  throw SettingsError(option + " " + path + ": expected a file ending in .ply, .obj or .glb");
}

MeshFormat checkMeshPath(const std::string& path) {
  const MeshFormat format = meshFormatOf(path);
  checkWritable(path, "--export-mesh");
  return format;
}

std::string materialPathOf(const std::string& objPath) {
  return std::filesystem::path(objPath).replace_extension(".mtl").string();
}

void writeSurfaceMesh(const std::string& path, const SurfaceMesh& mesh, const ExportMaterial& material,
                      UpAxis objUp) {
  writeMesh(checkMeshPath(path), path, mesh, material, objUp);
}

UpAxis checkObjUp(const std::string& name, const std::string& path) {
  if (name.empty()) return UpAxis::Y;
  const UpAxis up = upAxisNamed(name);
  if (path.empty() || meshFormatOf(path) != MeshFormat::Obj)
    throw SettingsError("--obj-up " + name + ": only an .obj export has a choice of axes (--export-mesh " +
                        (path.empty() ? std::string("not given") : path) +
                        "); a .glb is y up by glTF's rule, a .ply keeps the simulation's z up");
  return up;
}

MeshExporter::MeshExporter(std::string pattern, double every, double dt, double seconds, UpAxis objUp)
    : pattern_(std::move(pattern)), format_(meshFormatOf(pattern_)), every_(every), dt_(dt), objUp_(objUp) {
  const Conversion c = conversionIn(pattern_);
  if (format_ == MeshFormat::Glb && c.at != std::string::npos)
    throw SettingsError("--export-mesh " + pattern_ + ": a .glb holds every frame in one file; drop the frame number");
  if (format_ != MeshFormat::Glb && c.at == std::string::npos)
    throw SettingsError("--export-mesh " + pattern_ + ": a ." + (format_ == MeshFormat::Ply ? "ply" : "obj") +
                        " file holds one frame; put a frame number in the name, e.g. out/slime_%04d" +
                        (format_ == MeshFormat::Ply ? ".ply" : ".obj"));
  const double limit = format_ == MeshFormat::Glb ? kMostGlbFrames : kMostFrames;
  if (!std::isfinite(every) || every < dt || seconds / every + 1.0 > limit) {
    char text[200];
    std::snprintf(text, sizeof text, "--export-every %g: expected at least sim.dt (%g s) and at most %g frames "
                  "in the run (%g s)", every, dt, limit, seconds);
    throw SettingsError(text);
  }
  checkWritable(pathOf(0), "--export-mesh");
}

std::string MeshExporter::pathOf(int frame) const {
  const Conversion c = conversionIn(pattern_);
  return c.at == std::string::npos ? pattern_ : expand(pattern_, c, frame);
}

void MeshExporter::add(double time, std::span<const SurfaceView> surfaces, const ExportMaterial& material) {
  SurfaceMesh mesh = surfaceMeshOf(time, surfaces);
  if (format_ == MeshFormat::Glb) {
    if (kept_.empty()) material_ = material;
    kept_.push_back(std::move(mesh));
  } else {
    writeMesh(format_, pathOf(frames_), mesh, material, objUp_);
  }
  ++frames_;
  nextStep_ = std::llround(static_cast<double>(frames_) * every_ / dt_);
}

void MeshExporter::finish() {
  if (format_ == MeshFormat::Glb && !kept_.empty()) writeFileAtomically(pattern_, glbBytes(kept_, material_));
}

}  // namespace slime

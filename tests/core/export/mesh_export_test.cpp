// The exported surface read back by independent readers — a small PLY parser here, and assimp for
// .obj and .glb — holds exactly the simulation's vertex positions and triangles at the export times.
#include "core/export/mesh_exporter.h"
#include "core/simulation/simulation.h"
#include "core/settings/settings_io.h"

#include <assimp/Importer.hpp>
#include <assimp/anim.h>
#include <assimp/mesh.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace slime {
namespace {

namespace fs = std::filesystem;

struct Frame {
  double time;
  std::vector<glm::dvec3> positions;
  std::vector<Triangle> triangles;
};

fs::path freshDirectory(const std::string& name) {
  const fs::path dir = fs::path(SLIME_TEST_OUTPUT_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs the default bulk slime for 0.06 s, exporting every 0.02 s with `pattern`; returns what the
// simulation held at each export.
std::vector<Frame> runAndExport(const std::string& pattern) {
  Settings settings = defaultSettings();
  settings.slime.level = 2;  // 162 vertices: a fast test, the same code as at level 4
  Simulation simulation(settings);
  MeshExporter exporter(pattern, 0.02, settings.sim.dt, 0.06);
  std::vector<Frame> frames;
  const auto steps = static_cast<std::int64_t>(std::llround(0.06 / settings.sim.dt));
  while (true) {
    if (exporter.due(simulation.stepCount())) {
      exporter.add(simulation.time(), simulation.positions(), simulation.triangles());
      frames.push_back({simulation.time(), simulation.positions(), simulation.triangles()});
    }
    if (simulation.stepCount() >= steps) break;
    simulation.step();
  }
  exporter.finish();
  return frames;
}

// A binary little-endian PLY with double x y z, float nx ny nz and uchar/int face lists, as
// ply_file.h writes it; the header is checked line by line.
Frame readPly(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> header;
  while (std::getline(in, line) && line != "end_header") {
    header.push_back(line);
    std::istringstream words(line);
    std::string word, element;
    words >> word >> element;
    if (word == "element" && element == "vertex") words >> vertices;
    if (word == "element" && element == "face") words >> faces;
  }
  EXPECT_EQ(header.at(1), "format binary_little_endian 1.0");
  EXPECT_EQ(header.at(4), "property double x");
  EXPECT_EQ(header.at(7), "property float nx");
  Frame frame{0.0, std::vector<glm::dvec3>(vertices), std::vector<Triangle>(faces)};
  for (glm::dvec3& p : frame.positions) {
    in.read(reinterpret_cast<char*>(&p), sizeof(double) * 3);
    float normal[3];
    in.read(reinterpret_cast<char*>(normal), sizeof normal);
    EXPECT_NEAR(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2], 1.0, 1e-5);
  }
  for (Triangle& t : frame.triangles) {
    std::uint8_t count = 0;
    std::int32_t index[3];
    in.read(reinterpret_cast<char*>(&count), 1);
    in.read(reinterpret_cast<char*>(index), sizeof index);
    EXPECT_EQ(count, 3);
    t = Triangle(index[0], index[1], index[2]);
  }
  EXPECT_TRUE(in.good());
  in.peek();
  EXPECT_TRUE(in.eof()) << "bytes after the last face";
  return frame;
}

const aiScene* readWithAssimp(Assimp::Importer& importer, const fs::path& path) {
  const aiScene* scene = importer.ReadFile(path.string(), 0);  // no post-processing: the file as it is
  EXPECT_NE(scene, nullptr) << importer.GetErrorString();
  return scene;
}

TEST(MeshExport, PlyHoldsTheSimulationsDoublesAndTriangles) {
  const fs::path dir = freshDirectory("mesh_export_ply");
  const std::vector<Frame> frames = runAndExport((dir / "slime_%03d.ply").string());
  ASSERT_EQ(frames.size(), 4u);  // t = 0, 0.02, 0.04, 0.06
  for (std::size_t k = 0; k < frames.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "slime_%03zu.ply", k);
    const Frame read = readPly(dir / name);
    EXPECT_EQ(read.positions, frames[k].positions) << name;  // bit for bit
    EXPECT_EQ(read.triangles, frames[k].triangles) << name;
  }
  EXPECT_NE(frames[0].positions, frames[3].positions);  // the slime moved: the frames are not one
}

TEST(MeshExport, ObjReadByAssimpHoldsEveryCorner) {
  const fs::path dir = freshDirectory("mesh_export_obj");
  const std::vector<Frame> frames = runAndExport((dir / "slime_%d.obj").string());
  ASSERT_EQ(frames.size(), 4u);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    Assimp::Importer importer;
    const aiScene* scene = readWithAssimp(importer, dir / ("slime_" + std::to_string(k) + ".obj"));
    ASSERT_NE(scene, nullptr);
    ASSERT_EQ(scene->mNumMeshes, 1u);
    const aiMesh& mesh = *scene->mMeshes[0];
    ASSERT_EQ(mesh.mNumFaces, frames[k].triangles.size());
    // assimp's OBJ reader gives each face its own corners; each is the simulation's vertex (as float).
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      ASSERT_EQ(mesh.mFaces[f].mNumIndices, 3u);
      for (int c = 0; c < 3; ++c) {
        const aiVector3D& v = mesh.mVertices[mesh.mFaces[f].mIndices[c]];
        const glm::dvec3& p = frames[k].positions[frames[k].triangles[f][c]];
        // assimp parses numbers with its own fast_atof, not always to the nearest float.
        for (int i = 0; i < 3; ++i) ASSERT_NEAR(v[i], p[i], 2e-8) << "frame " << k << " face " << f;
      }
    }
    // The text itself, read with strtod: the simulation's doubles bit for bit, and its triangles.
    std::ifstream in(dir / ("slime_" + std::to_string(k) + ".obj"));
    std::vector<glm::dvec3> positions;
    std::vector<Triangle> triangles;
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("v ", 0) == 0) {
        char* at = line.data() + 2;
        glm::dvec3 p;
        for (int i = 0; i < 3; ++i) p[i] = std::strtod(at, &at);
        positions.push_back(p);
      } else if (line.rfind("f ", 0) == 0) {
        unsigned a, b, c, na, nb, nc;
        ASSERT_EQ(std::sscanf(line.c_str(), "f %u//%u %u//%u %u//%u", &a, &na, &b, &nb, &c, &nc), 6);
        triangles.emplace_back(a - 1, b - 1, c - 1);
      }
    }
    EXPECT_EQ(positions, frames[k].positions);
    EXPECT_EQ(triangles, frames[k].triangles);
  }
}

TEST(MeshExport, GlbReadByAssimpIsOneMeshAnimatedThroughEveryFrame) {
  const fs::path dir = freshDirectory("mesh_export_glb");
  const std::vector<Frame> frames = runAndExport((dir / "slime.glb").string());
  ASSERT_EQ(frames.size(), 4u);
  Assimp::Importer importer;
  const aiScene* scene = readWithAssimp(importer, dir / "slime.glb");
  ASSERT_NE(scene, nullptr);
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh& mesh = *scene->mMeshes[0];
  const Frame& first = frames[0];
  ASSERT_EQ(mesh.mNumVertices, first.positions.size());
  ASSERT_EQ(mesh.mNumFaces, first.triangles.size());
  for (unsigned f = 0; f < mesh.mNumFaces; ++f)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(mesh.mFaces[f].mIndices[c], first.triangles[f][c]);
  ASSERT_EQ(mesh.mNumAnimMeshes, frames.size());  // a morph target per frame
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const aiAnimMesh& target = *mesh.mAnimMeshes[k];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      for (int c = 0; c < 3; ++c) {
        // glTF is float: the reader's p_0 + (p_k − p_0), exactly as the file holds it ...
        const float base = static_cast<float>(first.positions[v][c]);
        const float offset = static_cast<float>(frames[k].positions[v][c] - first.positions[v][c]);
        ASSERT_EQ(mesh.mVertices[v][c], base) << "vertex " << v;
        ASSERT_EQ(target.mVertices[v][c], base + offset) << "frame " << k << " vertex " << v;
        // ... which is the simulation's position to a float's rounding (positions are ~0.1 m).
        ASSERT_NEAR(target.mVertices[v][c], frames[k].positions[v][c], 2e-8) << "frame " << k;
      }
  }
  ASSERT_EQ(scene->mNumAnimations, 1u);
  const aiAnimation& animation = *scene->mAnimations[0];
  ASSERT_EQ(animation.mNumMorphMeshChannels, 1u);
  const aiMeshMorphAnim& channel = *animation.mMorphMeshChannels[0];
  ASSERT_EQ(channel.mNumKeys, frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    // Key k shows frame k alone; assimp gives key times in ticks of mTicksPerSecond.
    EXPECT_NEAR(channel.mKeys[k].mTime / animation.mTicksPerSecond, frames[k].time, 1e-6);
    for (unsigned w = 0; w < channel.mKeys[k].mNumValuesAndWeights; ++w)
      EXPECT_EQ(channel.mKeys[k].mWeights[w], channel.mKeys[k].mValues[w] == k ? 1.0 : 0.0);
  }
}

TEST(MeshExport, BadPatternsAreRefusedBeforeAnyFile) {
  const fs::path dir = freshDirectory("mesh_export_bad");
  const auto refused = [&](const std::string& pattern, double every = 0.02) {
    EXPECT_THROW(MeshExporter(pattern, every, 0.001, 1.0), SettingsError) << pattern;
  };
  refused((dir / "a.ply").string());          // one file for many frames
  refused((dir / "a_%d_%d.ply").string());    // two frame numbers
  refused((dir / "a_%s.ply").string());       // not an integer
  refused((dir / "a_%d.stl").string());       // an unknown format
  refused((dir / "a_%d.glb").string());       // .glb holds every frame: no number
  refused((dir / "missing/a_%d.ply").string());  // no such directory
  refused((dir / "a_%d.ply").string(), 0.0);     // below sim.dt
  refused((dir / "a_%d.ply").string(), std::nan(""));
  EXPECT_TRUE(fs::is_empty(dir));
  MeshExporter literalPercent((dir / "a_%%_%04d.ply").string(), 0.02, 0.001, 1.0);
  EXPECT_EQ(literalPercent.pathOf(7), (dir / "a_%_0007.ply").string());
}

}  // namespace
}  // namespace slime

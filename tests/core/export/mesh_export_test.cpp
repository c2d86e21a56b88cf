// The exported surface read back by independent readers — a small PLY parser here, and assimp for
// .obj and .glb — holds exactly the simulation's vertex positions and triangles at the export times.
#include "core/export/mesh_exporter.h"
#include "core/membrane/slime_body.h"
#include "core/simulation/simulation.h"
#include "core/settings/settings_io.h"

#include <assimp/Importer.hpp>
#include <assimp/anim.h>
#include <assimp/material.h>
#include <assimp/mesh.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
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

// What the simulation holds as one mesh: every piece's vertices after the pieces before it, and its
// triangles offset by as many (put together here, independently of surfaceMeshOf).
Frame frameOf(const Simulation& simulation) {
  Frame frame{simulation.time(), {}, {}};
  for (const SurfaceView& surface : simulation.surfaces()) {
    const auto offset = static_cast<std::uint32_t>(frame.positions.size());
    frame.positions.insert(frame.positions.end(), surface.positions.begin(), surface.positions.end());
    for (const Triangle& t : surface.triangles) frame.triangles.push_back(t + Triangle(offset));
  }
  return frame;
}

// Runs `simulation` for 0.06 s, exporting every 0.02 s with `pattern`; returns what the simulation
// held at each export.
std::vector<Frame> exportRun(Simulation& simulation, const std::string& pattern, UpAxis objUp = UpAxis::Y) {
  const Settings& settings = simulation.settings();
  MeshExporter exporter(pattern, 0.02, settings.sim.dt, 0.06, objUp);
  std::vector<Frame> frames;
  const auto steps = static_cast<std::int64_t>(std::llround(0.06 / settings.sim.dt));
  while (true) {
    if (exporter.due(simulation.stepCount())) {
      exporter.add(simulation.time(), simulation.surfaces(), exportMaterialOf(settings.slime));
      frames.push_back(frameOf(simulation));
    }
    if (simulation.stepCount() >= steps) break;
    simulation.step();
  }
  exporter.finish();
  return frames;
}

// Runs the default bulk slime for 0.06 s, exporting every 0.02 s with `pattern`.
std::vector<Frame> runAndExport(const std::string& pattern, UpAxis objUp = UpAxis::Y,
                                Settings settings = defaultSettings()) {
  settings.slime.level = 2;  // 162 vertices: a fast test, the same code as at level 4
  Simulation simulation(settings);
  return exportRun(simulation, pattern, objUp);
}

// A slime of two pieces, which nothing makes yet (tearing is to come): two membrane balls given to
// Simulation as two bodies, of levels 2 and 1 so that their vertex counts differ.
Simulation twoPieces() {
  Settings settings = defaultSettings();
  settings.slime.model = "membrane";
  std::vector<SlimeBody> bodies;
  settings.slime.level = 2;
  settings.slime.position = {-0.06, 0.0, 0.05};
  bodies.push_back(buildSlimeBody(settings.slime));
  settings.slime.level = 1;
  settings.slime.radius = 0.02;
  settings.slime.position = {0.06, 0.0, 0.03};
  bodies.push_back(buildSlimeBody(settings.slime));
  settings.slime.level = 2;
  return Simulation(settings, std::move(bodies));
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

// Every piece goes into each frame's one file, piece after piece: the file holds the pieces' doubles
// bit for bit, and each face of the second piece indexes the second piece's vertices only.
TEST(MeshExport, PlyHoldsEveryPieceOfTheFrame) {
  const fs::path dir = freshDirectory("mesh_export_pieces_ply");
  Simulation simulation = twoPieces();
  ASSERT_EQ(simulation.pieceCount(), 2u);
  const std::size_t firstVertices = simulation.surfaces()[0].positions.size();
  const std::size_t firstFaces = simulation.surfaces()[0].triangles.size();
  ASSERT_NE(firstVertices, simulation.surfaces()[1].positions.size());
  const std::vector<Frame> frames = exportRun(simulation, (dir / "pieces_%d.ply").string());
  ASSERT_EQ(frames.size(), 4u);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const Frame read = readPly(dir / ("pieces_" + std::to_string(k) + ".ply"));
    ASSERT_EQ(read.positions, frames[k].positions) << "frame " << k;
    ASSERT_EQ(read.triangles, frames[k].triangles) << "frame " << k;
    for (std::size_t f = 0; f < read.triangles.size(); ++f)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(read.triangles[f][c] >= firstVertices, f >= firstFaces) << "face " << f << " reaches into the other piece";
  }
  EXPECT_NE(frames[0].positions, frames[3].positions);
}

// OBJ's y up: the simulation's (x, y, z) as the file holds it, (x, z, −y).
glm::dvec3 yUp(const glm::dvec3& p) { return {p.x, p.z, -p.y}; }

TEST(MeshExport, ObjReadByAssimpHoldsEveryCornerYUp) {
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
        const glm::dvec3 p = yUp(frames[k].positions[frames[k].triangles[f][c]]);
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
    std::vector<glm::dvec3> expected;
    for (const glm::dvec3& p : frames[k].positions) expected.push_back(yUp(p));
    EXPECT_EQ(positions, expected);  // the swap and the sign are exact
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

// A fixed set of pieces animates in a .glb as one mesh: every piece's vertices in the first frame, and
// each frame's morph target moves all of them.
TEST(MeshExport, GlbAnimatesAFixedSetOfPieces) {
  const fs::path dir = freshDirectory("mesh_export_pieces_glb");
  Simulation simulation = twoPieces();
  const std::vector<Frame> frames = exportRun(simulation, (dir / "pieces.glb").string());
  ASSERT_EQ(frames.size(), 4u);
  Assimp::Importer importer;
  const aiScene* scene = readWithAssimp(importer, dir / "pieces.glb");
  ASSERT_NE(scene, nullptr);
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh& mesh = *scene->mMeshes[0];
  ASSERT_EQ(mesh.mNumVertices, frames[0].positions.size());
  ASSERT_EQ(mesh.mNumFaces, frames[0].triangles.size());
  for (unsigned f = 0; f < mesh.mNumFaces; ++f)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(mesh.mFaces[f].mIndices[c], frames[0].triangles[f][c]);
  ASSERT_EQ(mesh.mNumAnimMeshes, frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k)
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(mesh.mAnimMeshes[k]->mVertices[v][c], frames[k].positions[v][c], 2e-8) << "frame " << k << " vertex " << v;
}

// Pieces that change (torn off, merged) cannot be morph targets of one mesh: each run of frames with one
// set of pieces is a mesh of its own, its node's scale stepping from 0 to 1 at its first frame and back
// to 0 at the next run's, so a player shows one piece, then two.
TEST(MeshExport, GlbShowsEachSetOfPiecesOverItsOwnFrames) {
  const fs::path dir = freshDirectory("mesh_export_pieces_change");
  const TriangleMesh left = makeIcosphere(2, 0.04, {-0.06, 0.0, 0.04});
  const TriangleMesh right = makeIcosphere(1, 0.02, {0.06, 0.0, 0.02});
  TriangleMesh lower = left;
  for (glm::dvec3& p : lower.positions) p.z -= 0.01;
  const Settings settings = defaultSettings();
  const double dt = settings.sim.dt;
  MeshExporter exporter((dir / "change.glb").string(), dt, dt, 1.0);
  const std::vector<SurfaceView> one = {left}, oneLower = {lower}, two = {left, right}, twoLower = {lower, right};
  const ExportMaterial material = exportMaterialOf(settings.slime);
  exporter.add(0.0, one, material);
  exporter.add(dt, oneLower, material);
  exporter.add(2 * dt, two, material);
  exporter.add(3 * dt, twoLower, material);
  exporter.finish();
  Assimp::Importer importer;
  const aiScene* scene = readWithAssimp(importer, dir / "change.glb");
  ASSERT_NE(scene, nullptr);
  ASSERT_EQ(scene->mNumMeshes, 2u);
  EXPECT_EQ(scene->mMeshes[0]->mNumVertices, left.positions.size());
  EXPECT_EQ(scene->mMeshes[1]->mNumVertices, left.positions.size() + right.positions.size());
  // Each run of frames is animated in its own mesh: its second frame is 1 cm lower (the mesh keeps the
  // simulation's z up; the node turns it y up).
  for (unsigned m = 0; m < 2; ++m) {
    ASSERT_EQ(scene->mMeshes[m]->mNumAnimMeshes, 2u) << "mesh " << m;
    EXPECT_NEAR(scene->mMeshes[m]->mAnimMeshes[1]->mVertices[0].z - scene->mMeshes[m]->mVertices[0].z, -0.01, 1e-6);
  }
  // The nodes' scale: the first run shown until the second run's first frame (t = 2 dt), then hidden; the
  // second hidden until then, then shown.
  ASSERT_EQ(scene->mNumAnimations, 1u);
  const aiAnimation& animation = *scene->mAnimations[0];
  const auto scaleAt = [&](unsigned node, double time) {
    for (unsigned c = 0; c < animation.mNumChannels; ++c) {
      const aiNodeAnim& channel = *animation.mChannels[c];
      if (std::string(channel.mNodeName.C_Str()) != std::string(scene->mRootNode->mChildren[node]->mName.C_Str()))
        continue;
      double scale = -1.0;
      for (unsigned k = 0; k < channel.mNumScalingKeys; ++k)
        if (channel.mScalingKeys[k].mTime / animation.mTicksPerSecond <= time + 1e-9) scale = channel.mScalingKeys[k].mValue.x;
      return scale;
    }
    return -2.0;  // no scale channel for the node
  };
  ASSERT_EQ(scene->mRootNode->mNumChildren, 2u);
  EXPECT_EQ(scaleAt(0, 0.0), 1.0);
  EXPECT_EQ(scaleAt(0, 1.5 * dt), 1.0);
  EXPECT_EQ(scaleAt(0, 2 * dt), 0.0);
  EXPECT_EQ(scaleAt(1, 0.0), 0.0);
  EXPECT_EQ(scaleAt(1, 1.5 * dt), 0.0);
  EXPECT_EQ(scaleAt(1, 2 * dt), 1.0);
  EXPECT_EQ(scaleAt(1, 3 * dt), 1.0);
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

double lowest(const std::vector<glm::dvec3>& values, int axis) {
  double low = values[0][axis];
  for (const glm::dvec3& v : values) low = std::min(low, v[axis]);
  return low;
}

// The extent of `values` along axis `axis`.
double extent(const std::vector<glm::dvec3>& values, int axis) {
  double low = values[0][axis], high = low;
  for (const glm::dvec3& v : values) low = std::min(low, v[axis]), high = std::max(high, v[axis]);
  return high - low;
}

// A slime flattened on the floor, so that its height and width differ, read back by assimp: y up (the
// default) puts its height along the file's y and its normals turn with it; z up keeps the
// simulation's axes. Each .obj names its .mtl.
TEST(MeshExport, ObjStandsUprightYUpAndKeepsZUpOnRequest) {
  const fs::path dir = freshDirectory("mesh_export_obj_axes");
  Settings settings = defaultSettings();
  settings.slime.level = 2;
  Simulation simulation(settings);
  std::vector<glm::dvec3> squashed = simulation.positions();
  for (glm::dvec3& p : squashed) p.z = 0.5 * p.z + 0.3 * p.y;  // height ≠ depth, and a tilt: no symmetry hides a swap
  const SurfaceMesh mesh = surfaceMeshOf(0.0, squashed, simulation.triangles());
  writeSurfaceMesh((dir / "y.obj").string(), mesh, exportMaterialOf(settings.slime));
  writeSurfaceMesh((dir / "z.obj").string(), mesh, exportMaterialOf(settings.slime), UpAxis::Z);
  for (const auto& [name, up] : {std::pair{"y", UpAxis::Y}, std::pair{"z", UpAxis::Z}}) {
    Assimp::Importer importer;
    const aiScene* scene = readWithAssimp(importer, dir / (std::string(name) + ".obj"));
    ASSERT_NE(scene, nullptr);
    const aiMesh& read = *scene->mMeshes[0];
    ASSERT_TRUE(read.HasNormals());
    std::vector<glm::dvec3> corners;
    for (unsigned f = 0; f < read.mNumFaces; ++f)
      for (int c = 0; c < 3; ++c) {
        const unsigned i = read.mFaces[f].mIndices[c];
        const unsigned v = mesh.triangles[f][c];
        const glm::dvec3 position = up == UpAxis::Y ? yUp(mesh.positions[v]) : mesh.positions[v];
        const glm::dvec3 normal = up == UpAxis::Y ? yUp(mesh.normals[v]) : mesh.normals[v];
        corners.push_back({read.mVertices[i].x, read.mVertices[i].y, read.mVertices[i].z});
        for (int a = 0; a < 3; ++a) {
          ASSERT_NEAR(read.mVertices[i][a], position[a], 2e-8) << name << " face " << f;
          ASSERT_NEAR(read.mNormals[i][a], normal[a], 1e-6) << name << " face " << f;
        }
      }
    // Up is up: the file's up axis spans the simulation's z, bottom to top, in the same direction.
    const int fileUp = up == UpAxis::Y ? 1 : 2;
    EXPECT_NEAR(lowest(corners, fileUp), lowest(squashed, 2), 1e-7) << name << ": the bottom";
    EXPECT_NEAR(lowest(corners, fileUp) + extent(corners, fileUp), lowest(squashed, 2) + extent(squashed, 2), 1e-7)
        << name << ": the top";
    EXPECT_LT(extent(squashed, 2), 0.9 * extent(squashed, 1));  // the squash made the height differ from the depth
  }
  std::ifstream in(dir / "y.obj");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nmtllib y.mtl\n"), std::string::npos);
  EXPECT_NE(text.find("\nusemtl slime\n"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "y.mtl"));
  EXPECT_TRUE(fs::exists(dir / "z.mtl"));
  EXPECT_THROW(upAxisNamed("x"), SettingsError);
  EXPECT_THROW(upAxisNamed("Y "), SettingsError);
  EXPECT_THROW(checkObjUp("z", (dir / "a.glb").string()), SettingsError);  // only an .obj has the choice
  EXPECT_EQ(checkObjUp("", (dir / "a.glb").string()), UpAxis::Y);
}

// A scene's own optics (not the defaults): a red, half-transmissive slime.
Settings redSlime() {
  Settings settings = defaultSettings();
  settings.slime.color = {0.8, 0.2, 0.1};
  settings.slime.transmission = 0.5;
  settings.slime.absorption = 40.0;
  settings.slime.ior = 1.42;
  settings.slime.specular = 0.3;
  return settings;
}

// The .mtl beside each .obj, read by assimp: the scene's colour, specular weight, IOR and transmission,
// and a surface that is neither dissolved nor metallic.
TEST(MeshExport, MtlCarriesTheScenesMaterial) {
  const fs::path dir = freshDirectory("mesh_export_mtl");
  const Settings settings = redSlime();
  runAndExport((dir / "slime_%d.obj").string(), UpAxis::Y, settings);
  ASSERT_TRUE(fs::exists(dir / "slime_3.mtl"));
  Assimp::Importer importer;
  const aiScene* scene = readWithAssimp(importer, dir / "slime_3.obj");
  ASSERT_NE(scene, nullptr);
  const aiMaterial& material = *scene->mMaterials[scene->mMeshes[0]->mMaterialIndex];
  aiString name;
  material.Get(AI_MATKEY_NAME, name);
  EXPECT_STREQ(name.C_Str(), "slime");
  aiColor3D diffuse, specular, ambient(1, 1, 1), filter;
  float ior = 0, opacity = 0;
  ASSERT_EQ(material.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse), aiReturn_SUCCESS);
  EXPECT_NEAR(diffuse.r, 0.8, 1e-6);
  EXPECT_NEAR(diffuse.g, 0.2, 1e-6);
  EXPECT_NEAR(diffuse.b, 0.1, 1e-6);
  ASSERT_EQ(material.Get(AI_MATKEY_COLOR_SPECULAR, specular), aiReturn_SUCCESS);
  EXPECT_NEAR(specular.g, 0.3, 1e-6);
  ASSERT_EQ(material.Get(AI_MATKEY_COLOR_AMBIENT, ambient), aiReturn_SUCCESS);
  EXPECT_EQ(ambient.r + ambient.g + ambient.b, 0.0f);  // Blender reads Ka as metallic
  ASSERT_EQ(material.Get(AI_MATKEY_REFRACTI, ior), aiReturn_SUCCESS);
  EXPECT_NEAR(ior, 1.42, 1e-6);
  ASSERT_EQ(material.Get(AI_MATKEY_OPACITY, opacity), aiReturn_SUCCESS);
  EXPECT_EQ(opacity, 1.0f);
  // Tf: the transmission, grey (the colour tints it, as glTF's base colour does).
  ASSERT_EQ(material.Get(AI_MATKEY_COLOR_TRANSPARENT, filter), aiReturn_SUCCESS);
  EXPECT_EQ(filter, aiColor3D(0.5f, 0.5f, 0.5f));
}

// The JSON chunk of a .glb (glTF 2.0 binary: a 12-byte header, then the JSON chunk's length and type).
nlohmann::json glbJson(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_GE(bytes.size(), 20u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

// The animated .glb's one material is the scene's: base colour, metallic 0, smooth; transmission and
// IOR; the volume's attenuation such that −ln(attenuationColor) / attenuationDistance is the
// renderer's σ = k (−ln colour); the thickness the jelly's mean chord; the extensions declared.
TEST(MeshExport, GlbCarriesTheScenesMaterial) {
  const fs::path dir = freshDirectory("mesh_export_glb_material");
  const Settings settings = redSlime();
  const std::vector<Frame> frames = runAndExport((dir / "slime.glb").string(), UpAxis::Y, settings);
  const nlohmann::json gltf = glbJson(dir / "slime.glb");
  ASSERT_EQ(gltf["materials"].size(), 1u);
  EXPECT_EQ(gltf["meshes"][0]["primitives"][0]["material"], 0);
  const nlohmann::json& material = gltf["materials"][0];
  const nlohmann::json& pbr = material["pbrMetallicRoughness"];
  ASSERT_EQ(pbr["baseColorFactor"].size(), 4u);
  EXPECT_NEAR(pbr["baseColorFactor"][0].get<double>(), 0.8, 1e-9);
  EXPECT_NEAR(pbr["baseColorFactor"][1].get<double>(), 0.2, 1e-9);
  EXPECT_NEAR(pbr["baseColorFactor"][2].get<double>(), 0.1, 1e-9);
  EXPECT_EQ(pbr["baseColorFactor"][3].get<double>(), 1.0);
  EXPECT_EQ(pbr["metallicFactor"].get<double>(), 0.0);
  EXPECT_LE(pbr["roughnessFactor"].get<double>(), 0.1);
  const nlohmann::json& extensions = material["extensions"];
  EXPECT_EQ(extensions["KHR_materials_transmission"]["transmissionFactor"].get<double>(), 0.5);
  EXPECT_NEAR(extensions["KHR_materials_ior"]["ior"].get<double>(), 1.42, 1e-12);
  const nlohmann::json& volume = extensions["KHR_materials_volume"];
  const double distance = volume["attenuationDistance"].get<double>();
  EXPECT_NEAR(distance, 1.0 / 40.0, 1e-12);
  const double color[3] = {0.8, 0.2, 0.1};
  for (int c = 0; c < 3; ++c) {
    const double sigma = -std::log(volume["attenuationColor"][c].get<double>()) / distance;
    EXPECT_NEAR(sigma, 40.0 * -std::log(color[c]), 1e-9) << "channel " << c;
  }
  const double chord = meanChord(surfaceMeshOf(0.0, frames[0].positions, frames[0].triangles));
  EXPECT_NEAR(volume["thicknessFactor"].get<double>(), chord, 1e-12);
  EXPECT_NEAR(chord, 4.0 * 0.04 / 3.0, 0.004);  // 4r/3 of the 4 cm ball, less the icosphere's facets
  std::vector<std::string> used = gltf["extensionsUsed"];
  std::sort(used.begin(), used.end());
  EXPECT_EQ(used, (std::vector<std::string>{"KHR_materials_ior", "KHR_materials_transmission",
                                            "KHR_materials_volume"}));
  EXPECT_FALSE(gltf.contains("extensionsRequired"));  // a reader without them still draws the ball
}

// A clear slime (no absorption) has no attenuation distance: glTF's default, infinite.
TEST(MeshExport, GlbOfAClearSlimeAbsorbsNothing) {
  const fs::path dir = freshDirectory("mesh_export_glb_clear");
  Settings settings = defaultSettings();
  settings.slime.absorption = 0.0;
  settings.slime.level = 2;
  Simulation simulation(settings);
  writeSurfaceMesh((dir / "clear.glb").string(),
                   surfaceMeshOf(0.0, simulation.positions(), simulation.triangles()),
                   exportMaterialOf(settings.slime));
  const nlohmann::json volume = glbJson(dir / "clear.glb")["materials"][0]["extensions"]["KHR_materials_volume"];
  EXPECT_FALSE(volume.contains("attenuationDistance"));
  EXPECT_FALSE(volume.contains("attenuationColor"));
  EXPECT_GT(volume["thicknessFactor"].get<double>(), 0.0);
  EXPECT_EQ(exportMaterialOf(settings.slime).absorptionPerMetre(), glm::dvec3(0.0));
}

}  // namespace
}  // namespace slime

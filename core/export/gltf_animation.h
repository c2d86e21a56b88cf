// Frames of the surface as one binary glTF 2.0 file (.glb), written with tinygltf. The mesh is the
// first frame; every frame k is a morph target holding p_k − p_0 (and n_k − n_0), and one animation
// drives the weights, one-hot at frame k's time and linear between frames, so Blender and other glTF
// readers play the run. Where the pieces change (slime.tearing: a tear, a merge), each run of frames
// with one set of pieces is a mesh and node of its own, animated so, and shown only over its frames:
// its node's scale steps from 0 to 1 at its first frame and back to 0 at the next run's (glTF 2.0 has
// no visibility; Blender and three.js play scale 0 as hidden), and only the first run is shown where
// a reader ignores the animation. glTF stores 32-bit floats: a reader's p_0 + (p_k − p_0) is within a float's
// rounding of the simulation's p_k. The one material is the slime's (export_material.h): base colour,
// KHR_materials_transmission, _ior and _volume, its thickness the first frame's mean chord.
#pragma once

#include "core/export/export_material.h"
#include "core/export/surface_mesh.h"

#include <string>
#include <vector>

namespace slime {

// Frames whose triangles change (a tear, a merge, another level) start a new mesh (above).
std::string glbBytes(const std::vector<SurfaceMesh>& frames, const ExportMaterial& material);

}  // namespace slime

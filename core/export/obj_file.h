// A surface as Wavefront OBJ text with its material as an MTL file beside it. The OBJ holds v and vn
// lines (positions in m with 17 significant digits, so a double reads back exactly; the axis swap
// below is exact too), faces "f a//a b//b c//c" counted from 1, and `mtllib` / `usemtl` naming the
// slime's material.
//
// Axes: OBJ's convention (Blender's and most importers' default) is y up; the simulation's is z up.
// UpAxis::Y writes each point and normal (x, y, z) as (x, z, −y), a rotation of −90° about x, so the
// slime stands upright where it is read y-up (Blender's default import turns it back into (x, y, z)).
// UpAxis::Z writes the simulation's coordinates unchanged.
#pragma once

#include "core/export/export_material.h"
#include "core/export/surface_mesh.h"

#include <string>

namespace slime {

enum class UpAxis { Y, Z };

// "y" or "z" (`--obj-up`); a SettingsError naming the option and the allowed values otherwise.
UpAxis upAxisNamed(const std::string& name, const std::string& option = "--obj-up");

// The simulation's (z-up) vector as the file writes it.
glm::dvec3 toFileAxes(const glm::dvec3& v, UpAxis up);

// `materialFile`: the .mtl's name as the OBJ refers to it (beside the OBJ, so a bare file name).
std::string objText(const SurfaceMesh& mesh, UpAxis up, const std::string& materialFile);

// The material "slime" (export_material.h) in MTL's terms: Ka 0 (not metallic), Kd = colour,
// Ks = slime.specular, Ns = 1000 (1 − r)² from the .glb's roughness r (Blender's reading of Ns), Ni = IOR,
// d = 1 (not dissolved: the light goes through by refraction), Tf = the transmission, grey, and illum 7
// (refraction with Fresnel reflection). MTL has no absorption inside: as in glTF's transmission, the
// colour (Kd) tints what passes; Blender reads Tf as its Principled BSDF's transmission and tints it with
// Kd, which for the default jelly is within 1 % of what the renderer's absorption leaves after the mean
// chord (docs/export.md).
std::string mtlText(const ExportMaterial& material);

}  // namespace slime

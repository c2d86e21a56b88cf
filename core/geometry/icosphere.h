// Icosphere: an icosahedron whose faces are recursively split in four, with every new vertex pushed
// onto the sphere. Vertices are shared, so level L has 20·4^L faces, 10·4^L + 2 vertices and
// 30·4^L edges; every triangle is wound counter-clockwise seen from outside (outward normals).
#pragma once

#include <glm/ext/vector_uint2_sized.hpp>
#include <glm/ext/vector_uint3_sized.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

using Triangle = glm::u32vec3;  // three vertex indices, counter-clockwise seen from outside

struct TriangleMesh {
  std::vector<glm::dvec3> positions;
  std::vector<Triangle> triangles;
};

constexpr int kMaxLevel = 7;

// The unit-free icosphere of `radius` about `center`; level in [0, kMaxLevel].
TriangleMesh makeIcosphere(int level, double radius, const glm::dvec3& center);

// Each undirected edge once, as (smaller index, larger index), sorted.
std::vector<glm::u32vec2> uniqueEdges(const std::vector<Triangle>& triangles);

}  // namespace slime

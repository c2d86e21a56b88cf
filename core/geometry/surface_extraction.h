// A closed, watertight surface made afresh from a scalar field on a grid, for a piece whose drawn
// surface cannot be carried over (a piece torn off, two pieces merged): the field is positive inside.
// Naive surface nets (Gibson 1998) place one vertex in each grid cell the surface crosses, at the mean
// of the crossings along its edges, and join the four cells about each grid edge the surface crosses by
// a quad split along its shorter diagonal: well-shaped triangles of about the grid's spacing, where
// marching tetrahedra leave slivers whose normals jump by tens of degrees. Where a cell face is a saddle
// (its diagonal corners inside) the nets would not be manifold: a corner near zero changes side first
// (resolveSaddleFaces); should the nets still not be closed and manifold, the whole surface is made by
// marching tetrahedra (each grid cell cut into six tetrahedra about its main diagonal, the same in every cell:
// no cracks, no ambiguous cases). Taubin's λ|μ smoothing (Taubin 1995) takes out the grid's steps
// without shrinking the surface. The fields come from closed surfaces (signedDistanceOnGrid: inside by
// ray parity along the grid's columns, the distance exact near the surface) and are combined by min
// (intersection) and a smooth max (union).
#pragma once

#include "core/geometry/icosphere.h"
#include "core/geometry/surface_view.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace slime {

struct ScalarGrid {
  glm::dvec3 origin{0.0};      // the point of index (0, 0, 0), m
  double spacing = 0.0;        // m
  glm::ivec3 size{0};          // points along x, y, z
  std::vector<double> values;  // x fastest, then y, then z

  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(size.x) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(size.y) * static_cast<std::size_t>(k));
  }
  glm::dvec3 point(int i, int j, int k) const { return origin + spacing * glm::dvec3(i, j, k); }
  std::size_t count() const { return static_cast<std::size_t>(size.x) * size.y * size.z; }
};

// A grid of `spacing` over the box [low, high] grown by `margin` on every side, values zero.
ScalarGrid gridAround(const glm::dvec3& low, const glm::dvec3& high, double spacing, double margin);

// The signed distance to the closed surface `surface` at every grid point, positive inside: exact
// within √3 spacings of the surface, ±2 spacings farther out (enough for the zero crossing and for a
// smooth union of blend radius up to about two spacings).
void signedDistanceOnGrid(const SurfaceView& surface, ScalarGrid& grid);

// Separable [1 2 1]/4 blur, `passes` times (values at the border kept).
void blurGrid(ScalarGrid& grid, int passes);

// Smooth max of a and b with blend radius k (the polynomial smooth union, for inside-positive fields).
double smoothMax(double a, double b, double k);

// The zero level of `grid` (positive inside) as a closed triangle surface wound counter-clockwise seen
// from outside: surface nets when they are closed and manifold, else marching tetrahedra.
TriangleMesh extractSurface(const ScalarGrid& grid);

// Takes out the saddles of the grid's cell faces (two diagonal corners inside, the other two outside),
// where surface nets would put an edge in four triangles: the corner nearest zero of the pair the
// bilinear field does not join across the face changes side. Returns how many corners changed.
std::size_t resolveSaddleFaces(ScalarGrid& grid);

// The two ways, on their own. Surface nets may leave an edge in four triangles (a saddle face).
TriangleMesh extractSurfaceNets(const ScalarGrid& grid);
TriangleMesh extractSurfaceTetrahedra(const ScalarGrid& grid);

// Every directed edge once and its reverse once: closed, each edge in two triangles, wound alike.
bool isClosedManifold(const TriangleMesh& mesh);

// Keeps the connected part of the surface with the most triangles (a piece is one body: the rest are
// bubbles that a crumpled source surface's inside test leaves); returns how many parts were dropped.
std::size_t keepLargestPart(TriangleMesh& mesh);

// Taubin's smoothing, `passes` pairs of a shrinking step λ and an inflating step μ (umbrella operator).
void taubinSmooth(TriangleMesh& mesh, int passes, double lambda = 0.5, double mu = -0.53);

// The grid's value at p, trilinear (p clamped into the grid).
double sampleGrid(const ScalarGrid& grid, const glm::dvec3& p);

}  // namespace slime

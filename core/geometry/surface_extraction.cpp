#include "core/geometry/surface_extraction.h"

#include "core/geometry/nearest_point.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

namespace slime {
namespace {

int clampIndex(double value, int size) { return std::clamp(static_cast<int>(std::floor(value)), 0, size - 1); }

// The six tetrahedra of a cell, by corner (bit 0: +x, bit 1: +y, bit 2: +z), all about the diagonal 0–7.
constexpr int kCellTetrahedra[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};

}  // namespace

ScalarGrid gridAround(const glm::dvec3& low, const glm::dvec3& high, double spacing, double margin) {
  ScalarGrid grid;
  grid.spacing = spacing;
  // A fraction of a spacing off the box's corner, so that a grid column meets a surface's vertices and
  // edges only by chance (the inside test counts crossings along columns).
  grid.origin = low - glm::dvec3(margin) + spacing * glm::dvec3(0.0137, 0.0291, 0.0071);
  const glm::dvec3 span = high - low + glm::dvec3(2.0 * margin);
  grid.size = glm::ivec3(glm::ceil(span / spacing)) + glm::ivec3(2);
  grid.values.assign(grid.count(), 0.0);
  return grid;
}

void signedDistanceOnGrid(const SurfaceView& surface, ScalarGrid& grid) {
  const double h = grid.spacing;
  const glm::ivec3 n = grid.size;
  // Inside: the crossings of each column (x_i, y_j) with the surface, counted below each point.
  std::vector<std::pair<std::size_t, double>> crossings;  // column, z
  for (const Triangle& t : surface.triangles) {
    const glm::dvec3 a = surface.positions[t.x], b = surface.positions[t.y], c = surface.positions[t.z];
    const glm::dvec3 low = glm::min(a, glm::min(b, c)), high = glm::max(a, glm::max(b, c));
    const int i0 = static_cast<int>(std::ceil((low.x - grid.origin.x) / h)), i1 = static_cast<int>(std::floor((high.x - grid.origin.x) / h));
    const int j0 = static_cast<int>(std::ceil((low.y - grid.origin.y) / h)), j1 = static_cast<int>(std::floor((high.y - grid.origin.y) / h));
    const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (area == 0.0) continue;
    for (int j = std::max(j0, 0); j <= std::min(j1, n.y - 1); ++j)
      for (int i = std::max(i0, 0); i <= std::min(i1, n.x - 1); ++i) {
        const double x = grid.origin.x + h * i, y = grid.origin.y + h * j;
        const double wa = ((b.x - x) * (c.y - y) - (c.x - x) * (b.y - y)) / area;
        const double wb = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;
        const double wc = 1.0 - wa - wb;
        if (wa < 0.0 || wb < 0.0 || wc < 0.0) continue;
        crossings.emplace_back(static_cast<std::size_t>(i) + static_cast<std::size_t>(n.x) * j, wa * a.z + wb * b.z + wc * c.z);
      }
  }
  std::sort(crossings.begin(), crossings.end());
  std::vector<std::uint8_t> inside(grid.count(), 0);
  for (std::size_t first = 0; first < crossings.size();) {
    std::size_t last = first;
    while (last < crossings.size() && crossings[last].first == crossings[first].first) ++last;
    const int i = static_cast<int>(crossings[first].first % n.x), j = static_cast<int>(crossings[first].first / n.x);
    std::size_t below = first;
    for (int k = 0; k < n.z; ++k) {
      const double z = grid.origin.z + h * k;
      while (below < last && crossings[below].second < z) ++below;
      inside[grid.index(i, j, k)] = static_cast<std::uint8_t>((below - first) % 2);
    }
    first = last;
  }
  // Near the surface: a point with a neighbour (of 26) on the other side lies within √3 spacings of it.
  std::vector<std::uint8_t> near(grid.count(), 0);
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const std::uint8_t own = inside[grid.index(i, j, k)];
        bool differs = false;
        for (int dk = -1; dk <= 1 && !differs; ++dk)
          for (int dj = -1; dj <= 1 && !differs; ++dj)
            for (int di = -1; di <= 1 && !differs; ++di) {
              const int a = i + di, b = j + dj, c = k + dk;
              if (a < 0 || b < 0 || c < 0 || a >= n.x || b >= n.y || c >= n.z) continue;
              differs = inside[grid.index(a, b, c)] != own;
            }
        near[grid.index(i, j, k)] = differs;
      }
  std::vector<double>& d = grid.values;
  d.assign(grid.count(), 2.0 * h);
  const double reach = 1.75 * h;
  for (const Triangle& t : surface.triangles) {
    const glm::dvec3 a = surface.positions[t.x], b = surface.positions[t.y], c = surface.positions[t.z];
    const glm::dvec3 boxLow = glm::min(a, glm::min(b, c)), boxHigh = glm::max(a, glm::max(b, c));
    const glm::dvec3 low = (boxLow - glm::dvec3(reach) - grid.origin) / h;
    const glm::dvec3 high = (boxHigh + glm::dvec3(reach) - grid.origin) / h;
    const int i0 = clampIndex(std::ceil(low.x), n.x), i1 = clampIndex(high.x, n.x);
    const int j0 = clampIndex(std::ceil(low.y), n.y), j1 = clampIndex(high.y, n.y);
    const int k0 = clampIndex(std::ceil(low.z), n.z), k1 = clampIndex(high.z, n.z);
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const std::size_t g = grid.index(i, j, k);
          if (!near[g]) continue;
          const glm::dvec3 p = grid.point(i, j, k);
          // No nearer than its box: a triangle whose box is as far as the nearest one found so far
          // cannot lower the distance (most of them, once a point's nearest neighbour has been met).
          const glm::dvec3 outside = glm::max(glm::max(boxLow - p, p - boxHigh), glm::dvec3(0.0));
          if (glm::dot(outside, outside) >= d[g] * d[g]) continue;
          d[g] = std::min(d[g], glm::length(p - closestPointOnTriangle(p, a, b, c)));
        }
  }
  for (std::size_t g = 0; g < d.size(); ++g)
    if (!inside[g]) d[g] = -d[g];
}

void blurGrid(ScalarGrid& grid, int passes) {
  const glm::ivec3 n = grid.size;
  std::vector<double> line;
  for (int pass = 0; pass < passes; ++pass)
    for (int axis = 0; axis < 3; ++axis) {
      const int length = n[axis];
      const std::size_t stride = axis == 0 ? 1 : axis == 1 ? static_cast<std::size_t>(n.x) : static_cast<std::size_t>(n.x) * n.y;
      line.resize(length);
      const int u = n[(axis + 1) % 3], v = n[(axis + 2) % 3];
      for (int b = 0; b < v; ++b)
        for (int a = 0; a < u; ++a) {
          glm::ivec3 start(0);
          start[(axis + 1) % 3] = a;
          start[(axis + 2) % 3] = b;
          const std::size_t base = grid.index(start.x, start.y, start.z);
          for (int s = 0; s < length; ++s) line[s] = grid.values[base + s * stride];
          for (int s = 1; s + 1 < length; ++s)
            grid.values[base + s * stride] = 0.25 * line[s - 1] + 0.5 * line[s] + 0.25 * line[s + 1];
        }
    }
}

double smoothMax(double a, double b, double k) {
  if (k <= 0.0) return std::max(a, b);
  const double mix = std::clamp(0.5 + 0.5 * (a - b) / k, 0.0, 1.0);
  return b + (a - b) * mix + k * mix * (1.0 - mix);
}

TriangleMesh extractSurfaceTetrahedra(const ScalarGrid& grid) {
  TriangleMesh mesh;
  const glm::ivec3 n = grid.size;
  std::unordered_map<std::uint64_t, std::uint32_t> edgeVertex;
  const auto value = [&](std::size_t g) { return grid.values[g]; };
  const auto vertexOn = [&](std::size_t inner, std::size_t outer, const glm::dvec3& p, const glm::dvec3& q) {
    const std::uint64_t key = static_cast<std::uint64_t>(std::min(inner, outer)) * grid.count() + std::max(inner, outer);
    const auto found = edgeVertex.find(key);
    if (found != edgeVertex.end()) return found->second;
    const double a = value(inner), b = value(outer);
    const double t = std::clamp(a / (a - b), 1e-3, 1.0 - 1e-3);
    const auto index = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.push_back(p + t * (q - p));
    edgeVertex.emplace(key, index);
    return index;
  };
  // A triangle wound so that its normal points along `outward`.
  const auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, const glm::dvec3& outward) {
    const glm::dvec3 normal = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (glm::dot(normal, outward) >= 0.0) mesh.triangles.emplace_back(a, b, c);
    else mesh.triangles.emplace_back(a, c, b);
  };
  for (int k = 0; k + 1 < n.z; ++k)
    for (int j = 0; j + 1 < n.y; ++j)
      for (int i = 0; i + 1 < n.x; ++i) {
        std::array<std::size_t, 8> corner;
        std::array<glm::dvec3, 8> at;
        int insideCount = 0;
        for (int c = 0; c < 8; ++c) {
          const int ci = i + (c & 1), cj = j + ((c >> 1) & 1), ck = k + ((c >> 2) & 1);
          corner[c] = grid.index(ci, cj, ck);
          at[c] = grid.point(ci, cj, ck);
          insideCount += value(corner[c]) > 0.0;
        }
        if (insideCount == 0 || insideCount == 8) continue;
        for (const auto& tet : kCellTetrahedra) {
          int in[4], out[4], ins = 0, outs = 0;
          for (int c : tet) (value(corner[c]) > 0.0 ? in[ins++] : out[outs++]) = c;
          if (ins == 0 || outs == 0) continue;
          const auto v = [&](int a, int b) { return vertexOn(corner[a], corner[b], at[a], at[b]); };
          if (ins == 1) {
            const glm::dvec3 outward = (at[out[0]] + at[out[1]] + at[out[2]]) / 3.0 - at[in[0]];
            emit(v(in[0], out[0]), v(in[0], out[1]), v(in[0], out[2]), outward);
          } else if (ins == 3) {
            const glm::dvec3 outward = at[out[0]] - (at[in[0]] + at[in[1]] + at[in[2]]) / 3.0;
            emit(v(in[0], out[0]), v(in[1], out[0]), v(in[2], out[0]), outward);
          } else {
            const glm::dvec3 outward = 0.5 * (at[out[0]] + at[out[1]]) - 0.5 * (at[in[0]] + at[in[1]]);
            const std::uint32_t ac = v(in[0], out[0]), ad = v(in[0], out[1]), bd = v(in[1], out[1]), bc = v(in[1], out[0]);
            emit(ac, ad, bd, outward);
            emit(ac, bd, bc, outward);
          }
        }
      }
  return mesh;
}

bool isClosedManifold(const TriangleMesh& mesh) {
  // Every directed edge once and its reverse once: each edge in exactly two triangles, wound alike.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const Triangle& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) edges.emplace_back(t[e], t[(e + 1) % 3]);
  std::sort(edges.begin(), edges.end());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (e + 1 < edges.size() && edges[e + 1] == edges[e]) return false;
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(edges[e].second, edges[e].first))) return false;
  }
  return true;
}

TriangleMesh extractSurfaceNets(const ScalarGrid& grid) {
  TriangleMesh mesh;
  const glm::ivec3 n = grid.size;
  if (n.x < 2 || n.y < 2 || n.z < 2) return mesh;
  const auto inside = [&](int i, int j, int k) { return grid.values[grid.index(i, j, k)] > 0.0; };
  const glm::ivec3 cells = n - glm::ivec3(1);
  const auto cellIndex = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(cells.x) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(cells.y) * static_cast<std::size_t>(k));
  };
  constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> cellVertex(static_cast<std::size_t>(cells.x) * cells.y * cells.z, kNoVertex);
  // The twelve edges of a cell, by corner (bit 0: +x, bit 1: +y, bit 2: +z).
  constexpr int kCellEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (int k = 0; k < cells.z; ++k)
    for (int j = 0; j < cells.y; ++j)
      for (int i = 0; i < cells.x; ++i) {
        double value[8];
        int insideCount = 0;
        for (int c = 0; c < 8; ++c) {
          value[c] = grid.values[grid.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))];
          insideCount += value[c] > 0.0;
        }
        if (insideCount == 0 || insideCount == 8) continue;
        // The mean of the crossings along the cell's edges, in the cell's own coordinates.
        glm::dvec3 sum(0.0);
        int crossings = 0;
        for (const auto& edge : kCellEdges) {
          const double a = value[edge[0]], b = value[edge[1]];
          if ((a > 0.0) == (b > 0.0)) continue;
          const double t = std::clamp(a / (a - b), 0.0, 1.0);
          const glm::dvec3 p(edge[0] & 1, (edge[0] >> 1) & 1, (edge[0] >> 2) & 1), q(edge[1] & 1, (edge[1] >> 1) & 1, (edge[1] >> 2) & 1);
          sum += p + t * (q - p);
          ++crossings;
        }
        cellVertex[cellIndex(i, j, k)] = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.push_back(grid.point(i, j, k) + grid.spacing * (sum / static_cast<double>(crossings)));
      }
  // A quad of the four cells about each grid edge the surface crosses, split along its shorter
  // diagonal, wound so that its normal points from the inside end of the edge to the outside one.
  const auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d, bool flip) {
    if (flip) std::swap(b, d);
    const glm::dvec3 &pa = mesh.positions[a], &pb = mesh.positions[b], &pc = mesh.positions[c], &pd = mesh.positions[d];
    if (glm::length(pc - pa) <= glm::length(pd - pb)) {
      mesh.triangles.emplace_back(a, b, c);
      mesh.triangles.emplace_back(a, c, d);
    } else {
      mesh.triangles.emplace_back(a, b, d);
      mesh.triangles.emplace_back(b, c, d);
    }
  };
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const bool here = inside(i, j, k);
        // Along +x: the cells (i, j-1|j, k-1|k), counter-clockwise about +x (y, then z).
        if (i + 1 < n.x && j > 0 && k > 0 && j < cells.y && k < cells.z && inside(i + 1, j, k) != here)
          quad(cellVertex[cellIndex(i, j - 1, k - 1)], cellVertex[cellIndex(i, j, k - 1)], cellVertex[cellIndex(i, j, k)],
               cellVertex[cellIndex(i, j - 1, k)], !here);
        // Along +y: about +y (z, then x).
        if (j + 1 < n.y && i > 0 && k > 0 && i < cells.x && k < cells.z && inside(i, j + 1, k) != here)
          quad(cellVertex[cellIndex(i - 1, j, k - 1)], cellVertex[cellIndex(i - 1, j, k)], cellVertex[cellIndex(i, j, k)],
               cellVertex[cellIndex(i, j, k - 1)], !here);
        // Along +z: about +z (x, then y).
        if (k + 1 < n.z && i > 0 && j > 0 && i < cells.x && j < cells.y && inside(i, j, k + 1) != here)
          quad(cellVertex[cellIndex(i - 1, j - 1, k)], cellVertex[cellIndex(i, j - 1, k)], cellVertex[cellIndex(i, j, k)],
               cellVertex[cellIndex(i - 1, j, k)], !here);
      }
  return mesh;
}

std::size_t resolveSaddleFaces(ScalarGrid& grid) {
  const glm::ivec3 n = grid.size;
  std::vector<double>& v = grid.values;
  std::size_t flipped = 0;
  // The faces of the grid's cells, by their lowest corner and the two axes they span.
  const glm::ivec3 axes[3][2] = {{{1, 0, 0}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}}};
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i)
        for (const auto& axis : axes) {
          const glm::ivec3 p(i, j, k), u = p + axis[0], w = p + axis[1], d = p + axis[0] + axis[1];
          if (d.x >= n.x || d.y >= n.y || d.z >= n.z) continue;
          const std::size_t corner[4] = {grid.index(p.x, p.y, p.z), grid.index(u.x, u.y, u.z), grid.index(d.x, d.y, d.z), grid.index(w.x, w.y, w.z)};
          const bool in0 = v[corner[0]] > 0.0, in1 = v[corner[1]] > 0.0;
          if (in0 == in1 || (v[corner[2]] > 0.0) != in0 || (v[corner[3]] > 0.0) != in1) continue;
          // A saddle: the bilinear field's value at the face's centre says which diagonal pair joins
          // across it; the corner of the other pair nearest zero joins them.
          const bool insideJoins = v[corner[0]] + v[corner[1]] + v[corner[2]] + v[corner[3]] > 0.0;
          std::size_t nearest = corner[0];
          double least = std::numeric_limits<double>::infinity();
          for (std::size_t c : corner)
            if ((v[c] > 0.0) != insideJoins && std::abs(v[c]) < least) {
              least = std::abs(v[c]);
              nearest = c;
            }
          v[nearest] = (insideJoins ? 1e-6 : -1e-6) * grid.spacing;
          ++flipped;
        }
  return flipped;
}

TriangleMesh extractSurface(const ScalarGrid& grid) {
  ScalarGrid resolved = grid;
  for (int round = 0; round < 4; ++round)
    if (resolveSaddleFaces(resolved) == 0) break;
  TriangleMesh mesh = extractSurfaceNets(resolved);
  if (isClosedManifold(mesh)) return mesh;
  return extractSurfaceTetrahedra(grid);
}

std::size_t keepLargestPart(TriangleMesh& mesh) {
  const std::size_t count = mesh.positions.size();
  std::vector<std::uint32_t> parent(count);
  for (std::uint32_t v = 0; v < count; ++v) parent[v] = v;
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const Triangle& t : mesh.triangles)
    for (int corner = 1; corner < 3; ++corner) {
      const std::uint32_t a = find(t.x), b = find(t[corner]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<std::size_t> triangles(count, 0);
  for (const Triangle& t : mesh.triangles) ++triangles[find(t.x)];
  std::size_t parts = 0;
  std::uint32_t largest = 0;
  for (std::uint32_t v = 0; v < count; ++v) {
    if (triangles[v] == 0) continue;
    ++parts;
    if (triangles[v] > triangles[largest]) largest = v;
  }
  if (parts <= 1) return 0;
  std::vector<std::uint32_t> newIndex(count, 0);
  std::vector<glm::dvec3> kept;
  for (std::uint32_t v = 0; v < count; ++v)
    if (find(v) == largest) {
      newIndex[v] = static_cast<std::uint32_t>(kept.size());
      kept.push_back(mesh.positions[v]);
    }
  std::vector<Triangle> keptTriangles;
  for (const Triangle& t : mesh.triangles)
    if (find(t.x) == largest) keptTriangles.emplace_back(newIndex[t.x], newIndex[t.y], newIndex[t.z]);
  mesh.positions.swap(kept);
  mesh.triangles.swap(keptTriangles);
  return parts - 1;
}

void taubinSmooth(TriangleMesh& mesh, int passes, double lambda, double mu) {
  const std::size_t count = mesh.positions.size();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  pairs.reserve(mesh.triangles.size() * 6);
  for (const Triangle& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      pairs.emplace_back(t[e], t[(e + 1) % 3]);
      pairs.emplace_back(t[(e + 1) % 3], t[e]);
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<std::uint32_t> start(count + 1, 0);
  for (const auto& p : pairs) ++start[p.first + 1];
  for (std::size_t i = 0; i < count; ++i) start[i + 1] += start[i];
  std::vector<glm::dvec3> moved(count);
  const auto umbrella = [&](double factor) {
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t begin = start[i], end = start[i + 1];
      if (begin == end) {
        moved[i] = mesh.positions[i];
        continue;
      }
      glm::dvec3 mean(0.0);
      for (std::uint32_t k = begin; k < end; ++k) mean += mesh.positions[pairs[k].second];
      mean /= static_cast<double>(end - begin);
      moved[i] = mesh.positions[i] + factor * (mean - mesh.positions[i]);
    }
    mesh.positions.swap(moved);
  };
  for (int pass = 0; pass < passes; ++pass) {
    umbrella(lambda);
    umbrella(mu);
  }
}

double sampleGrid(const ScalarGrid& grid, const glm::dvec3& p) {
  const glm::dvec3 u = (p - grid.origin) / grid.spacing;
  const glm::ivec3 low = glm::clamp(glm::ivec3(glm::floor(u)), glm::ivec3(0), grid.size - glm::ivec3(2));
  const glm::dvec3 f = glm::clamp(u - glm::dvec3(low), glm::dvec3(0.0), glm::dvec3(1.0));
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
    const double w = (dx ? f.x : 1.0 - f.x) * (dy ? f.y : 1.0 - f.y) * (dz ? f.z : 1.0 - f.z);
    value += w * grid.values[grid.index(low.x + dx, low.y + dy, low.z + dz)];
  }
  return value;
}

}  // namespace slime

#include "core/bulk/bulk_body.h"

#include "core/contact/floor_contact.h"
#include "core/geometry/volume.h"
#include "core/bulk/element_pass.h"
#include "core/bulk/tet_lanes.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slime {
namespace {

static_assert(kTetLanes % kLaneWidth == 0, "a block holds whole vectors of lanes");

std::size_t edgeIndex(const std::vector<glm::u32vec2>& edges, std::uint32_t a, std::uint32_t b) {
  const glm::u32vec2 key{std::min(a, b), std::max(a, b)};
  const auto it = std::lower_bound(edges.begin(), edges.end(), key, [](const auto& l, const auto& r) {
    return l.x != r.x ? l.x < r.x : l.y < r.y;
  });
  return static_cast<std::size_t>(it - edges.begin());
}

// One lane's 3×3 matrix from entries stored [3·column + row][lane], and back.
inline glm::dmat3 laneMatrix(const ElementReal (&entries)[9][kTetLanes], std::size_t lane) {
  return glm::dmat3(entries[0][lane], entries[1][lane], entries[2][lane], entries[3][lane], entries[4][lane],
                    entries[5][lane], entries[6][lane], entries[7][lane], entries[8][lane]);
}
inline void setLaneMatrix(ElementReal (&entries)[9][kTetLanes], std::size_t lane, const glm::dmat3& m) {
  for (int entry = 0; entry < 9; ++entry) entries[entry][lane] = static_cast<ElementReal>(m[entry / 3][entry % 3]);
}

// Whether a surface triangle may carry a drawn vertex below the floor: the drawn surface bulges past
// the flat body triangle by a small fraction of the triangle's size, so a triangle whose lowest node
// is more than half its longest edge up cannot (in squares: no square roots).
bool mayTouchFloor(const std::vector<glm::dvec3>& x, const Triangle& triangle) {
  const double lowest = std::min({x[triangle.x].z, x[triangle.y].z, x[triangle.z].z});
  const glm::dvec3 a = x[triangle.y] - x[triangle.x], b = x[triangle.z] - x[triangle.y], c = x[triangle.x] - x[triangle.z];
  const double spanSquared = std::max({glm::dot(a, a), glm::dot(b, b), glm::dot(c, c)});
  return !(lowest > 0.0 && lowest * lowest > 0.25 * spanSquared);
}

// visit(t, w, z) for each floor point (BulkBody::floorPoints, or the drawn vertices where that is empty)
// over a surface triangle that may touch the floor: the element map's nodes t and weights w, and the
// point's height z (read when it is visited, so a visit that moves nodes is seen by the next).
template <typename Visit>
void forEachFloorPointNearFloor(const BulkBody& body, Visit&& visit) {
  const std::vector<glm::dvec3>& x = body.state.positions;
  const SurfaceEmbedding& points = body.floorPoints.nodes.empty() ? body.embedding : body.floorPoints;
  for (std::size_t s = 0; s < body.mesh.surface.size(); ++s) {
    if (!mayTouchFloor(x, body.mesh.surface[s])) continue;
    for (std::uint32_t vertex : points.verticesOfSurfaceTriangle[s]) {
      const Tetrahedron& t = points.nodes[vertex];
      const glm::dvec4& w = points.weights[vertex];
      visit(t, w, w.x * x[t.x].z + w.y * x[t.y].z + w.z * x[t.z].z + w.w * x[t.w].z);
    }
  }
}

}  // namespace

BulkBody buildBulkBody(const SlimeSettings& slime) {
  BulkBody body;
  body.mesh = makeBallTetMesh(slime.resolution, slime.radius, slime.position);
  const TetMesh& mesh = body.mesh;
  body.state.positions = mesh.positions;
  body.state.velocities.assign(mesh.positions.size(), glm::dvec3(0.0));
  body.rest.reserve(mesh.tetrahedra.size());
  for (const Tetrahedron& t : mesh.tetrahedra) {
    body.rest.push_back(makeTetRest(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z], mesh.positions[t.w]));
    body.restVolume += body.rest.back().volume;
  }
  body.restBlocks.resize((mesh.tetrahedra.size() + kTetLanes - 1) / kTetLanes);
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    TetBlock& block = body.restBlocks[e / kTetLanes];
    for (int entry = 0; entry < 9; ++entry) {
      block.restInverse[entry][e % kTetLanes] = static_cast<ElementReal>(body.rest[e].restInverse[entry / 3][entry % 3]);
      block.forceMap[entry][e % kTetLanes] = static_cast<ElementReal>(body.rest[e].forceMap[entry / 3][entry % 3]);
    }
  }
  body.maxwell.resize(body.restBlocks.size());
  for (MaxwellBlock& block : body.maxwell)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
      setLaneMatrix(block.inverse, lane, glm::dmat3(1.0));
      setLaneMatrix(block.metric, lane, glm::dmat3(1.0));
      for (int entry = 0; entry < 3; ++entry) block.plastic[entry][lane] = 1;
    }
  fillElementBlocks(body);
  body.edges = tetrahedronEdges(mesh.tetrahedra);
  body.edgeColours = colourEdges(body.edges, mesh.positions.size());
  body.drawn = makeIcosphere(slime.level, slime.radius, slime.position);
  const int floorLevel = floorContactLevel(mesh.shellLevel);
  // A drawn sphere coarser than the shells is the body's own nodes (below), and the floor holds those up:
  // level-4 points, on the sphere, bulge about 0.5 mm past the faces between them, and a level-1 slime
  // rested that far above the floor, a gap the contact's rays showed as dark specks (ContactLong).
  if (slime.level != floorLevel && slime.level >= mesh.shellLevel)
    body.floorPoints = embedByElements(mesh, makeIcosphere(floorLevel, slime.radius, slime.position), floorLevel);
  if (slime.level >= mesh.shellLevel) {
    body.embedding = embedSurface(mesh, body.drawn, slime.level);
  } else {  // a coarser drawn sphere: its vertices are the first body nodes themselves
    const std::size_t count = body.drawn.positions.size();
    body.embedding.nodes.resize(count);
    body.embedding.weights.assign(count, glm::dvec4(1.0, 0.0, 0.0, 0.0));
    for (std::size_t i = 0; i < count; ++i) body.embedding.nodes[i] = Tetrahedron(static_cast<std::uint32_t>(i));
    body.embedding.smoothStart.resize(count + 1);  // and the smooth map is the same: x_i = x_body[i]
    body.embedding.smoothTerms.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      body.embedding.smoothStart[i] = i;
      body.embedding.smoothTerms[i] = {1.0, i};
    }
    body.embedding.smoothStart[count] = static_cast<std::uint32_t>(count);
    // Each drawn vertex in one body surface triangle that has it as a corner (for the floor contact).
    body.embedding.verticesOfSurfaceTriangle.assign(mesh.surface.size(), {});
    std::vector<bool> placed(count, false);
    for (std::size_t s = 0; s < mesh.surface.size(); ++s)
      for (int corner = 0; corner < 3; ++corner) {
        const std::uint32_t vertex = mesh.surface[s][corner];
        if (vertex >= count || placed[vertex]) continue;
        placed[vertex] = true;
        body.embedding.verticesOfSurfaceTriangle[s].push_back(vertex);
      }
  }
  applyBulkMaterial(body, slime);
  return body;
}

glm::dmat3 maxwellInverse(const BulkBody& body, std::size_t tetrahedron) {
  return laneMatrix(body.maxwell[tetrahedron / kTetLanes].inverse, tetrahedron % kTetLanes);
}

glm::dmat3 plasticMetric(const BulkBody& body, std::size_t tetrahedron) {
  const MaxwellBlock& block = body.maxwell[tetrahedron / kTetLanes];
  const std::size_t lane = tetrahedron % kTetLanes;
  glm::dmat3 g;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) g[c][r] = block.plastic[kSymmetricEntry[r][c]][lane];
  return g;
}

glm::dmat3 plasticInverse(const BulkBody& body, std::size_t tetrahedron) {
  return plasticInverseOf(plasticMetric(body, tetrahedron));
}

double damage(const BulkBody& body, std::size_t tetrahedron) {
  if (body.material.damageStretch <= 0.0) return 0.0;
  const MaxwellBlock& block = body.maxwell[tetrahedron / kTetLanes];
  const std::size_t lane = tetrahedron % kTetLanes;
  return damageOfTrace(double(block.plastic[0][lane]) + block.plastic[1][lane] + block.plastic[2][lane],
                       body.material.damageStretch);
}

double elasticStretch(const BulkBody& body, const std::vector<glm::dvec3>& x, std::size_t tetrahedron) {
  const Tetrahedron& t = body.mesh.tetrahedra[tetrahedron];
  const glm::dmat3 f = deformationGradient(body.rest[tetrahedron], x[t.x], x[t.y], x[t.z], x[t.w]);
  return equivalentStretch(deviatoricStretchMeasure(f, plasticInverse(body, tetrahedron)));
}

void applyBulkMaterial(BulkBody& body, const SlimeSettings& slime) {
  const TetMesh& mesh = body.mesh;
  body.totalMass = slime.mass;
  const double density = slime.mass / body.restVolume;
  std::vector<double> masses(mesh.positions.size(), 0.0);
  std::vector<double> edgeVolume(body.edges.size(), 0.0);
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = mesh.tetrahedra[e];
    for (int i = 0; i < 4; ++i) {
      masses[t[i]] += density * body.rest[e].volume / 4.0;
      for (int j = i + 1; j < 4; ++j) edgeVolume[edgeIndex(body.edges, t[i], t[j])] += body.rest[e].volume / 6.0;
    }
  }
  body.freeInverseMasses.resize(masses.size());
  for (std::size_t i = 0; i < masses.size(); ++i) body.freeInverseMasses[i] = 1.0 / masses[i];
  // Pinned nodes (w = 0) stay pinned; the others take the new masses.
  if (body.state.inverseMasses.size() != masses.size()) body.state.inverseMasses = body.freeInverseMasses;
  for (std::size_t i = 0; i < masses.size(); ++i)
    if (body.state.inverseMasses[i] != 0.0) body.state.inverseMasses[i] = body.freeInverseMasses[i];

  body.material.longTermShear = slime.longTerm * slime.modulus;
  body.material.maxwellShear = (1.0 - slime.longTerm) * slime.modulus;
  body.material.lameLambda = lameLambdaFor(slime.modulus, slime.poisson);
  body.material.relaxationTime = slime.relaxation;
  body.material.plastic = slime.plastic;
  body.material.yieldStretch = slime.yieldStretch;
  body.material.plasticFlowTime = slime.flowTime;
  body.material.recoveryTime = slime.recoveryTime;
  // Damage scales the long-term force maps K_p (element_pass.h): a change refreshes them (a torn part's body is
  // filled before its material is applied).
  const double damageStretch = slime.plastic && slime.damage ? slime.damageStretch : 0.0;
  const bool damageChanged = damageStretch != body.material.damageStretch;
  body.material.damageStretch = damageStretch;
  body.edgeDamping.resize(body.edges.size());
  for (std::size_t s = 0; s < body.edges.size(); ++s) {
    const glm::dvec3 d = mesh.positions[body.edges[s].y] - mesh.positions[body.edges[s].x];
    body.edgeDamping[s] = slime.viscosity * edgeVolume[s] / glm::dot(d, d);
  }
  if (damageChanged && !body.restBlocks.empty()) refreshMaxwellForceMaps(body, true);
}

void bulkInternalForces(const BulkBody& body, const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                        std::vector<glm::dvec3>& forces, bool dampers) {
  // Elastic and Maxwell branches: f = −V0 P Dm⁻ᵀ on nodes 1..3, the opposite of their sum on node 0
  // (element_pass.h: gathered, stressed and scattered kLaneWidth tetrahedra at a time).
  elementForces(body, x, forces);
  // The seed's damper along each edge: −k_d ((v_j − v_i)·u) u on i's side, u the unit edge.
  if (dampers) {
    for (std::size_t s = 0; s < body.edges.size(); ++s) {
      const std::uint32_t i = body.edges[s].x, j = body.edges[s].y;
      const glm::dvec3 d = x[j] - x[i];
      const double lengthSquared = glm::dot(d, d);
      if (lengthSquared <= 0.0) continue;
      const glm::dvec3 force = (body.edgeDamping[s] * glm::dot(v[j] - v[i], d) / lengthSquared) * d;
      forces[i] += force;
      forces[j] -= force;
    }
  }
}

void dampEdges(const BulkBody& body, double h, BulkScratch& scratch, ParticleState& state) {
  const std::vector<double>& w = state.inverseMasses;
  const std::vector<std::uint32_t>& order = body.edgeColours.order;
  const std::size_t count = body.edges.size();
  if (scratch.decayStep != h || scratch.edgeDecay.size() != count) {
    const bool coloured = order.size() == count;  // else the edges' own order
    scratch.dampedPairs.resize(count);
    scratch.edgeDecay.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t s = coloured ? order[k] : k;
      scratch.dampedPairs[k] = body.edges[s];
      scratch.edgeDecay[k] = 1.0 - std::exp(-body.edgeDamping[s] * (w[body.edges[s].x] + w[body.edges[s].y]) * h);
    }
    scratch.decayStep = h;
  }
  // Pair after pair, colour after colour. Within a colour no two pairs share a node, so no pair waits
  // on the one before it; the change is (w_i, w_j)·a·((v_j − v_i)·d) d with a = decay/(|d|² (w_i + w_j)).
  const glm::u32vec2* pairs = scratch.dampedPairs.data();
  const double* decay = scratch.edgeDecay.data();
  const glm::dvec3* x = state.positions.data();
  glm::dvec3* v = state.velocities.data();
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t i = pairs[k].x, j = pairs[k].y;
    const double inverseMassSum = w[i] + w[j];
    if (inverseMassSum <= 0.0) continue;
    const glm::dvec3 d = x[j] - x[i];
    const double lengthSquared = glm::dot(d, d);
    if (lengthSquared <= 0.0) continue;
    const double share = decay[k] / (lengthSquared * inverseMassSum);
    const double relativeSpeed = glm::dot(v[j] - v[i], d);
    v[i] += (w[i] * share * relativeSpeed) * d;
    v[j] -= (w[j] * share * relativeSpeed) * d;
  }
}

void projectBulkVolume(const BulkBody& body, double h, BulkScratch& scratch, ParticleState& state,
                       const std::vector<double>* floor) {
  // One pass over the surface triangles for 6V and 6∇V (volume.h's sums, about the first node; the
  // surface triangles hold only the surface nodes 0..N_s−1), one over those nodes for Σ w|∇V|².
  const std::size_t surfaceNodes = body.mesh.surfaceNodes;
  std::vector<glm::dvec3>& gradient = scratch.volumeGradient;  // 6∇V
  std::vector<glm::dvec3>& x = state.positions;
  if (surfaceNodes == 0) return;
  if (floor != nullptr && floor->size() != x.size())
    throw std::invalid_argument("projectBulkVolume: a floor of " + std::to_string(floor->size()) + " heights for " +
                                std::to_string(x.size()) + " nodes");
  const double sixTimesVolume = sixTimesVolumeGradient(x, body.mesh.surface, surfaceNodes, gradient);
  // A node lying on the floor is held by it (as a pinned node is by the hand): it does not move.
  const std::vector<double>& w = state.inverseMasses;
  const auto free = [&](std::size_t i) { return x[i].z > (floor != nullptr ? (*floor)[i] : 0.0); };
  double resistance = 0.0;  // Σ w_i |6∇_i V|²
  for (std::size_t i = 0; i < surfaceNodes; ++i)
    resistance += (free(i) ? w[i] : 0.0) * glm::dot(gradient[i], gradient[i]);
  if (resistance <= 0.0) return;
  // Δx_i = (V0 − V) w_i ∇_i V / Σ w|∇V|² = 6 (V0 − V) w_i (6∇_i V) / Σ w|6∇V|².
  const double multiplier = 6.0 * (body.restVolume - sixTimesVolume / 6.0) / resistance;
  const double inverseStep = 1.0 / h;
  for (std::size_t i = 0; i < surfaceNodes; ++i) {
    if (!free(i)) continue;
    const glm::dvec3 move = (multiplier * w[i]) * gradient[i];
    x[i] += move;
    state.velocities[i] += move * inverseStep;
  }
}

double bulkElasticEnergy(const BulkBody& body, const std::vector<glm::dvec3>& x) {
  double energy = 0.0;
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const glm::dmat3 f = deformationGradient(body.rest[e], x[t.x], x[t.y], x[t.z], x[t.w]);
    energy += body.rest[e].volume * energyDensity(body.material, f, maxwellInverse(body, e), plasticInverse(body, e));
  }
  return energy;
}

void relaxBulk(BulkBody& body, double dt) {
  const PlasticFlow plastic = plasticFlowOver(body.material, dt);
  if (body.material.maxwellShear <= 0.0 && plastic.flow <= 0.0) return;
  relaxElements(body, std::exp(-dt / body.material.relaxationTime), plastic);
}

int bulkFlowInterval(const SlimeSettings& slime, double dt, int fewest) {
  const double shortest = slime.plastic ? std::min(slime.relaxation, slime.flowTime) : slime.relaxation;
  return maxwellFlowInterval(shortest, dt, fewest);
}

std::size_t resolveDrawnFloorContact(BulkBody& body, double friction) {
  ParticleState& state = body.state;
  std::size_t touched = 0;
  // The element map's point (4 terms), not the smooth one the drawn surface shows (~45 terms: 6× the
  // step's cost at level 6, and lifting ~45 nodes per vertex in one pass left drawn vertices 0.95 mm
  // under the floor in the torture runs). The smooth map's vertices are set on the floor where they dip
  // under it when placed (bulk_piece.cpp's liftOntoFloor).
  forEachFloorPointNearFloor(body, [&](const Tetrahedron& t, const glm::dvec4& w, double z) {
    if (z >= 0.0) return;
    // Only the nodes with positive weights lift the vertex (a node the affine map extrapolates
    // with a negative weight would be pushed down); lifted nodes lose their downward speed.
    double stiffness = 0.0;  // Σ w_j² / m_j over those nodes
    for (int j = 0; j < 4; ++j)
      if (w[j] > 0.0) stiffness += w[j] * w[j] * state.inverseMasses[t[j]];
    if (stiffness <= 0.0) return;
    ++touched;
    const double lift = -z / stiffness;
    for (int j = 0; j < 4; ++j) {
      if (w[j] <= 0.0 || state.inverseMasses[t[j]] == 0.0) continue;
      state.positions[t[j]].z += lift * w[j] * state.inverseMasses[t[j]];
      stopFallWithFriction(state.velocities[t[j]], friction);
    }
  });
  return touched;
}

std::size_t floorPointsNearFloor(const BulkBody& body) {
  std::size_t count = 0;
  forEachFloorPointNearFloor(body, [&](const Tetrahedron&, const glm::dvec4&, double) { ++count; });
  return count;
}

void drawnFloorHeights(const BulkBody& body, std::vector<double>& heights) {
  const std::vector<glm::dvec3>& x = body.state.positions;
  heights.assign(x.size(), 0.0);
  forEachFloorPointNearFloor(body, [&](const Tetrahedron& t, const glm::dvec4& w, double z) {
    int owner = 0;
    for (int j = 1; j < 4; ++j)
      if (w[j] > w[owner]) owner = j;
    heights[t[owner]] = std::max(heights[t[owner]], x[t[owner]].z - std::max(z, 0.0) / w[owner]);
  });
}

double bulkHighestFrequency(const BulkBody& body, BulkScratch& scratch, int iterations) {
  return bulkHighestFrequencyAt(body, body.mesh.positions, scratch, iterations);
}

double bulkHighestFrequencyAt(const BulkBody& body, const std::vector<glm::dvec3>& rest, BulkScratch& scratch,
                              int iterations) {
  // Power iteration on M⁻¹K, K applied as −(f(x + εu) − f(x))/ε at the shape x.
  const std::size_t n = rest.size();
  std::vector<glm::dvec3> base, probe, direction(n);
  // In double lanes: the probe moves each node by ~ε/√n, below float's rounding of an element's edge.
  elementForcesInDouble(body, rest, base);
  for (std::size_t i = 0; i < n; ++i)  // a deterministic start that excites every node
    direction[i] = glm::dvec3(std::sin(1.0 + 3.0 * i), std::cos(2.0 + 5.0 * i), std::sin(3.0 + 7.0 * i));
  const double epsilon = 1e-8;  // m, along a unit vector over all nodes
  double eigenvalue = 0.0;
  std::vector<glm::dvec3>& displaced = scratch.positions;
  for (int k = 0; k < iterations; ++k) {
    double norm = 0.0;
    for (const glm::dvec3& d : direction) norm += glm::dot(d, d);
    norm = std::sqrt(norm);
    if (norm == 0.0) return 0.0;
    displaced.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      direction[i] /= norm;
      displaced[i] = rest[i] + epsilon * direction[i];
    }
    elementForcesInDouble(body, displaced, probe);
    double rayleigh = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 next = -(probe[i] - base[i]) / epsilon * body.freeInverseMasses[i];
      rayleigh += glm::dot(next, direction[i]);
      direction[i] = next;
    }
    eigenvalue = rayleigh;
  }
  return std::sqrt(std::max(eigenvalue, 0.0));
}

double bulkHighestDampingRate(const BulkBody& body) {
  std::vector<double> rate(body.mesh.positions.size(), 0.0);
  for (std::size_t s = 0; s < body.edges.size(); ++s) {
    rate[body.edges[s].x] += 2.0 * body.edgeDamping[s];
    rate[body.edges[s].y] += 2.0 * body.edgeDamping[s];
  }
  double highest = 0.0;
  for (std::size_t i = 0; i < rate.size(); ++i) highest = std::max(highest, rate[i] * body.freeInverseMasses[i]);
  return highest;
}

std::size_t invertedBulkElements(const BulkBody& body, const std::vector<glm::dvec3>& x) {
  std::size_t inverted = 0;
  for (const Tetrahedron& t : body.mesh.tetrahedra)
    if (glm::determinant(glm::dmat3(x[t.y] - x[t.x], x[t.z] - x[t.x], x[t.w] - x[t.x])) <= 0.0) ++inverted;
  return inverted;
}

}  // namespace slime

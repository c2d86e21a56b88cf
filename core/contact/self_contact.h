// Self-contact: the slime's drawn surface does not pass through itself, nor through another piece's,
// and touching surfaces cling and peel by the sticky floor's law (floor_adhesion.h).
//
// A position-level contact on the drawn surface, as the floor's (resolveDrawnFloorContact): once per
// step, a drawn vertex that has crossed a drawn triangle it is not a neighbour of at rest is put back
// on that triangle's front, by moving the body nodes that carry the vertex and the triangle (the
// element map, surface_embedding.h) along the triangle's normal n in proportion to g_j / m_j, g_j the
// node's coefficient in the gap C = (x_v − x_t)·n (+φ_j for the vertex's nodes, −β_k φ_kj for the
// triangle's, β its barycentric coordinates; Σ g_j = 0, so momentum is kept); the pair's relative
// normal approach speed is removed the same way, and Coulomb friction (slime.friction) takes at most μ
// times that from its relative sliding. XPBD with zero compliance along a fixed normal (Macklin et al.
// 2016): Δx_j = −C g_j w_j n / Σ g² w.
//
// Which vertex has crossed: it lies behind the triangle (0 > C > −band, projecting inside it) now,
// and lay in front of it at the end of the last step (continuous in time, so a vertex that is inside
// the body legitimately — the far side of a pressed or thin slab — is never pushed through it).
// Neighbours at rest are in contact only where the surface has folded: two outer triangles of one body
// whose rest centroids are nearer than kSelfContactExclusion rest edges are skipped (a crease bends them
// towards each other) unless their normals have turned more than 60° apart and they are not each behind
// the other's plane (a crumple under a pressing hand); then only drawn vertices and triangles nearer at
// rest than kSelfContactDrawnExclusion drawn edges are skipped. Where an element that carries the vertex
// or the triangle is inverted (a slam turns elements inside out, and the drawn surface with them), there
// is no contact: its triangle's front faces into the body.
//
// Cost: a broad phase every kSelfContactBroadInterval steps on the bodies' outer triangles (a few
// hundred), balls grown by what the fastest node can travel meanwhile relative to its body's mean
// (a body falling or carried whole keeps its pairs), sorted and swept along x; pairs that lie each
// wholly behind the other's plane are dropped (every pair of an unfolded, convex slime, and a
// pancake's top and bottom); the drawn vertices are tested only against the drawn triangles of the
// outer triangles whose balls met. A slime that touches nothing costs one broad phase per interval. Serial, in a fixed order: the same
// result whatever the thread count.
//
// Cling (slime.cling, Pa): a vertex pushed out sticks to its triangle. Stuck, it is held there against
// a separating pull up to σ(t) A_v (A_v a third of its drawn triangles' rest area, σ(t) the floor's
// contact ageing), read as the floor reads it, F = m_eff |Δ| / h², m_eff = 1 / Σ g² w; held, it creeps
// apart at the floor's creep law; pulled harder it peels only on the contact's edge (a drawn neighbour
// not stuck), so a peel runs in from the edge as a front; peeled, it sticks again only after it has
// left the cling band (2 × kClingBand). Only the normal pull: sliding is left to friction.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/geometry/particle_state.h"

#include <glm/ext/vector_uint4_sized.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace slime {

// Steps between broad phases, at most; fewer while a node moves farther than kSelfContactTravel mean
// rest outer edges in that many steps (the boxes are grown by that much).
constexpr int kSelfContactBroadInterval = 8;
constexpr double kSelfContactTravel = 0.25;
// Outer triangles of one body whose rest centroids lie within this many mean rest outer edges are
// neighbours: never in contact.
constexpr double kSelfContactExclusion = 3.5;
// ... unless they have folded towards each other (a crumple under a hand): the cosine between their
// normals is below this, and they are not each behind the other's plane.
constexpr double kSelfContactFacing = 0.5;
// Within such a pair, a drawn vertex nearer at rest than this many mean drawn edges to a drawn
// triangle's centroid is its neighbour (a corner of it, or of one beside it): never in contact.
constexpr double kSelfContactDrawnExclusion = 2.0;
// How far behind a triangle a crossing is sought, in mean rest outer edges (a vertex moves far less in a step).
constexpr double kSelfContactBand = 0.25;
// The gap a contact leaves between the sheets, m: the drawn surface is placed by the smooth map, which
// differs from the element map the contact holds by a fraction of a millimetre where a sheet bends.
constexpr double kSelfContactSkin = 0.0003;
// A stuck vertex farther than this from its triangle on the contact's edge has peeled, m.
constexpr double kClingBand = 0.001;

// One body as the self-contact sees it: its nodes, its outer triangles over them, and the drawn surface
// riding on them by the element map (surface_embedding.h). The spans are borrowed for one call.
struct ContactBody {
  ParticleState* state = nullptr;
  std::span<const glm::dvec3> restNodes;  // node positions at rest
  std::span<const Triangle> surface;      // the body's outer triangles, over node indices
  std::span<const Triangle> drawnTriangles;
  std::span<const glm::u32vec4> carriers;  // per drawn vertex, its four element-map nodes
  std::span<const glm::dvec4> weights;     // and their weights (Σ = 1)
  std::span<const std::vector<std::uint32_t>> verticesOfSurfaceTriangle;  // per outer triangle, the drawn vertices over it
};

struct SelfContactOptions {
  double friction = 0.6;  // Coulomb coefficient between the sheets (slime.friction)
  double cling = 0.0;     // σ_c, Pa (slime.cling); 0 = none
  double dt = 0.001;      // the step, s
};

class SelfContact {
 public:
  // After a step: pushes out the drawn vertices that crossed a drawn triangle of their own body or of
  // another, and holds or peels the clinging ones. Returns how many vertices were pushed out.
  std::size_t resolve(std::span<const ContactBody> bodies, const SelfContactOptions& options);
  // Forgets the last step's positions and every contact (after a rollback, or when the bodies change).
  void forget();

  std::size_t clingingCount() const;                         // vertices stuck now
  std::size_t peeledCount() const { return peeled_; }         // vertices peeled since forget
  std::size_t candidatePairs() const { return pairs_.size(); }  // outer-triangle pairs of the last broad phase

 private:
  struct Node {  // a node's share in one contact's gap
    ParticleState* state;
    std::uint32_t index;
    double coefficient;  // g_j
  };
  struct BodyCache {  // per body: what follows from its rest shape, its last positions and its contacts
    std::size_t nodeCount = 0, drawnCount = 0, surfaceCount = 0;
    double meanEdge = 0.0;                      // of the outer triangles at rest, m
    double meanDrawnEdge = 0.0;                 // of the drawn triangles at rest, m
    std::vector<glm::dvec3> restDrawn;          // per drawn vertex, where the element map places it at rest
    std::vector<glm::dvec3> restCentroids;      // per outer triangle
    std::vector<double> patchScale;             // per outer triangle: its drawn patch's reach / its corners', at rest
    std::vector<std::uint32_t> ownedStart, owned;  // per outer triangle, the drawn triangles over it (CSR)
    std::vector<std::uint32_t> neighbourStart, neighbours;  // drawn vertices' neighbours (CSR)
    std::vector<double> restArea;               // per drawn vertex, a third of its triangles' rest area, m²
    std::vector<glm::dvec3> previous;           // node positions after the last step's contact
    std::vector<glm::dvec3> atBroad;            // node positions at the last broad phase
    bool hasPrevious = false;
    std::vector<std::uint8_t> stuck, left;      // per drawn vertex: clinging; peeled and not yet away
    std::vector<std::uint32_t> partnerBody, partnerTriangle;
    std::vector<glm::dvec3> partnerBarycentric;
    std::vector<double> age;                    // s in contact
    std::vector<std::uint64_t> touched;         // the step a contact last pushed it out
  };
  struct Pair {
    std::uint32_t bodyA, triangleA, bodyB, triangleB;
    bool near;  // of one body, within the exclusion at rest (and folded towards each other)
  };

  bool matches(std::span<const ContactBody> bodies) const;
  void build(std::span<const ContactBody> bodies);
  void broadPhase(std::span<const ContactBody> bodies, const SelfContactOptions& options);
  std::size_t vertexAgainstTriangles(std::span<const ContactBody> bodies, std::uint32_t a, std::uint32_t sa,
                                     std::uint32_t b, std::uint32_t sb, bool near, const SelfContactOptions& options);
  void cling(std::span<const ContactBody> bodies, const SelfContactOptions& options);
  void gather(const ContactBody& vertexBody, std::uint32_t vertex, const ContactBody& triangleBody,
              std::uint32_t triangle, const glm::dvec3& barycentric, bool sameBody);
  double stiffness() const;  // Σ g² w over nodes_
  void moveAlong(const glm::dvec3& normal, double gap, double stiffness);
  double relativeSpeed(const glm::dvec3& normal) const;
  void stopApproach(const glm::dvec3& normal, double stiffness, double friction, bool separating);

  std::vector<BodyCache> bodies_;
  std::vector<Pair> pairs_;
  std::vector<Node> nodes_;  // scratch: the contact being resolved
  int stepsToBroad_ = 0;
  std::uint64_t step_ = 0;
  std::size_t peeled_ = 0;
  bool contactsLeft_ = false;  // some vertex clings, or has peeled and not yet left
};

}  // namespace slime

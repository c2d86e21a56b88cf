#include "core/contact/self_contact.h"

#include "core/contact/floor_adhesion.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

// A crossing counts where the vertex projects inside the triangle, up to this much of it past an edge
// (so a vertex crossing right at an edge between two triangles is caught by one of them).
constexpr double kEdgeSlack = 0.02;
// A vertex lay in front of the triangle at the last step if at most this far behind it, m (the other
// contacts of that step may have moved it a little after its own; they leave it kSelfContactSkin in front).
constexpr double kPreviousSlack = 0.00025;
// A clinging vertex whose projection has slid this far past its triangle's edge lets go of it.
constexpr double kSlideOff = 0.25;

glm::dvec3 place(const ContactBody& body, std::uint32_t vertex, std::span<const glm::dvec3> nodes) {
  const glm::u32vec4& c = body.carriers[vertex];
  const glm::dvec4& w = body.weights[vertex];
  return w.x * nodes[c.x] + w.y * nodes[c.y] + w.z * nodes[c.z] + w.w * nodes[c.w];
}

// The unit normal of abc (zero for a flat one) and p's barycentric coordinates in its plane.
glm::dvec3 unitNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  return length > 0.0 ? n / length : glm::dvec3(0.0);
}
glm::dvec3 barycentricInPlane(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, q = p - a;
  const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
  const double d20 = glm::dot(q, e1), d21 = glm::dot(q, e2);
  const double denominator = d00 * d11 - d01 * d01;
  if (denominator <= 0.0) return glm::dvec3(-1.0);
  const double beta1 = (d11 * d20 - d01 * d21) / denominator, beta2 = (d00 * d21 - d01 * d20) / denominator;
  return {1.0 - beta1 - beta2, beta1, beta2};
}
glm::dvec3 clampedBarycentric(glm::dvec3 beta) {
  beta = glm::max(beta, glm::dvec3(0.0));
  const double sum = beta.x + beta.y + beta.z;
  return sum > 0.0 ? beta / sum : glm::dvec3(1.0 / 3.0);
}
double smallest(const glm::dvec3& v) { return std::min({v.x, v.y, v.z}); }

// A drawn triangle's corners placed from `nodes`.
struct Corners {
  glm::dvec3 a, b, c;
};
Corners corners(const ContactBody& body, std::uint32_t triangle, std::span<const glm::dvec3> nodes) {
  const Triangle& t = body.drawnTriangles[triangle];
  return {place(body, t.x, nodes), place(body, t.y, nodes), place(body, t.z, nodes)};
}

// Whether the tetrahedron that carries a drawn vertex is inverted now (its carriers are a
// tetrahedron's nodes, positively oriented at rest: tet_mesh.h). Where a slam or a squeeze turns an
// element inside out, the element map turns the drawn surface over it inside out too: its triangles'
// fronts face into the body, and a contact there would push the sheets through each other.
bool carriedInverted(const ContactBody& body, std::uint32_t vertex, std::span<const glm::dvec3> nodes) {
  const glm::u32vec4& c = body.carriers[vertex];
  const glm::dvec3 a = nodes[c.x];
  return glm::dot(nodes[c.y] - a, glm::cross(nodes[c.z] - a, nodes[c.w] - a)) <= 0.0;
}

// How far a drawn patch may stand off its outer triangle's plane, in mean rest outer edges (the broad
// phase's back-to-back test allows this much).
constexpr double kSelfContactBulge = 0.25;

// Whether two outer triangles lie each wholly behind the other's plane by more than `margin` (the
// drawn patch's bulge off its triangle, the band, and what both may travel before the next broad
// phase): then no drawn vertex over one can come to the other from its front. On a slime that is not
// folded every pair is so (a convex surface lies behind each of its tangent planes), and so are the
// top and bottom of a pancake, whose balls meet.
// np and nq their unit normals.
bool backToBack(const ContactBody& first, std::uint32_t s, const glm::dvec3& np, const ContactBody& second, std::uint32_t t,
                const glm::dvec3& nq, double margin) {
  const std::vector<glm::dvec3>&x = first.state->positions, &y = second.state->positions;
  const Triangle &p = first.surface[s], &q = second.surface[t];
  const double qInFront = std::max({glm::dot(y[q.x] - x[p.x], np), glm::dot(y[q.y] - x[p.x], np), glm::dot(y[q.z] - x[p.x], np)});
  if (qInFront > -margin) return false;
  const double pInFront = std::max({glm::dot(x[p.x] - y[q.x], nq), glm::dot(x[p.y] - y[q.x], nq), glm::dot(x[p.z] - y[q.x], nq)});
  return pInFront < -margin;
}

// Whether two outer triangles of one body (unit normals np, nq) have folded towards each other: their
// normals turned more than acos(kSelfContactFacing) apart, and not each centroid behind the other's
// plane (the convex rim of a slime sagging on the floor, whose pairs would cost and never meet). Only
// then can neighbours at rest meet, as in the crumple under a pressing hand.
bool folded(const ContactBody& body, std::uint32_t s, const glm::dvec3& np, std::uint32_t t, const glm::dvec3& nq) {
  const std::vector<glm::dvec3>& x = body.state->positions;
  const Triangle &p = body.surface[s], &q = body.surface[t];
  if (glm::dot(np, nq) >= kSelfContactFacing) return false;
  const glm::dvec3 apart = (x[q.x] + x[q.y] + x[q.z] - x[p.x] - x[p.y] - x[p.z]) / 3.0;
  return !(glm::dot(apart, np) < 0.0 && glm::dot(apart, nq) > 0.0);
}

}  // namespace

void SelfContact::forget() {
  for (BodyCache& cache : bodies_) {
    cache.hasPrevious = false;
    cache.atBroad.clear();
    std::fill(cache.stuck.begin(), cache.stuck.end(), 0);
    std::fill(cache.left.begin(), cache.left.end(), 0);
  }
  pairs_.clear();
  stepsToBroad_ = 0;
  peeled_ = 0;
  contactsLeft_ = false;
}

std::size_t SelfContact::clingingCount() const {
  std::size_t count = 0;
  for (const BodyCache& cache : bodies_) count += static_cast<std::size_t>(std::count(cache.stuck.begin(), cache.stuck.end(), 1));
  return count;
}

bool SelfContact::matches(std::span<const ContactBody> bodies) const {
  if (bodies.size() != bodies_.size()) return false;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].state->size() != bodies_[b].nodeCount || bodies[b].carriers.size() != bodies_[b].drawnCount ||
        bodies[b].surface.size() != bodies_[b].surfaceCount)
      return false;
  return true;
}

void SelfContact::build(std::span<const ContactBody> bodies) {
  bodies_.assign(bodies.size(), BodyCache{});
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const ContactBody& body = bodies[b];
    BodyCache& cache = bodies_[b];
    cache.nodeCount = body.state->size();
    cache.drawnCount = body.carriers.size();
    cache.surfaceCount = body.surface.size();
    // The outer triangles' rest centroids and edges.
    double edgeSum = 0.0;
    for (const Triangle& t : body.surface) {
      const glm::dvec3 &a = body.restNodes[t.x], &b2 = body.restNodes[t.y], &c = body.restNodes[t.z];
      cache.restCentroids.push_back((a + b2 + c) / 3.0);
      for (const double edge : {glm::length(b2 - a), glm::length(c - b2), glm::length(a - c)}) edgeSum += edge;
    }
    cache.meanEdge = body.surface.empty() ? 0.0 : edgeSum / (3.0 * static_cast<double>(body.surface.size()));
    // Each drawn triangle over the outer triangle that carries its first corner.
    std::vector<std::uint32_t> ownerOfVertex(cache.drawnCount, std::numeric_limits<std::uint32_t>::max());
    for (std::size_t s = 0; s < body.verticesOfSurfaceTriangle.size(); ++s)
      for (std::uint32_t v : body.verticesOfSurfaceTriangle[s]) ownerOfVertex[v] = static_cast<std::uint32_t>(s);
    cache.ownedStart.assign(cache.surfaceCount + 1, 0);
    for (const Triangle& t : body.drawnTriangles)
      if (ownerOfVertex[t.x] < cache.surfaceCount) ++cache.ownedStart[ownerOfVertex[t.x] + 1];
    for (std::size_t s = 0; s < cache.surfaceCount; ++s) cache.ownedStart[s + 1] += cache.ownedStart[s];
    cache.owned.resize(cache.ownedStart.back());
    std::vector<std::uint32_t> fill(cache.ownedStart.begin(), cache.ownedStart.end() - 1);
    for (std::uint32_t t = 0; t < body.drawnTriangles.size(); ++t) {
      const std::uint32_t owner = ownerOfVertex[body.drawnTriangles[t].x];
      if (owner < cache.surfaceCount) cache.owned[fill[owner]++] = t;
    }
    // The drawn vertices' neighbours and rest areas.
    std::vector<glm::dvec3>& rest = cache.restDrawn;
    rest.resize(cache.drawnCount);
    for (std::uint32_t v = 0; v < cache.drawnCount; ++v) rest[v] = place(body, v, body.restNodes);
    double drawnEdgeSum = 0.0;
    for (const Triangle& t : body.drawnTriangles)
      drawnEdgeSum += glm::length(rest[t.y] - rest[t.x]) + glm::length(rest[t.z] - rest[t.y]) + glm::length(rest[t.x] - rest[t.z]);
    cache.meanDrawnEdge = body.drawnTriangles.empty() ? 0.0 : drawnEdgeSum / (3.0 * static_cast<double>(body.drawnTriangles.size()));
    // How much farther than its corners from its centroid what is drawn over each outer triangle reaches.
    cache.patchScale.assign(cache.surfaceCount, 1.0);
    for (std::uint32_t s = 0; s < cache.surfaceCount; ++s) {
      const Triangle& outer = body.surface[s];
      const glm::dvec3& centre = cache.restCentroids[s];
      const double corners = std::max({glm::length(body.restNodes[outer.x] - centre), glm::length(body.restNodes[outer.y] - centre),
                                       glm::length(body.restNodes[outer.z] - centre)});
      double patch = corners;
      for (std::uint32_t k = cache.ownedStart[s]; k < cache.ownedStart[s + 1]; ++k) {
        const Triangle& t = body.drawnTriangles[cache.owned[k]];
        patch = std::max({patch, glm::length(rest[t.x] - centre), glm::length(rest[t.y] - centre), glm::length(rest[t.z] - centre)});
      }
      for (std::uint32_t v : body.verticesOfSurfaceTriangle[s]) patch = std::max(patch, glm::length(rest[v] - centre));
      if (corners > 0.0) cache.patchScale[s] = patch / corners;
    }
    std::vector<std::vector<std::uint32_t>> lists(cache.drawnCount);
    cache.restArea.assign(cache.drawnCount, 0.0);
    for (const Triangle& t : body.drawnTriangles) {
      const double third = glm::length(glm::cross(rest[t.y] - rest[t.x], rest[t.z] - rest[t.x])) / 6.0;
      const std::uint32_t corner[3] = {t.x, t.y, t.z};
      for (int k = 0; k < 3; ++k) {
        cache.restArea[corner[k]] += third;
        lists[corner[k]].push_back(corner[(k + 1) % 3]);
        lists[corner[k]].push_back(corner[(k + 2) % 3]);
      }
    }
    cache.neighbourStart.assign(1, 0);
    for (std::vector<std::uint32_t>& list : lists) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      cache.neighbours.insert(cache.neighbours.end(), list.begin(), list.end());
      cache.neighbourStart.push_back(static_cast<std::uint32_t>(cache.neighbours.size()));
    }
    cache.stuck.assign(cache.drawnCount, 0);
    cache.left.assign(cache.drawnCount, 0);
    cache.partnerBody.assign(cache.drawnCount, 0);
    cache.partnerTriangle.assign(cache.drawnCount, 0);
    cache.partnerBarycentric.assign(cache.drawnCount, glm::dvec3(0.0));
    cache.age.assign(cache.drawnCount, 0.0);
    cache.touched.assign(cache.drawnCount, 0);
  }
  pairs_.clear();
  stepsToBroad_ = 0;
}

void SelfContact::broadPhase(std::span<const ContactBody> bodies, const SelfContactOptions& options) {
  struct Ball {  // a bounding ball of what is drawn over one outer triangle
    glm::dvec3 centre;
    double radius;
    std::uint32_t body, triangle;
    glm::dvec3 normal;  // the outer triangle's, now
  };
  // Only motion relative to each other matters: a body that falls or is carried whole keeps its pairs.
  // Each body's nodes are measured from their mean (its velocity, its shift since the last broad
  // phase); the pairs between bodies add how fast and far those means part.
  const auto mean = [](const std::vector<glm::dvec3>& values) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& value : values) sum += value;
    return values.empty() ? sum : sum / static_cast<double>(values.size());
  };
  // The next broad phase comes before the fastest node has travelled kSelfContactTravel edges.
  double fastest = 0.0, parting = 0.0, shortestEdge = std::numeric_limits<double>::infinity();
  std::vector<glm::dvec3> bodyVelocity(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    bodyVelocity[b] = mean(bodies[b].state->velocities);
    for (const glm::dvec3& v : bodies[b].state->velocities) fastest = std::max(fastest, glm::dot(v - bodyVelocity[b], v - bodyVelocity[b]));
    for (std::size_t c = 0; c < b; ++c) parting = std::max(parting, glm::length(bodyVelocity[b] - bodyVelocity[c]));
    shortestEdge = std::min(shortestEdge, bodies_[b].meanEdge);
  }
  const double travel = kSelfContactTravel * shortestEdge;
  // Steps until the next one, counting the step from the last positions, which the crossing test reads.
  const double steps = travel / ((std::sqrt(fastest) + parting) * options.dt) - 1.0;
  stepsToBroad_ = steps >= kSelfContactBroadInterval ? kSelfContactBroadInterval : std::max(1, static_cast<int>(steps));
  // Bodies still where the last broad phase saw them (no node moved by half the travel allowance
  // relative to its body, nor a body by as much relative to another; the balls below carry that besides)
  // have the same pairs: a slime at rest, or falling whole, pays this scan only.
  const double slack = 0.5 * travel;
  const double nodeSlack = bodies.size() > 1 ? 0.5 * slack : slack;
  bool moved = false;
  glm::dvec3 firstShift(0.0);
  for (std::size_t b = 0; b < bodies.size() && !moved; ++b) {
    const std::vector<glm::dvec3>& x = bodies[b].state->positions;
    const std::vector<glm::dvec3>& then = bodies_[b].atBroad;
    moved = then.size() != x.size();
    if (moved) break;
    const glm::dvec3 shift = mean(x) - mean(then);
    if (b == 0) firstShift = shift;
    moved = glm::length(shift - firstShift) > slack;
    for (std::size_t i = 0; i < x.size() && !moved; ++i) {
      const glm::dvec3 own = x[i] - then[i] - shift;
      moved = glm::dot(own, own) > nodeSlack * nodeSlack;
    }
  }
  if (!moved) return;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    bodies_[b].atBroad.assign(bodies[b].state->positions.begin(), bodies[b].state->positions.end());
  // Each outer triangle's ball holds the drawn triangles over it (its corners' ball scaled as at rest:
  // the element map moves them with the triangle), half the band and skin, and what it may travel
  // before the next broad phase. (Balls, not boxes: on the convex rest of a slime, axis-aligned boxes
  // of triangles farther apart than the exclusion met.)
  std::vector<Ball> balls;
  double margin = 0.0;
  for (std::uint32_t b = 0; b < bodies.size(); ++b) {
    const BodyCache& cache = bodies_[b];
    const ContactBody& body = bodies[b];
    margin = std::max(margin, 0.5 * (kSelfContactBand * cache.meanEdge + kSelfContactSkin) + travel + slack);
    const std::vector<glm::dvec3>& x = body.state->positions;
    for (std::uint32_t s = 0; s < cache.surfaceCount; ++s) {
      if (cache.ownedStart[s] == cache.ownedStart[s + 1]) continue;
      const Triangle& outer = body.surface[s];
      Ball ball{(x[outer.x] + x[outer.y] + x[outer.z]) / 3.0, 0.0, b, s, unitNormal(x[outer.x], x[outer.y], x[outer.z])};
      const double corner = std::max({glm::dot(x[outer.x] - ball.centre, x[outer.x] - ball.centre),
                                      glm::dot(x[outer.y] - ball.centre, x[outer.y] - ball.centre),
                                      glm::dot(x[outer.z] - ball.centre, x[outer.z] - ball.centre)});
      ball.radius = std::sqrt(corner) * cache.patchScale[s];
      ball.radius += 0.5 * (kSelfContactBand * cache.meanEdge + kSelfContactSkin) + travel + slack;
      balls.push_back(ball);
    }
  }
  std::sort(balls.begin(), balls.end(), [](const Ball& l, const Ball& r) {
    const double left = l.centre.x - l.radius, right = r.centre.x - r.radius;
    if (left != right) return left < right;
    return l.body != r.body ? l.body < r.body : l.triangle < r.triangle;
  });
  pairs_.clear();
  for (std::size_t i = 0; i < balls.size(); ++i)
    for (std::size_t j = i + 1; j < balls.size() && balls[j].centre.x - balls[j].radius <= balls[i].centre.x + balls[i].radius; ++j) {
      const Ball &p = balls[i], &q = balls[j];
      const glm::dvec3 between = p.centre - q.centre;
      const double reach = p.radius + q.radius;
      if (glm::dot(between, between) > reach * reach) continue;
      bool near = false;
      if (p.body == q.body) {
        const BodyCache& cache = bodies_[p.body];
        const double exclusion = kSelfContactExclusion * cache.meanEdge;
        const glm::dvec3 apart = cache.restCentroids[p.triangle] - cache.restCentroids[q.triangle];
        near = glm::dot(apart, apart) < exclusion * exclusion;
        if (near && !folded(bodies[p.body], p.triangle, p.normal, q.triangle, q.normal)) continue;
      }
      if (backToBack(bodies[p.body], p.triangle, p.normal, bodies[q.body], q.triangle, q.normal,
                     kSelfContactBulge * shortestEdge + 2.0 * margin))
        continue;
      pairs_.push_back({p.body, p.triangle, q.body, q.triangle, near});
    }
  // The sweep's order follows positions; the contacts are resolved in the bodies' own order.
  std::sort(pairs_.begin(), pairs_.end(), [](const Pair& l, const Pair& r) {
    if (l.bodyA != r.bodyA) return l.bodyA < r.bodyA;
    if (l.triangleA != r.triangleA) return l.triangleA < r.triangleA;
    if (l.bodyB != r.bodyB) return l.bodyB < r.bodyB;
    return l.triangleB < r.triangleB;
  });
}

void SelfContact::gather(const ContactBody& vertexBody, std::uint32_t vertex, const ContactBody& triangleBody,
                         std::uint32_t triangle, const glm::dvec3& barycentric, bool sameBody) {
  nodes_.clear();
  const auto add = [&](ParticleState* state, std::uint32_t index, double coefficient) {
    if (sameBody)
      for (Node& node : nodes_)
        if (node.index == index && node.state == state) {
          node.coefficient += coefficient;
          return;
        }
    nodes_.push_back({state, index, coefficient});
  };
  for (int j = 0; j < 4; ++j) add(vertexBody.state, vertexBody.carriers[vertex][j], vertexBody.weights[vertex][j]);
  const Triangle& t = triangleBody.drawnTriangles[triangle];
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      add(triangleBody.state, triangleBody.carriers[t[k]][j], -barycentric[k] * triangleBody.weights[t[k]][j]);
}

double SelfContact::stiffness() const {
  double sum = 0.0;
  for (const Node& node : nodes_) sum += node.coefficient * node.coefficient * node.state->inverseMasses[node.index];
  return sum;
}

void SelfContact::moveAlong(const glm::dvec3& normal, double gap, double stiffness) {
  // Δx_j = −C g_j w_j n / Σ g² w, which takes the gap C to zero.
  for (const Node& node : nodes_) {
    const double w = node.state->inverseMasses[node.index];
    if (w != 0.0) node.state->positions[node.index] -= (gap * node.coefficient * w / stiffness) * normal;
  }
}

void SelfContact::stopApproach(const glm::dvec3& normal, double stiffness, double friction, bool separating) {
  glm::dvec3 relative(0.0);  // Σ g_j v_j: the vertex's velocity relative to the triangle's point
  for (const Node& node : nodes_) relative += node.coefficient * node.state->velocities[node.index];
  const double normalSpeed = glm::dot(relative, normal);
  // Approaching (or, held by the cling, separating): that normal speed is taken away.
  const double normalChange = normalSpeed < 0.0 || separating ? -normalSpeed : 0.0;
  const glm::dvec3 sliding = relative - normalSpeed * normal;
  const double slidingSpeed = glm::length(sliding);
  const double slidingChange = slidingSpeed > 0.0 ? std::min(slidingSpeed, friction * std::abs(normalChange)) : 0.0;
  const glm::dvec3 change = normalChange * normal - (slidingSpeed > 0.0 ? slidingChange / slidingSpeed : 0.0) * sliding;
  if (change == glm::dvec3(0.0)) return;
  for (const Node& node : nodes_) {
    const double w = node.state->inverseMasses[node.index];
    if (w != 0.0) node.state->velocities[node.index] += (node.coefficient * w / stiffness) * change;
  }
}

std::size_t SelfContact::vertexAgainstTriangles(std::span<const ContactBody> bodies, std::uint32_t a, std::uint32_t sa,
                                                std::uint32_t b, std::uint32_t sb, bool near, const SelfContactOptions& options) {
  const ContactBody &vertexBody = bodies[a], &triangleBody = bodies[b];
  BodyCache &vertexCache = bodies_[a], &triangleCache = bodies_[b];
  if (!vertexCache.hasPrevious || !triangleCache.hasPrevious) return 0;
  const std::span<const glm::dvec3> x = vertexBody.state->positions, y = triangleBody.state->positions;
  const double band = kSelfContactBand * triangleCache.meanEdge;
  // The box of the drawn triangles over sb, grown by the band: vertices outside it meet none of them.
  const std::uint32_t first = triangleCache.ownedStart[sb], last = triangleCache.ownedStart[sb + 1];
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (std::uint32_t k = first; k < last; ++k) {
    const Corners c = corners(triangleBody, triangleCache.owned[k], y);
    low = glm::min(low, glm::min(c.a, glm::min(c.b, c.c)));
    high = glm::max(high, glm::max(c.a, glm::max(c.b, c.c)));
  }
  low -= glm::dvec3(band + kSelfContactSkin);
  high += glm::dvec3(band + kSelfContactSkin);
  std::size_t pushed = 0;
  for (std::uint32_t vertex : vertexBody.verticesOfSurfaceTriangle[sa]) {
    const glm::dvec3 p = place(vertexBody, vertex, x);
    if (glm::any(glm::lessThan(p, low)) || glm::any(glm::greaterThan(p, high))) continue;
    for (std::uint32_t k = first; k < last; ++k) {
      const std::uint32_t triangle = triangleCache.owned[k];
      if (near) {  // a crumple: its drawn neighbours at rest are never in contact
        const Triangle& t = triangleBody.drawnTriangles[triangle];
        const std::vector<glm::dvec3>& rest = triangleCache.restDrawn;
        const glm::dvec3 apart = rest[vertex] - (rest[t.x] + rest[t.y] + rest[t.z]) / 3.0;
        const double exclusion = kSelfContactDrawnExclusion * triangleCache.meanDrawnEdge;
        if (glm::dot(apart, apart) < exclusion * exclusion) continue;
      }
      const Corners c = corners(triangleBody, triangle, y);
      const glm::dvec3 normal = unitNormal(c.a, c.b, c.c);
      const double gap = glm::dot(p - c.a, normal) - kSelfContactSkin;
      if (gap >= 0.0 || gap < -band) continue;
      const glm::dvec3 beta = barycentricInPlane(p, c.a, c.b, c.c);
      if (smallest(beta) < -kEdgeSlack) continue;
      // Crossed since the last step, or inside the body all along (then not a contact)?
      const Corners before = corners(triangleBody, triangle, triangleCache.previous);
      const double distanceBefore = glm::dot(place(vertexBody, vertex, vertexCache.previous) - before.a,
                                             unitNormal(before.a, before.b, before.c));
      if (distanceBefore < -kPreviousSlack) continue;
      const Triangle& t = triangleBody.drawnTriangles[triangle];
      if (carriedInverted(vertexBody, vertex, x) || carriedInverted(triangleBody, t.x, y) ||
          carriedInverted(triangleBody, t.y, y) || carriedInverted(triangleBody, t.z, y))
        continue;
      const glm::dvec3 onTriangle = clampedBarycentric(beta);
      gather(vertexBody, vertex, triangleBody, triangle, onTriangle, a == b);
      const double resistance = stiffness();
      if (resistance <= 0.0) continue;
      moveAlong(normal, gap, resistance);
      stopApproach(normal, resistance, options.friction, false);
      ++pushed;
      vertexCache.touched[vertex] = step_;
      if (!vertexCache.left[vertex]) {  // in contact: held on the next steps too, clinging or not
        if (!vertexCache.stuck[vertex]) vertexCache.age[vertex] = 0.0;
        vertexCache.stuck[vertex] = 1;
        vertexCache.partnerBody[vertex] = b;
        vertexCache.partnerTriangle[vertex] = triangle;
        vertexCache.partnerBarycentric[vertex] = onTriangle;
      }
      break;  // one triangle per vertex and pair
    }
  }
  return pushed;
}

void SelfContact::cling(std::span<const ContactBody> bodies, const SelfContactOptions& options) {
  const double h = options.dt;
  contactsLeft_ = false;
  for (std::uint32_t a = 0; a < bodies.size(); ++a) {
    const ContactBody& body = bodies[a];
    BodyCache& cache = bodies_[a];
    std::vector<std::uint32_t> peel;
    for (std::uint32_t vertex = 0; vertex < cache.drawnCount; ++vertex) {
      if (!cache.stuck[vertex] && !cache.left[vertex]) continue;
      const std::uint32_t b = cache.partnerBody[vertex], triangle = cache.partnerTriangle[vertex];
      if (b >= bodies.size()) {
        cache.stuck[vertex] = cache.left[vertex] = 0;
        continue;
      }
      const ContactBody& other = bodies[b];
      const glm::dvec3 p = place(body, vertex, body.state->positions);
      const Corners c = corners(other, triangle, other.state->positions);
      const glm::dvec3 normal = unitNormal(c.a, c.b, c.c);
      const glm::dvec3 beta = barycentricInPlane(p, c.a, c.b, c.c);
      const double gap = glm::dot(p - c.a, normal) - kSelfContactSkin;
      if (smallest(beta) < -kSlideOff) {  // slid off its triangle: no longer over it
        cache.stuck[vertex] = cache.left[vertex] = 0;
        continue;
      }
      if (cache.left[vertex]) {  // peeled: free to stick again once out of the band
        if (gap + kSelfContactSkin > 2.0 * kClingBand) cache.left[vertex] = 0;
        continue;
      }
      cache.age[vertex] += h;
      if (cache.touched[vertex] == step_) continue;  // pushed out this step
      cache.partnerBarycentric[vertex] = clampedBarycentric(beta);
      gather(body, vertex, other, triangle, cache.partnerBarycentric[vertex], a == b);
      const double resistance = stiffness();
      if (resistance <= 0.0) continue;
      if (gap < 0.0) {  // still pressed together
        moveAlong(normal, gap, resistance);
        stopApproach(normal, resistance, options.friction, false);
        continue;
      }
      if (options.cling <= 0.0) {  // no cling: apart, the contact ends
        cache.stuck[vertex] = 0;
        continue;
      }
      // The pull that parted them this step, F = m_eff gap / h², against σ(t) A_v.
      const double pull = gap / (resistance * h * h);
      const double holds = adhesionGrownShare(cache.age[vertex]) * options.cling * cache.restArea[vertex];
      bool edge = false;
      for (std::uint32_t k = cache.neighbourStart[vertex]; k < cache.neighbourStart[vertex + 1] && !edge; ++k)
        edge = !cache.stuck[cache.neighbours[k]];
      if (pull > holds && edge) {
        peel.push_back(vertex);
        continue;
      }
      // Held: it creeps apart by the floor's law, and a vertex on the edge lifted out of the band has peeled.
      const double creep = std::min(gap, adhesionCreepDistance(pull, holds, h));
      if (edge && creep + kSelfContactSkin > kClingBand) {
        peel.push_back(vertex);
        continue;
      }
      moveAlong(normal, gap - creep, resistance);
      stopApproach(normal, resistance, 0.0, true);
    }
    for (std::uint32_t vertex : peel) {  // decided on the state before this pass: the front moves a ring per step
      cache.stuck[vertex] = 0;
      cache.left[vertex] = 1;
      ++peeled_;
    }
    for (std::uint32_t vertex = 0; vertex < cache.drawnCount && !contactsLeft_; ++vertex)
      contactsLeft_ = cache.stuck[vertex] || cache.left[vertex];
  }
}

std::size_t SelfContact::resolve(std::span<const ContactBody> bodies, const SelfContactOptions& options) {
  ++step_;
  if (!matches(bodies)) build(bodies);
  if (stepsToBroad_ <= 0) broadPhase(bodies, options);  // sets stepsToBroad_
  --stepsToBroad_;
  std::size_t pushed = 0;
  for (const Pair& pair : pairs_) {
    pushed += vertexAgainstTriangles(bodies, pair.bodyA, pair.triangleA, pair.bodyB, pair.triangleB, pair.near, options);
    pushed += vertexAgainstTriangles(bodies, pair.bodyB, pair.triangleB, pair.bodyA, pair.triangleA, pair.near, options);
  }
  if (pushed > 0 || contactsLeft_) cling(bodies, options);
  // The crossing test needs the last step's positions wherever it will look: at every step while
  // triangles are near, and before each broad phase.
  const bool lookNext = !pairs_.empty() || stepsToBroad_ == 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    BodyCache& cache = bodies_[b];
    cache.hasPrevious = lookNext;
    if (lookNext) cache.previous.assign(bodies[b].state->positions.begin(), bodies[b].state->positions.end());
  }
  return pushed;
}

}  // namespace slime

#include "core/bulk/damper_lanes.h"

#include <stdexcept>
#include <string>

#include "core/bulk/quad_lanes.h"

namespace slime {
namespace {

// The padded copies (quad_lanes.h): positions (x, y, z, 0) and velocities with the inverse mass as the
// fourth entry (v_x, v_y, v_z, w), one spare node at the end; per thread, as the element pass's.
struct DamperNodes {
  std::vector<Quad> positions;
  std::vector<Quad> velocities;
};
DamperNodes& damperNodes() {
  thread_local DamperNodes nodes;
  return nodes;
}

}  // namespace

DamperLanes packDamperLanes(const std::vector<glm::u32vec2>& pairs, const std::vector<double>& decay,
                            const std::vector<std::uint32_t>& starts, std::size_t nodeCount) {
  if (decay.size() != pairs.size() || starts.empty() || starts.back() != pairs.size())
    throw std::invalid_argument("packDamperLanes: " + std::to_string(pairs.size()) + " pairs, " +
                                std::to_string(decay.size()) + " decays and colours ending at " +
                                std::to_string(starts.empty() ? 0 : starts.back()) + " do not match");
  DamperLanes lanes;
  lanes.nodeCount = nodeCount;
  const auto spare = static_cast<std::uint32_t>(nodeCount);
  lanes.colours.push_back(0);
  for (std::size_t c = 0; c + 1 < starts.size(); ++c) {
    for (std::uint32_t k = starts[c]; k < starts[c + 1]; k += 4) {
      DamperQuad quad;
      for (std::uint32_t l = 0; l < 4; ++l) {
        const bool real = k + l < starts[c + 1];
        quad.first[l] = real ? pairs[k + l].x : spare;
        quad.second[l] = real ? pairs[k + l].y : spare;
        quad.decay[l] = real ? decay[k + l] : 0.0;
      }
      lanes.quads.push_back(quad);
    }
    lanes.colours.push_back(static_cast<std::uint32_t>(lanes.quads.size()));
  }
  return lanes;
}

void dampPairLanes(const DamperLanes& lanes, const std::vector<glm::dvec3>& positions,
                   std::vector<glm::dvec3>& velocities, const std::vector<double>& inverseMasses) {
  DamperNodes& nodes = damperNodes();
  const std::size_t n = lanes.nodeCount;
  if (positions.size() != n || velocities.size() != n || inverseMasses.size() != n)
    throw std::invalid_argument("dampPairLanes: the dampers were packed for " + std::to_string(n) +
                                " nodes, not " + std::to_string(positions.size()));
  nodes.positions.resize(n + 1);
  nodes.velocities.resize(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    nodes.positions[i] = Quad{positions[i].x, positions[i].y, positions[i].z, 0.0};
    nodes.velocities[i] = Quad{velocities[i].x, velocities[i].y, velocities[i].z, inverseMasses[i]};
  }
  nodes.positions[n] = Quad{};
  nodes.velocities[n] = Quad{};
  Quad* x = nodes.positions.data();
  Quad* v = nodes.velocities.data();
  for (const DamperQuad& quad : lanes.quads) {
    // Each pair as whole quads (d = x_j − x_i with a zero fourth entry; v_j − v_i, whose fourth entry
    // the zero leaves out of (v_j − v_i)·d), then the four |d|² and (v_j − v_i)·d into lanes at once.
    Quad d[4], vi[4], vj[4], squares[4], products[4];
    for (int l = 0; l < 4; ++l) {
      vi[l] = v[quad.first[l]];
      vj[l] = v[quad.second[l]];
      d[l] = x[quad.second[l]] - x[quad.first[l]];
      squares[l] = d[l] * d[l];
      products[l] = (vj[l] - vi[l]) * d[l];
    }
    Quad lengthSquared, relativeSpeed, wi, wj, unused[3];
    transposeIn(squares[0], squares[1], squares[2], squares[3], unused[0], unused[1], unused[2]);
    lengthSquared = unused[0] + unused[1] + unused[2];
    transposeIn(products[0], products[1], products[2], products[3], unused[0], unused[1], unused[2]);
    relativeSpeed = unused[0] + unused[1] + unused[2];
    wi = Quad{vi[0][3], vi[1][3], vi[2][3], vi[3][3]};
    wj = Quad{vj[0][3], vj[1][3], vj[2][3], vj[3][3]};
    const Quad inverseMassSum = wi + wj;
    Quad decay;
    __builtin_memcpy(&decay, quad.decay, sizeof decay);
    const Quad share = decay / (lengthSquared * inverseMassSum);
    // Zero where the pair-by-pair loop skips (no mass to move, or coincident ends).
    const auto acts = (inverseMassSum > 0.0) & (lengthSquared > 0.0);
    const Quad scaleI = acts ? wi * share * relativeSpeed : Quad{};
    const Quad scaleJ = acts ? wj * share * relativeSpeed : Quad{};
    for (int l = 0; l < 4; ++l) {
      v[quad.first[l]] = vi[l] + scaleI[l] * d[l];
      v[quad.second[l]] = vj[l] - scaleJ[l] * d[l];
    }
  }
  for (std::size_t i = 0; i < n; ++i) velocities[i] = glm::dvec3(v[i][0], v[i][1], v[i][2]);
}

}  // namespace slime

#include "core/bulk/element_pass.h"

#include "core/bulk/node_quads.h"
#include "core/bulk/tet_lanes.h"

#include <algorithm>
#include <cstring>

namespace slime {
namespace {

// elementForces in Real lanes.
template <class Real>
void elementForcesIn(const BulkBody& body, const std::vector<glm::dvec3>& x, std::vector<glm::dvec3>& forces) {
  NodeQuads& quads = nodeQuads();
  copyToQuads(x, quads.positions);
  quads.forces.assign(x.size(), Quad{});
  const ViscoelasticMaterial& material = body.material;
  const double lambdaPrime = volumetricModulus(material), alpha = restVolumeRatio(material);
  const std::size_t tetrahedra = body.mesh.tetrahedra.size();
  const bool prefetch = body.restBlocks.size() >= kPrefetchFromBlocks;
  for (std::size_t b = 0; b < body.restBlocks.size(); ++b) {
    const TetBlock& block = body.restBlocks[b];
    if (prefetch && b + 1 < body.restBlocks.size()) {
      const TetBlock& next = body.restBlocks[b + 1];
      prefetchBytes<0>(next.nodes, sizeof next.nodes);
      prefetchBytes<0>(next.stiffnessMap, sizeof next.stiffnessMap + sizeof next.volumeScale);
      prefetchBytes<0>(body.maxwellMaps[b + 1].forceMap, sizeof body.maxwellMaps[b + 1].forceMap);
    }
    const std::size_t count = std::min(kTetLanes, tetrahedra - b * kTetLanes);
    for (std::size_t o = 0; o < count; o += kLanesOf<Real>) {
      LanesOf<Real> ds[9], h[9];
      gatherLanes<Real>(block, quads.positions, o, ds);
      shapeForceLanes<Real>(material.longTermShear, material.maxwellShear, lambdaPrime, alpha, ds, block.stiffnessMap,
                            body.maxwellMaps[b].forceMap, block.volumeScale, o, h);
      scatterLanes<Real>(block, h, o, quads.forces);
    }
  }
  forces.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) forces[i] = glm::dvec3(quads.forces[i][0], quads.forces[i][1], quads.forces[i][2]);
}

// K_p of the kLaneWidth tetrahedra from offset `o` of block `b` from their G_p, in double as K0 is
// (fillElementBlocks), so that G_p = I gives K0 bit for bit.
void refreshLongTermMap(BulkBody& body, std::size_t b, std::size_t o) {
  TetBlock& block = body.restBlocks[b];
  alignas(64) ElementReal inverse[9][kTetLanes];
  for (std::size_t lanes = o; lanes < o + kLaneWidth; lanes += kLanesOf<double>) {
    plasticInverseLanes<double>(body.maxwell[b].plastic, lanes, inverse);
    congruenceLanes<double, ElementReal, kTetLanes>(block.restInverse, block.forceMap, inverse, lanes, block.stiffnessMap);
  }
  // Damage (slime.damage): the branch's stress is (1 − D) times its own, D from G_p's trace.
  const double damageStretch = body.material.damageStretch;
  if (damageStretch <= 0.0) return;
  const MaxwellBlock& rest = body.maxwell[b];
  for (std::size_t lane = o; lane < o + kLaneWidth; ++lane) {
    const double intact = 1.0 - damageOfTrace(double(rest.plastic[0][lane]) + rest.plastic[1][lane] + rest.plastic[2][lane],
                                              damageStretch);
    if (intact == 1.0) continue;
    for (int entry = 0; entry < 6; ++entry)
      block.stiffnessMap[entry][lane] = static_cast<ElementReal>(intact * block.stiffnessMap[entry][lane]);
  }
}

}  // namespace

void fillElementBlocks(BulkBody& body) {
  const std::vector<Tetrahedron>& tetrahedra = body.mesh.tetrahedra;
  for (std::size_t e = 0; e < tetrahedra.size(); ++e) {
    TetBlock& block = body.restBlocks[e / kTetLanes];
    for (int corner = 0; corner < 4; ++corner) block.nodes[corner][e % kTetLanes] = tetrahedra[e][corner];
    block.volumeScale[e % kTetLanes] = static_cast<ElementReal>(1.0 / (6.0 * body.rest[e].volume));  // 1/det Dm
  }
  for (TetBlock& block : body.restBlocks)
    for (std::size_t o = 0; o < kTetLanes; o += kLanesOf<double>)
      congruenceLanes<double, ElementReal, kTetLanes>(block.restInverse, block.forceMap, nullptr, o, block.stiffnessMap);
  refreshMaxwellForceMaps(body);
}

void refreshMaxwellForceMaps(BulkBody& body, bool longTermToo) {
  body.maxwellMaps.resize(body.maxwell.size());
  for (std::size_t b = 0; b < body.maxwell.size() && b < body.restBlocks.size(); ++b)
    for (std::size_t o = 0; o < kTetLanes; o += kLaneWidth) {
      congruenceLanes<ElementReal>(body.restBlocks[b].restInverse, body.restBlocks[b].forceMap, body.maxwell[b].inverse, o,
                      body.maxwellMaps[b].forceMap);
      if (longTermToo) refreshLongTermMap(body, b, o);
    }
}

void elementForces(const BulkBody& body, const std::vector<glm::dvec3>& x, std::vector<glm::dvec3>& forces) {
  elementForcesIn<ElementReal>(body, x, forces);
}

void elementForcesInDouble(const BulkBody& body, const std::vector<glm::dvec3>& x, std::vector<glm::dvec3>& forces) {
  elementForcesIn<double>(body, x, forces);
}

void relaxElements(BulkBody& body, double decay, const PlasticFlow& plastic, bool maxwellToo) {
  NodeQuads& quads = nodeQuads();
  copyToQuads(body.state.positions, quads.positions);
  const bool prefetch = body.restBlocks.size() >= kPrefetchFromBlocks;
  const bool maxwellFlows = maxwellToo && body.material.maxwellShear > 0.0, plasticFlows = plastic.flow > 0.0;
  for (std::size_t b = 0; b < body.restBlocks.size(); ++b) {
    const TetBlock& block = body.restBlocks[b];
    MaxwellBlock& maxwell = body.maxwell[b];
    if (prefetch && b + 1 < body.restBlocks.size()) {
      const TetBlock& next = body.restBlocks[b + 1];
      prefetchBytes<0>(next.nodes, sizeof next.nodes);
      prefetchBytes<0>(next.restInverse, sizeof next.restInverse + sizeof next.forceMap);
      prefetchBytes<1>(&body.maxwell[b + 1], sizeof(MaxwellBlock));
      prefetchBytes<1>(&body.maxwellMaps[b + 1], sizeof(MaxwellMapBlock));
    }
    alignas(64) ElementReal shape[9][kTetLanes];
    gatherBlock(block, quads.positions, shape);
    for (std::size_t o = 0; o < kTetLanes; o += kLaneWidth) {
      if (maxwellFlows) {
        relaxLanes<ElementReal>(shape, block.restInverse, decay, o, maxwell.metric, maxwell.inverse);
        congruenceLanes<ElementReal>(block.restInverse, block.forceMap, maxwell.inverse, o, body.maxwellMaps[b].forceMap);
      }
      if (plasticFlows && flowLongTermLanes<ElementReal>(shape, block.restInverse, plastic.yieldMeasure, plastic.flow,
                                                         plastic.recovery, o, maxwell.plastic))
        refreshLongTermMap(body, b, o);
    }
  }
}

}  // namespace slime

// A sticky floor (slime.adhesion, Pa): the bulk body's surface nodes that come to rest on the floor
// stick where they landed. A stuck node is held in place against tangential and upward pull up to
// its share of the contact's strength, F_i ≤ σ_a · A_i, where σ_a is slime.adhesion and A_i a third of
// the floor-facing (projected) area of its surface triangles. The pull is read from the substep
// itself: a stuck node starts a substep at rest at its anchor, so what moved it, Δx = h² F/m for the
// kick-drift step, gives F = m |Δx| / h² (upward and sideways; pressing down is the floor's). Held,
// it is put back and stopped. Pulled harder, it peels only if it lies on the contact's edge (a surface
// neighbour not stuck): peeling starts at the edge and runs inwards as a front, as a tape's does; an
// interior node holds until the front reaches it. A peeled node sticks again only after it has left
// the floor (z above twice the contact band) and come back. slime.adhesion = 0 does nothing at all.
//
// Rate dependence (issue 29; a wet slime or a pressure-sensitive adhesive is a viscous contact, not a
// rigid weld): (1) below its strength a stuck node creeps — it slides (and, on the contact's edge,
// lifts) at v = v_c · r^n with r = F / (σ A) its load ratio, kAdhesionCreepSpeed v_c and
// kAdhesionCreepExponent n < 1 (a power-law creep of the contact layer, as in the power-law rheology
// of soft adhesives: a sublinear law lets the body's own small restoring pull still creep while a
// hand's pull, which loads the contact several times more, moves it barely faster); an edge node
// lifted out of the contact band has peeled. (2) A fresh contact is weak and gains strength with the
// time it has been in contact (contact ageing, as in Dieterich's rate-and-state friction):
// σ(t) = σ_a · (f₀ + (1 − f₀)(1 − exp(−t / τ_w))), f₀ = kAdhesionFreshShare, τ_w = kAdhesionDwell,
// so a slime landing on the table does not glue itself down at the spread of its impact.
#pragma once

#include "core/geometry/particle_state.h"
#include "core/geometry/icosphere.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

// Surface nodes at most this high are on the floor (the bulk's surface nodes rest a little above it:
// the drawn surface, which bulges below the node triangles, is what touches), m.
constexpr double kAdhesionContactBand = 0.002;
// The contact's creep speed at its full strength (r = 1), m/s, and the creep law's exponent n.
constexpr double kAdhesionCreepSpeed = 0.005;
constexpr double kAdhesionCreepExponent = 0.5;
// Contact ageing: a fresh contact holds kAdhesionFreshShare of σ_a and grows to σ_a over kAdhesionDwell, s.
constexpr double kAdhesionFreshShare = 0.2;
constexpr double kAdhesionDwell = 0.5;

// The law's two rates, which the self-contact's cling (self_contact.h) shares with the floor:
// the share of its full strength a contact holds after `age` s in contact, f₀ + (1 − f₀)(1 − exp(−t/τ_w));
double adhesionGrownShare(double age);
// and how far a held contact creeps in a substep h under a pull of `pull` against `holds` N, h v_c r^n, m.
double adhesionCreepDistance(double pull, double holds, double h);

class FloorAdhesion {
 public:
  // Forget every contact; `surfaceNodes` nodes 0..N_s−1 carry the `surface` triangles.
  void reset(const std::vector<Triangle>& surface, std::size_t surfaceNodes);
  // A piece made from other pieces' nodes (a tear, a merge) keeps their contacts: reset to the new
  // surface, then each surface node i whose origin source[i] is a surface node of `from` takes its
  // state (stuck or peeled, its age). `source` gives a node of `from` per new surface node, or
  // kNoSource for a node that had none.
  static constexpr std::uint32_t kNoSource = 0xFFFFFFFFu;
  void carryOver(const FloorAdhesion& from, const std::vector<std::uint32_t>& source);
  // Records where the stuck nodes start the substep (call before it).
  void beginSubstep(const ParticleState& state);
  // After a substep of length h: holds or peels the stuck nodes, sticks the ones newly at rest on
  // the floor. `strength` is slime.adhesion, Pa; masses from `freeInverseMasses`.
  void endSubstep(ParticleState& state, const std::vector<Triangle>& surface,
                  const std::vector<double>& freeInverseMasses, double strength, double h);
  std::size_t stuckCount() const;
  std::size_t peeledCount() const { return peeled_; }  // nodes peeled since reset
  // Σ σ(t)·A_i over the nodes stuck after the last substep, N: the most the contact holds against a
  // pull on its edge nodes (an interior node holds until the peeling front reaches it).
  double strengthHeld() const { return strengthHeld_; }
  // What the contact has taken from the body since reset, summed over the nodes it held, stopped or
  // put back: momentum Σ m_i Δv_i (kg·m/s) and mass-weighted displacement Σ m_i Δx_i (kg·m). The body's
  // centre of mass at time T lies (Σ_s m Δx_s + Σ_s m Δv_s (T − t_s)) / M behind where the other forces
  // alone would put it (Newton for the substeps s the contact acted in).
  glm::dvec3 momentumTaken() const { return momentumTaken_; }
  glm::dvec3 displacementTaken() const { return displacementTaken_; }
  bool stuck(std::size_t node) const { return node < stuck_.size() && stuck_[node] != 0; }

 private:
  void updateAreas(const std::vector<Triangle>& surface, const std::vector<glm::dvec3>& positions);
  bool onEdge(std::size_t node) const;

  std::vector<std::uint8_t> stuck_, left_;  // left_: peeled and not yet off the floor
  std::vector<glm::dvec3> start_;
  std::vector<double> area_, age_;  // age_: time in contact, s
  std::vector<std::uint32_t> neighbourStart_, neighbours_;  // surface adjacency (CSR)
  std::size_t peeled_ = 0;
  double strengthHeld_ = 0.0;  // N
  glm::dvec3 momentumTaken_{0.0}, displacementTaken_{0.0};
};

}  // namespace slime

// The viscoelastic body as a piece (slime.model=bulk, the default): a tetrahedral body carrying the
// drawn icosphere (core/bulk/bulk_body.h), stepped by symplectic_euler, explicit_euler, rk4 or
// projective, with the sticky floor; a hand pulls its nodes with a mouse spring.
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/bulk/projective_dynamics.h"
#include "core/contact/floor_adhesion.h"
#include "core/contact/self_contact.h"
#include "core/simulation/piece.h"
#include "core/simulation/tearing.h"

#include <array>
#include <limits>

namespace slime {

class BulkPiece final : public Piece {
 public:
  // `slimeRestVolume` (m³): the whole slime's, of which this piece is a part (0: this piece's own), so
  // that a change of slime.mass gives the piece its share.
  explicit BulkPiece(BulkBody body, double slimeRestVolume = 0.0);

  std::unique_ptr<Piece> clone() const override;
  bool bulk() const override { return true; }
  void rebuildModels(const Settings& settings, Integrator integrator) override;
  void applyMaterial(const SlimeSettings& slime) override;
  void beginStep(const StepContext& context) override;
  void substep(double h) override;
  void endStep(const StepContext& context) override;
  double largestStableStep() const override;
  void saveGoodState() override;
  void rollBack() override;

  const ParticleState& state() const override { return body_.state; }
  ParticleState& state() override { return body_.state; }
  const std::vector<glm::dvec3>& drawnPositions() const override;
  const std::vector<Triangle>& drawnTriangles() const override { return body_.drawn.triangles; }
  double volume() const override;
  // Seconds since this piece was made by a merge (infinity for one never merged): the fused seam is not
  // judged by the tear criterion until it has set (Simulation::tearPieces).
  double secondsSinceMerge() const { return sinceMerge_; }
  double restVolume() const override { return body_.restVolume; }
  SlimeMetrics metrics() const override { return metricsOf(body_.freeInverseMasses); }
  std::size_t elementCount() const override { return body_.mesh.tetrahedra.size(); }
  double elasticEnergy() const override { return bulkElasticEnergy(body_, body_.state.positions); }
  std::size_t invertedElements() const override { return invertedBulkElements(body_, body_.state.positions); }

  bool grab(const glm::dvec3& point, double radius, int hand, Grip grip) override;

  const BulkBody& body() const { return body_; }
  // The body as the self-contact sees it (self_contact.h), borrowed until the body changes; the drawn
  // surface is placed again after the contact moves its nodes.
  ContactBody contactBody();
  const FloorAdhesion& adhesion() const { return adhesion_; }
  double slimeRestVolume() const { return slimeRestVolume_; }

  // A tear in two steps, so that no one step does all of it: first the drawn surfaces of the parts that
  // `plan` (tearing.h) cuts this piece into, made afresh on a grid of `spacing` (m) at the state now
  // (empty when a part would have no drawn surface: no tear), with the node positions they were made at.
  struct SplitSurfaces {
    TearPlan plan;
    std::vector<TriangleMesh> surfaces;  // per part
    std::vector<glm::dvec3> reference;   // this piece's node positions when they were made
    double drawnShare = 0.0;             // its drawn volume over its body's then
  };
  SplitSurfaces splitSurfaces(const TearPlan& plan, double spacing) const;
  // Then, steps later (the plan's topology unchanged), the pieces themselves, each with its tetrahedra's
  // rest and Maxwell states, its nodes' state now, its floor contacts and its drawn surface, carried from
  // where it was made by a smooth map of `support` (m). A holding hand goes with the part that has most
  // of its nodes (handPart[hand]; −1 for a hand that holds nothing), holding the nodes it had there.
  // Their models are not built yet (rebuildModels).
  std::vector<std::unique_ptr<BulkPiece>> split(const SplitSurfaces& made, double support, std::array<int, kHands>& handPart);
  // This piece and `other` as one (merging.h), welded within `weldDistance` (m), its drawn surface the
  // smooth union of theirs on a grid of `spacing`; a holding hand of either keeps its nodes
  // (handFrom[hand]: 0 this piece's, 1 the other's, −1 none). Its models are not built yet. None when
  // the smooth union of the drawn surfaces is not one surface (they do not meet).
  std::unique_ptr<BulkPiece> mergedWith(BulkPiece& other, double weldDistance, double spacing, double support,
                                        std::array<int, kHands>& handFrom);
  // Hand `which` holds its nodes of another piece, renumbered here by `newOfOld` (kNoNode: not here).
  static constexpr std::uint32_t kNoNode = 0xFFFFFFFFu;
  void takeHand(int which, const Hand& hand, const std::vector<std::uint32_t>& newOfOld);

 private:
  const glm::dvec3& grabOffset(const Hand& hand, std::size_t k) const override { return hand.spring.offsets[k]; }
  void bindAccelerations();  // accelerationField_, for this object
  void accelerations(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v, std::vector<glm::dvec3>& a);
  int travelSubstepsNeeded() const;  // substeps so that no node crosses kTravelPerSubstep of an edge

  BulkBody body_;
  double slimeRestVolume_ = 0.0;  // the whole slime's rest volume, m³
  // A piece made afresh (a tear): its drawn volume over its body's, which its drawn surface keeps
  // (0: the icosphere's smooth map as it is).
  double drawnVolumeShare_ = 0.0;
  double roundingLeft_ = 0.0;  // s: a merged piece's long-term rest shape still flowing to its ball
  double sinceMerge_ = std::numeric_limits<double>::infinity();  // s since the merge that made this piece
  BulkScratch scratch_;
  FloorAdhesion adhesion_;  // the sticky floor (slime.adhesion)
  mutable std::vector<glm::dvec3> drawnPositions_;  // placed from the body when first asked for
  mutable bool drawnStale_ = true;
  mutable TriangleMesh drawnMesh_;  // offsetToVolume's scratch
  double restFrequency_ = 0.0;     // ω_max at the rest shape; highestFrequency_ never drops below it
  bool deformedFrequency_ = false; // highestFrequency_ is above the rest one (a stretched body)
  double dampingRate_ = 0.0;       // the dampers' Gershgorin rate, for symplectic_euler's cap
  ProjectiveSolver projective_;     // sim.integrator=projective
  bool projectiveActive_ = false;   // its Maxwell stretches are the live ones (the body's metrics a copy)
  AccelerationField accelerationField_;
  IntegratorScratch integratorScratch_;
  double shortestEdge_ = 0.0;  // the tetrahedra's shortest rest edge, m
  std::vector<MaxwellBlock> goodMaxwell_;  // the guard's B_v and G_v
};

}  // namespace slime

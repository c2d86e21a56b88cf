#include "core/bulk/projective_local.h"

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

using Real = ProjectiveReal;

constexpr int kPolarIterations = 2;  // Müller et al. 2016 sweeps per local step (warm-started)

// (1 − e)^(−1/3) − 1 for a volume ratio 1 − e near 1: two fourth-order steps r ← r (1 + ε/3 + 2ε²/9 +
// 14ε³/81), ε = 1 − (1 − e) r³, from r = 1 (the Taylor series of (1 − ε)^(−1/3); a step leaves an error
// of 35ε⁴/243, so the second is within float's rounding for 1 − e in [0.6, 1.6], and a step's flow
// changes U_v's volume far less), written on ρ = r − 1 so that a small e keeps its digits. ε is clamped
// to [−1, 0.5], where the polynomial is positive and monotone, so a volume ratio farther out (a long
// step's flow of a squashed element: 0.3 → 0.98, 10 → 1.35) is brought most of the way to 1 and the
// rest by the next steps. No division or root: it lies on the local step's longest chain.
inline Real inverseCubeRootNearOneMinusOne(Real e) {
  const auto series = [](Real x) {
    const Real clamped = std::min(std::max(x, Real(-1)), Real(0.5));
    return clamped * (Real(1.0 / 3.0) + clamped * (Real(2.0 / 9.0) + clamped * Real(14.0 / 81.0)));
  };
  const Real rho = series(e);
  // 1 − (1 − e)(1 + ρ)³ without the cancellation of its leading terms.
  const Real left = e - (1 - e) * rho * (3 + rho * (3 + rho));
  return rho + (1 + rho) * series(left);
}

// The material's constants of the target, in Real: μ∞, μ1 and 3λ/2, each × −(2μ + 3λ)/(μ + 3λ/2), so
// that p·forceMap is w_e p_e Dm⁻ᵀ (forceMap = −V0 Dm⁻ᵀ, w_e = V0 (2μ + 3λ)).
struct TargetWeights {
  Real longTermShear, maxwellShear, volumeWeight;
  Real flow;                                       // 1 − exp(−h/τ) of the Maxwell branch
};

// One block's targets, w_e p_e Dm⁻ᵀ per tetrahedron into `out` ([3·column + row][lane], the
// columns for nodes 1..3). One tetrahedron per lane, no branches and no calls: the loop the compiler
// vectorises; `block` is restrict, so its stores need no runtime check against the rest data.
template <bool Flows, bool Plastic>
void blockTargets(const TargetWeights& k, const Real (&shape)[9][kTetLanes], const TetBlock& rest,
                  ProjectiveBlock* __restrict block, Real (&out)[9][kTetLanes]) {
  ProjectiveBlock& state = *block;
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    Real f[9];  // F = Ds·Dm⁻¹, [3·column + row]
    #pragma GCC unroll 9
    for (int c = 0; c < 3; ++c)
      #pragma GCC unroll 9
      for (int r = 0; r < 3; ++r)
        f[3 * c + r] = shape[r][lane] * Real(rest.restInverse[3 * c][lane]) +
                       shape[3 + r][lane] * Real(rest.restInverse[3 * c + 1][lane]) +
                       shape[6 + r][lane] * Real(rest.restInverse[3 * c + 2][lane]);
    // R by Müller et al.'s sweeps from the warm start q: ω = Σ r_c × f_c, the rotation by
    // ω/(2 |Σ r_c·f_c|) taken as the quaternion (1, ω/(2 |Σ r_c·f_c|)) (the same to second order, no
    // trigonometry). Written on the unnormalised quaternion: M(q) = |q|² R(q) (the rotation's entries as
    // quadratic forms) scales ω and the dot alike, so n = 2 (|dot| + ε) q + (0, ω) q points where the
    // normalised update does, and only the last sweep's n is normalised (no division or root on the way).
    // ε keeps a collapsed element's n (F = 0: n = 2ε q) off float's underflow.
    Real qw = state.rotation[0][lane], qx = state.rotation[1][lane], qy = state.rotation[2][lane], qz = state.rotation[3][lane];
    Real rot[9];
    const auto quadraticForms = [&] {
      const Real ww = qw * qw, xx = qx * qx, yy = qy * qy, zz = qz * qz;
      rot[0] = ww + xx - yy - zz, rot[1] = 2 * (qx * qy + qw * qz), rot[2] = 2 * (qx * qz - qw * qy);
      rot[3] = 2 * (qx * qy - qw * qz), rot[4] = ww - xx + yy - zz, rot[5] = 2 * (qy * qz + qw * qx);
      rot[6] = 2 * (qx * qz + qw * qy), rot[7] = 2 * (qy * qz - qw * qx), rot[8] = ww - xx - yy + zz;
    };
    #pragma GCC unroll 9
    for (int sweep = 0; sweep < kPolarIterations; ++sweep) {
      quadraticForms();
      Real ox = 0, oy = 0, oz = 0, dot = 0;
      #pragma GCC unroll 9
      for (int c = 0; c < 3; ++c) {
        const Real* r = rot + 3 * c;
        const Real* g = f + 3 * c;
        ox += r[1] * g[2] - r[2] * g[1];
        oy += r[2] * g[0] - r[0] * g[2];
        oz += r[0] * g[1] - r[1] * g[0];
        dot += r[0] * g[0] + r[1] * g[1] + r[2] * g[2];
      }
      const Real along = 2 * (std::abs(dot) + Real(1e-6));
      const Real nw = along * qw - ox * qx - oy * qy - oz * qz;
      const Real nx = along * qx + ox * qw + oy * qz - oz * qy;
      const Real ny = along * qy + oy * qw + oz * qx - ox * qz;
      const Real nz = along * qz + oz * qw + ox * qy - oy * qx;
      qw = nw, qx = nx, qy = ny, qz = nz;
    }
    quadraticForms();
    const Real inverseNormSquared = 1 / (qw * qw + qx * qx + qy * qy + qz * qz);
    #pragma GCC unroll 9
    for (int e = 0; e < 9; ++e) rot[e] *= inverseNormSquared;
    const Real inverseNorm = std::sqrt(inverseNormSquared);
    state.rotation[0][lane] = qw * inverseNorm, state.rotation[1][lane] = qx * inverseNorm;
    state.rotation[2][lane] = qy * inverseNorm, state.rotation[3][lane] = qz * inverseNorm;
    Real d[6];  // U_v − I
    #pragma GCC unroll 9
    for (int e = 0; e < 6; ++e) d[e] = state.maxwellStretch[e][lane];
    if constexpr (Flows) {
      // U = sym(RᵀF); U_v ← U_v + (U − U_v)·flow, then det U_v = 1 (an inverted blend keeps U_v). On
      // the deviations B = U_v − I: det(I + B) = 1 + tr B + (B's principal 2×2 minors) + det B, so
      // 1 − det and the rescaled B (1 + ρ) + ρ I (ρ = det^(−1/3) − 1) keep a small B's digits.
      Real s[9];
      #pragma GCC unroll 9
      for (int c = 0; c < 3; ++c)
        #pragma GCC unroll 9
        for (int r = 0; r < 3; ++r)
          s[3 * c + r] = rot[3 * r] * f[3 * c] + rot[3 * r + 1] * f[3 * c + 1] + rot[3 * r + 2] * f[3 * c + 2];
      const Real stretch[6] = {s[0] - 1, s[4] - 1, s[8] - 1, Real(0.5) * (s[1] + s[3]), Real(0.5) * (s[2] + s[6]),
                               Real(0.5) * (s[5] + s[7])};
      Real b[6];
      #pragma GCC unroll 9
      for (int e = 0; e < 6; ++e) b[e] = d[e] + (stretch[e] - d[e]) * k.flow;
      const Real minors = b[0] * b[1] - b[3] * b[3] + b[0] * b[2] - b[4] * b[4] + b[1] * b[2] - b[5] * b[5];
      const Real determinant = b[0] * (b[1] * b[2] - b[5] * b[5]) - b[3] * (b[3] * b[2] - b[5] * b[4]) +
                               b[4] * (b[3] * b[5] - b[1] * b[4]);
      const Real shrink = -(b[0] + b[1] + b[2] + minors + determinant);  // 1 − det(I + B)
      const bool positive = shrink < 1;
      const Real rho = inverseCubeRootNearOneMinusOne(positive ? shrink : Real(0));
      #pragma GCC unroll 9
      for (int e = 0; e < 6; ++e) {
        d[e] = positive ? b[e] * (1 + rho) + (e < 3 ? rho : Real(0)) : d[e];
        state.maxwellStretch[e][lane] = d[e];
      }
    }
    // The volume target: one Newton step from F towards det = 1 along det's gradient cof F,
    // p_V = F + δ cof F with δ = (1 − J)/|cof F|² (at small strain F − (tr ε/3) I, the same
    // stiffness as F J^(−1/3)); it stays at a bounded distance from F for an element squashed flat
    // (cof F points out of its plane), where F J^(−1/3) grows without bound. R lies on det = 1 too,
    // so no closer point is farther than R: an inverted element (J ≤ 0), or a step that would go
    // farther, takes R.
    Real cof[9];  // cof F = columns f1×f2, f2×f0, f0×f1 (∂J/∂F)
    cof[0] = f[4] * f[8] - f[5] * f[7], cof[1] = f[5] * f[6] - f[3] * f[8], cof[2] = f[3] * f[7] - f[4] * f[6];
    cof[3] = f[7] * f[2] - f[8] * f[1], cof[4] = f[8] * f[0] - f[6] * f[2], cof[5] = f[6] * f[1] - f[7] * f[0];
    cof[6] = f[1] * f[5] - f[2] * f[4], cof[7] = f[2] * f[3] - f[0] * f[5], cof[8] = f[0] * f[4] - f[1] * f[3];
    const Real j = f[0] * cof[0] + f[1] * cof[1] + f[2] * cof[2];
    Real cofSquared = 0, toRotation = 0;
    #pragma GCC unroll 9
    for (int e = 0; e < 9; ++e) {
      cofSquared += cof[e] * cof[e];
      toRotation += (f[e] - rot[e]) * (f[e] - rot[e]);
    }
    const Real delta = (1 - j) / (cofSquared + Real(1e-30));
    const bool newton = j > 0 && delta * delta * cofSquared <= toRotation;
    // −(2μ + 3λ) p with p = (μ∞ R U_p + μ1 R U_v + (3λ/2) p_V) / (μ + 3λ/2), p_V = F + δ cof F or R:
    // a R + μ1 R (U_v − I) + μ∞ R (U_p − I) + c F + step cof F with the lane's a, c and step.
    Real plastic[6] = {};
    if constexpr (Plastic) {
      #pragma GCC unroll 9
      for (int e = 0; e < 6; ++e) plastic[e] = state.plasticStretch[e][lane];
    }
    const Real a = k.longTermShear + k.maxwellShear + (newton ? Real(0) : k.volumeWeight);
    const Real c = newton ? k.volumeWeight : Real(0), step = newton ? k.volumeWeight * delta : Real(0);
    Real p[9];
    #pragma GCC unroll 9
    for (int col = 0; col < 3; ++col)
      #pragma GCC unroll 9
      for (int r = 0; r < 3; ++r) {
        const Real rd = rot[r] * d[kSymmetricEntry[0][col]] + rot[3 + r] * d[kSymmetricEntry[1][col]] + rot[6 + r] * d[kSymmetricEntry[2][col]];
        const int e = 3 * col + r;
        p[e] = a * rot[e] + k.maxwellShear * rd + c * f[e] + step * cof[e];
        if constexpr (Plastic)
          p[e] += k.longTermShear * (rot[r] * plastic[kSymmetricEntry[0][col]] + rot[3 + r] * plastic[kSymmetricEntry[1][col]] +
                                     rot[6 + r] * plastic[kSymmetricEntry[2][col]]);
      }
    // p·forceMap: the columns go to nodes 1..3.
    #pragma GCC unroll 9
    for (int col = 0; col < 3; ++col)
      #pragma GCC unroll 9
      for (int r = 0; r < 3; ++r)
        out[3 * col + r][lane] = p[r] * Real(rest.forceMap[3 * col][lane]) + p[3 + r] * Real(rest.forceMap[3 * col + 1][lane]) +
                                 p[6 + r] * Real(rest.forceMap[3 * col + 2][lane]);
  }
}

template <bool Flows, bool Plastic>
void allTargets(const BulkBody& body, const TargetWeights& weights, std::vector<ProjectiveBlock>& blocks, NodeQuads& quads) {
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const TetBlock& rest = body.restBlocks[b];
    alignas(64) Real shape[9][kTetLanes];
    gatherBlock(rest, quads.positions, shape);
    alignas(64) Real out[9][kTetLanes];
    blockTargets<Flows, Plastic>(weights, shape, rest, &blocks[b], out);
    scatterBlock(rest, out, quads.forces);
  }
}

}  // namespace

void projectiveTargets(const BulkBody& body, bool flows, double flow, bool plastic, std::vector<ProjectiveBlock>& blocks,
                       NodeQuads& quads, std::vector<glm::dvec3>& targets) {
  const ViscoelasticMaterial& m = body.material;
  const double mu = m.longTermShear + m.maxwellShear, volumeWeight = 1.5 * m.lameLambda;
  const double scale = -(2.0 * mu + 3.0 * m.lameLambda) / (mu + volumeWeight);
  const TargetWeights weights{static_cast<Real>(scale * m.longTermShear), static_cast<Real>(scale * m.maxwellShear),
                              static_cast<Real>(scale * volumeWeight), static_cast<Real>(flow)};
  const std::vector<glm::dvec3>& x = body.state.positions;
  copyToQuads(x, quads.positions);
  quads.forces.assign(x.size(), Quad{});
  if (plastic) {
    if (flows) allTargets<true, true>(body, weights, blocks, quads);
    else allTargets<false, true>(body, weights, blocks, quads);
  } else {
    if (flows) allTargets<true, false>(body, weights, blocks, quads);
    else allTargets<false, false>(body, weights, blocks, quads);
  }
  targets.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) targets[i] = glm::dvec3(quads.forces[i][0], quads.forces[i][1], quads.forces[i][2]);
}

}  // namespace slime

#include "core/bulk/eigen.h"  // first: see its header
#include "core/bulk/projective_factor.h"

#include <stdexcept>

namespace slime {
namespace {

constexpr double kPinnedMassFactor = 1e6;  // a pinned node's mass in the matrix, × the body's mass

using SparseMatrix = Eigen::SparseMatrix<double>;

// The strictly lower L by columns.
template <typename Compressed>
void compress(const SparseMatrix& matrix, Compressed& out) {
  const int n = static_cast<int>(matrix.cols());
  out.start.assign(static_cast<std::size_t>(n) + 1, 0);
  out.index.clear();
  out.values.clear();
  out.index.reserve(static_cast<std::size_t>(matrix.nonZeros()));
  out.values.reserve(static_cast<std::size_t>(matrix.nonZeros()));
  for (int k = 0; k < n; ++k) {
    for (SparseMatrix::InnerIterator it(matrix, k); it; ++it) {
      out.index.push_back(static_cast<int>(it.row()));
      out.values.push_back(it.value());
    }
    out.start[static_cast<std::size_t>(k) + 1] = static_cast<int>(out.index.size());
  }
}

}  // namespace

std::vector<MatrixEntry> projectiveMatrix(const BulkBody& body, double h, std::vector<double>& masses) {
  const ViscoelasticMaterial& m = body.material;
  const double mu = m.longTermShear + m.maxwellShear, lambda = m.lameLambda;
  const std::size_t n = body.state.size();
  std::vector<MatrixEntry> entries;
  entries.reserve(n + 16 * body.mesh.tetrahedra.size());
  masses.resize(n);
  const std::vector<double>& w = body.state.inverseMasses;
  for (std::size_t i = 0; i < n; ++i) {
    const double mass = w[i] > 0.0 ? 1.0 / w[i] : kPinnedMassFactor * body.totalMass;
    masses[i] = mass / (h * h);
    entries.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i), masses[i]});
  }
  // w_e D_eᵀD_e with D_e x = F: Q = Dm⁻¹Dm⁻ᵀ on nodes 1..3, node 0 the negative sums.
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const TetRest& rest = body.rest[e];
    const double weight = rest.volume * (2.0 * mu + 3.0 * lambda);
    double k[4][4] = {};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        double q = 0.0;  // (Dm⁻¹Dm⁻ᵀ)_ab, glm [column][row]
        for (int c = 0; c < 3; ++c) q += rest.restInverse[c][a] * rest.restInverse[c][b];
        k[a + 1][b + 1] = weight * q;
      }
    for (int b = 1; b < 4; ++b) {
      k[0][b] = -(k[1][b] + k[2][b] + k[3][b]);
      k[b][0] = k[0][b];
    }
    k[0][0] = -(k[0][1] + k[0][2] + k[0][3]);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) entries.push_back({t[a], t[b], k[a][b]});
  }
  return entries;
}

void ProjectiveFactor::factor(std::size_t n, const std::vector<MatrixEntry>& entries) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(entries.size());
  for (const MatrixEntry& e : entries)
    triplets.emplace_back(static_cast<int>(e.row), static_cast<int>(e.column), e.value);
  SparseMatrix matrix(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(matrix);
  if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any())
    throw std::runtime_error("projective solver: the global matrix is not positive definite");
  const SparseMatrix& lower = ldlt.matrixL().nestedExpression();
  compress(lower, byColumn_);
  inverseDiagonal_.resize(n);
  permutation_.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    inverseDiagonal_[j] = 1.0 / ldlt.vectorD()(static_cast<Eigen::Index>(j));
    permutation_[j] = ldlt.permutationP().indices()(static_cast<Eigen::Index>(j));
  }
  work_.assign(n, Node{});
}

// out ← out·scale − Σ_p values[p] · work[index[p]] over one line of L, four coordinates wide (one 256-bit
// multiply-add with AVX2, two 128-bit ones without; left to the vectoriser, GCC 12 kept one of the
// four accumulators scalar). Four accumulators, so that
// consecutive multiply-adds do not wait on each other.
inline void ProjectiveFactor::subtractLine(const double* __restrict values, const int* __restrict index, int count,
                                           const Node* work, double scale, Node& out) {
  Lanes sum0 = {}, sum1 = {}, sum2 = {}, sum3 = {};
  int p = 0;
  for (; p + 3 < count; p += 4) {
    sum0 += values[p] * work[index[p]].lanes;
    sum1 += values[p + 1] * work[index[p + 1]].lanes;
    sum2 += values[p + 2] * work[index[p + 2]].lanes;
    sum3 += values[p + 3] * work[index[p + 3]].lanes;
  }
  for (; p < count; ++p) sum0 += values[p] * work[index[p]].lanes;
  out.lanes = out.lanes * scale - ((sum0 + sum1) + (sum2 + sum3));
}

// x = A⁻¹ b = Pᵀ L⁻ᵀ D⁻¹ L⁻¹ P b, both ways along L's columns: forward each column's x_j taken
// from the rows below it, back each x_j gathered from them.
void ProjectiveFactor::solve(const std::vector<glm::dvec3>& b, std::vector<glm::dvec3>& x) {
  const std::size_t n = work_.size();
  Node* work = work_.data();
  for (std::size_t i = 0; i < n; ++i) work[permutation_[i]].lanes = Lanes{b[i].x, b[i].y, b[i].z, 0.0};
  const Compressed& columns = byColumn_;
  for (std::size_t j = 0; j < n; ++j) {
    const Lanes xj = work[j].lanes;
    for (int p = columns.start[j]; p < columns.start[j + 1]; ++p) work[columns.index[p]].lanes -= columns.values[p] * xj;
  }
  for (std::size_t j = n; j-- > 0;) {
    const int first = columns.start[j];
    subtractLine(columns.values.data() + first, columns.index.data() + first, columns.start[j + 1] - first, work,
                 inverseDiagonal_[j], work[j]);
  }
  x.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Lanes& v = work[permutation_[i]].lanes;
    x[i] = glm::dvec3(v[0], v[1], v[2]);
  }
}

// Four unit right-hand sides in the four lanes of one solve. Forward by L's columns, so that the
// zeros of L⁻¹e (every entry off the elimination tree's paths from the nodes up) are skipped.
void ProjectiveFactor::columns(const std::uint32_t* nodes, std::size_t count, std::vector<double>* const* x) {
  if (count > 4) throw std::invalid_argument("ProjectiveFactor::columns: at most four at once");
  const std::size_t n = work_.size();
  Node* work = work_.data();
  for (std::size_t j = 0; j < n; ++j) work[j].lanes = Lanes{0.0, 0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < count; ++k) work[permutation_[nodes[k]]].lanes[k] = 1.0;
  const Compressed& columns = byColumn_;
  const Lanes zero = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t j = 0; j < n; ++j) {
    const Lanes xj = work[j].lanes;
    const auto nonzero = xj != zero;  // −1 per lane that is not zero
    if (!(nonzero[0] | nonzero[1] | nonzero[2] | nonzero[3])) continue;
    for (int p = columns.start[j]; p < columns.start[j + 1]; ++p) work[columns.index[p]].lanes -= columns.values[p] * xj;
  }
  for (std::size_t j = n; j-- > 0;) {
    const int first = columns.start[j];
    subtractLine(columns.values.data() + first, columns.index.data() + first, columns.start[j + 1] - first, work,
                 inverseDiagonal_[j], work[j]);
  }
  for (std::size_t k = 0; k < count; ++k) {
    std::vector<double>& out = *x[k];
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = work[permutation_[i]].lanes[k];
  }
}

}  // namespace slime

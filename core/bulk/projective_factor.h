// The global matrix of sim.integrator=projective, A = M/h² + Σ w_e D_eᵀD_e (projective_dynamics.h),
// and its sparse factor P A Pᵀ = L D Lᵀ (Eigen's SimplicialLDLT with its AMD ordering), kept as plain
// arrays for the solve that every global step makes.
//
// The solve carries x, y and z together, padded to four doubles per node, so that each entry of L is
// one four-wide multiply-add (one 256-bit FMA on AVX2); Eigen's solve with three right-hand sides
// walks L three times. L is kept once, by columns: forward each column's x_j is subtracted from the
// rows below (a scatter), back each x_j gathers them into four register accumulators. A second copy
// by rows (gather both ways) was 10 % faster at resolution 2 but twice as slow at resolution 3, where
// L (409k entries, 4.9 MB a copy) no longer fits the caches and the solve streams it from memory.
// Only Eigen's factorisation (once per matrix) is used.
#pragma once

#include "core/bulk/bulk_body.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace slime {

struct MatrixEntry {
  std::uint32_t row = 0, column = 0;
  double value = 0.0;
};

// A's entries (repeated (row, column) pairs add up) for a step h; `masses` gets its mass term m_i/h²
// per node (a pinned node: kPinnedMassFactor × the body's mass).
std::vector<MatrixEntry> projectiveMatrix(const BulkBody& body, double h, std::vector<double>& masses);

class ProjectiveFactor {
 public:
  // Factors the symmetric positive definite n × n matrix given by `entries`; throws
  // std::runtime_error if it is not positive definite.
  void factor(std::size_t n, const std::vector<MatrixEntry>& entries);
  // x = A⁻¹ b for the three coordinates at once.
  void solve(const std::vector<glm::dvec3>& b, std::vector<glm::dvec3>& x);
  // *x[k] = A⁻¹ e_nodes[k] for k < count ≤ 4 (columns of the inverse, for the floor's active set),
  // computed together in one solve's four lanes.
  void columns(const std::uint32_t* nodes, std::size_t count, std::vector<double>* const* x);
  std::size_t size() const { return inverseDiagonal_.size(); }
  // Entries of L strictly below its diagonal (the solve's work is twice this, per coordinate).
  std::size_t nonZeros() const { return byColumn_.values.size(); }

 private:
  // x, y, z and a zero: four doubles, one 256-bit register with AVX2 (GCC's and Clang's vector type).
  using Lanes = double __attribute__((vector_size(32)));
  struct Node {
    Lanes lanes;
  };
  static void subtractLine(const double* values, const int* index, int count, const Node* work, double scale, Node& out);
  // Strictly lower L by columns: entry p of column j is (row index[p], values[p]) for p in
  // [start[j], start[j + 1]).
  struct Compressed {
    std::vector<int> start, index;
    std::vector<double> values;
  };
  Compressed byColumn_;
  std::vector<double> inverseDiagonal_;
  std::vector<int> permutation_;  // (P b)[permutation_[i]] = b[i]
  std::vector<Node> work_;
};

}  // namespace slime

// Eigen as the bulk body's files use it (dense, Cholesky, eigenvalues, sparse Cholesky). Include it
// first in a source file, before anything that could include <immintrin.h>: GCC 12 warns
// -Wmaybe-uninitialized inside its own AVX-512 intrinsics (avx512fintrin.h's _mm512_insertf64x4 reads
// an undefined __m256d on purpose; GCC bug 105593) wherever Eigen's matrix-product kernels inline them,
// and the pragma below covers the intrinsics' lines only if they are first read under it. Our own
// code keeps the warning; so does every line after this header.
#pragma once

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"  // the same, as -O1 (the sanitizer builds) reports it
#endif
#include <immintrin.h>
#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#pragma once
// Zero-fill incomplete Cholesky factor, M = L L^T ~ A, of the symmetric Newton matrix
// (I - gamma J in y = sqrt(C) T) on the conductance-Laplacian pattern: the preconditioner of the
// "pcg" linear solver. Unlike Jacobi it follows the strong contacts, so CG keeps converging when
// conductances span many decades. Newton matrices here are diagonally dominant M-matrices, for
// which IC(0) exists without breakdown.
#include <cstdint>
#include <span>
#include <vector>

#include "thermal/integrators/NewtonPreconditioner.h"
#include "thermal/system/JacobianPattern.h"

namespace tmdem::thermal {

class IncompleteCholesky final : public NewtonPreconditioner {
 public:
  // Takes the lower triangle of `pattern` (symmetric, diagonal present) as L's pattern.
  void analyse(const JacobianPattern& pattern) override;
  // Factors A = scale * J + diag(shift), J given by its values in `pattern` order (both
  // triangles present), shift one value per row: the Newton matrix is formed on the fly, no copy
  // of it is kept. Returns false on a non-positive pivot (A not positive definite).
  bool factor(std::span<const double> J_values, double scale, std::span<const double> shift) override;
  // z = (L L^T)^-1 r.
  void solve(std::span<const double> r, std::span<double> z) override;

 private:
  std::vector<std::int64_t> start_;  // n + 1, CSC columns of L
  std::vector<std::int64_t> row_;    // rows, diagonal first in each column
  std::vector<std::int64_t> from_;   // slot of each L entry in the pattern
  std::vector<double> value_;
  std::vector<std::int64_t> marker_; // scratch: slot of row i in the column being updated
};

}  // namespace tmdem::thermal

#pragma once
// Algebraic multigrid (hypre BoomerAMG, Debian libhypre-dev) as the preconditioner of the "amg"
// linear solver: one V-cycle per conjugate-gradient iteration on the symmetric Newton matrix
// M = scale * J + diag(shift). IC(0) ("pcg") loses effectiveness as the bed grows: its CG
// iterations grow with the graph's diameter, while a V-cycle's contraction does not depend on
// the size, so the iterations per solve stay flat (bench/bench_thermal.cpp, docs/benchmarks.md).
// The same V-cycle preconditions hypre's own CG for the steady state (SteadyStateSolver.h).
//
// hypre as packaged by Debian is built with MPI: the first preconditioner initialises MPI in
// singleton mode (no mpirun needed) unless the program already did, and hypre; both are
// finalised at exit. Everything runs on MPI_COMM_SELF (one process, serial) unless
// set_distribution makes the matrix one process's rows of a matrix over MPI_COMM_WORLD (the
// heating over MPI: the V-cycle then spans all processes, not one block per process).
// Allocation: the hierarchy is rebuilt by hypre at every factor (a preconditioner setup, which
// CVODE/IDA do every few tens of steps), not per CG iteration.
#include <cstdint>
#include <span>
#include <vector>

#include "thermal/integrators/NewtonPreconditioner.h"

namespace tmdem::thermal {

class BoomerAmgPreconditioner final : public NewtonPreconditioner {
 public:
  BoomerAmgPreconditioner();
  ~BoomerAmgPreconditioner() override;
  BoomerAmgPreconditioner(const BoomerAmgPreconditioner&) = delete;
  BoomerAmgPreconditioner& operator=(const BoomerAmgPreconditioner&) = delete;

  // The state scaling of the conjugate-gradient solvers, y = s T with s = sqrt(C): the Newton
  // matrix M = I - gamma S^-1 K S^-1 (K the conductance Laplacian) is S^-1 (C - gamma K) S^-1,
  // so M^-1 = S (C - gamma K)^-1 S, and the V-cycle is built for C - gamma K. Why: classical
  // AMG interpolates the constant vector, which is the near-null vector of C - gamma K but not
  // of M (there it is sqrt(C)); with M itself, capacities one decade apart doubled the CG
  // iterations per 4x lattice width (test_boomer_amg.cpp). Empty (the default): s = 1.
  void set_state_scale(std::span<const double> s) { scale_.assign(s.begin(), s.end()); }
  // Distributed over MPI_COMM_WORLD: the pattern given to analyse is a LocalNetwork's, whose
  // first `owned` nodes are this process's rows (consecutive global rows); global_row gives the
  // row of every local node, ghosts included, i.e. the global column of each pattern entry. The
  // ghosts' own rows are left out. Call before analyse; every process calls analyse, factor and
  // solve together. solve_cg stays serial.
  void set_distribution(std::size_t owned, std::span<const std::int32_t> global_row);
  void analyse(const JacobianPattern& pattern) override;
  // Builds M in hypre and its multigrid hierarchy. Returns false if hypre reports an error.
  bool factor(std::span<const double> J_values, double scale,
              std::span<const double> shift) override;
  // z = one V-cycle on M z = r from z = 0 (with a state scale: z = S V(S r)).
  void solve(std::span<const double> r, std::span<double> z) override;

  // M x = b by hypre's conjugate gradients preconditioned with the V-cycle, from x as given,
  // until ||b - M x|| <= relative_tolerance ||b|| (no state scale: the steady state).
  struct CgResult {
    int iterations = 0;
    double relative_residual = 0.0;
    bool converged = false;
  };
  CgResult solve_cg(std::span<const double> b, std::span<double> x, double relative_tolerance,
                    int max_iterations);

 private:
  void release_matrix();
  void set_vector(void* ij_vector, std::span<const double> values);
  void get_vector(void* ij_vector, std::span<double> values);

  std::int32_t n_ = 0;                  // rows of this process
  std::int32_t first_row_ = 0;          // its first global row (0 unless distributed)
  bool distributed_ = false;
  std::size_t owned_ = 0;               // distributed: owned nodes of the local pattern
  std::vector<std::int32_t> global_row_;  // distributed: local node -> global row
  std::size_t row_slots_ = 0;           // the slots of this process's rows: [0, row_slots_)
  std::vector<std::int32_t> row_size_;  // entries per row (rows = columns: M is symmetric)
  std::vector<std::int32_t> rows_;      // global rows first_row_ .. first_row_ + n - 1
  std::vector<std::int32_t> columns_;   // CSR global column indices (the pattern's row indices)
  std::vector<std::int32_t> local_column_;  // the pattern's row index of each slot
  std::vector<std::int32_t> row_of_slot_;  // the CSR row (pattern column) of each slot
  std::vector<double> scale_;           // s, or empty: 1
  std::vector<double> scaled_rhs_;      // s r
  std::vector<std::int64_t> diagonal_;  // slot of (i, i)
  std::vector<double> values_;          // M in pattern order
  // hypre objects, as opaque pointers (HYPRE_IJMatrix, HYPRE_IJVector, HYPRE_Solver).
  void* matrix_ = nullptr;
  void* b_ = nullptr;
  void* x_ = nullptr;
  void* amg_ = nullptr;
};

}  // namespace tmdem::thermal

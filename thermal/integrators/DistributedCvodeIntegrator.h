#pragma once
// BDF with Newton through CVODES over MPI processes (`mpirun -np N tmdem run`, frozen beds;
// docs/scale-out.md). Each process integrates the temperatures of its own particles, a block of
// the network split by NetworkPartition, held in SUNDIALS' parallel vector (Debian
// libsundials-nvecparallel-mpi); the right-hand side and the Jacobian products of its rows run
// on its LocalNetwork, whose ghost temperatures GhostExchange brings from their owners before
// each evaluation. The linear solver is conjugate gradients on y = sqrt(C) T (as "amg" in one
// process, CvodeIntegrator.h), preconditioned by one BoomerAMG V-cycle on the whole Newton
// matrix distributed over the processes (hypre's ParCSR matrix, each process its rows).
//
// The boundary heat is the quadrature of sum over free particles of q_i, summed over the
// processes: the energy the state gains, so the balance closes as in one process.
// temperatures_K() is every particle's temperature, gathered to every process after each
// advance (the coupling writes frames from it on rank 0).
#include <cvodes/cvodes.h>

#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "thermal/integrators/BoomerAmgPreconditioner.h"
#include "thermal/integrators/GhostExchange.h"
#include "thermal/integrators/PreconditionerReuse.h"
#include "thermal/integrators/SundialsContext.h"
#include "thermal/integrators/SundialsHandles.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/network/LocalNetwork.h"
#include "thermal/network/NetworkPartition.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::thermal {

class DistributedCvodeIntegrator final : public ThermalIntegrator {
 public:
  // local: the ThermalSystem on this process's LocalNetwork `layout` of `partition`; it must
  // outlive the integrator. Always conjugate gradients with BoomerAMG across the processes,
  // whatever settings.linear_solver says (which solvers a run over MPI may name is decided once,
  // in coupling/run/LinearSolverChoice.h). Needs a symmetric Jacobian; throws
  // std::invalid_argument otherwise.
  DistributedCvodeIntegrator(ThermalSystem& local, const LocalNetwork& layout,
                             const NetworkPartition& partition, const IntegratorSettings& settings);
  ~DistributedCvodeIntegrator() override;
  DistributedCvodeIntegrator(const DistributedCvodeIntegrator&) = delete;
  DistributedCvodeIntegrator& operator=(const DistributedCvodeIntegrator&) = delete;

  IntegratorKind kind() const override { return IntegratorKind::Cvode; }
  // T0_K and temperatures_K(): every particle of the global network, by node id.
  void initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) override;
  void advance_to(double t_s) override;
  void restart() override;
  double time_s() const override { return t_; }
  std::span<const double> temperatures_K() const override { return T_global_; }
  double boundary_heat_J() const override;
  double dissipation_heat_J() const override { return 0.0; }  // frozen: no dissipation
  IntegratorStats stats() const override;
  void restore_stats(const IntegratorStats& earlier) override { history_ = earlier; }

 private:
  // CVODES' callbacks (their signatures are SUNDIALS' function types), with the integrator as
  // user data.
  static std::remove_pointer_t<CVRhsFn> rhs;
  static std::remove_pointer_t<CVQuadRhsFn> boundary_rhs;
  static std::remove_pointer_t<CVLsJacTimesSetupFn> jtimes_setup;
  static std::remove_pointer_t<CVLsJacTimesVecFn> jtimes;
  static std::remove_pointer_t<CVLsPrecSetupFn> precond_setup;
  static std::remove_pointer_t<CVLsPrecSolveFn> precond_solve;
  static std::remove_pointer_t<CVErrHandlerFn> error_handler;  // keeps the message

  // T_local_: owned entries y / s, ghosts from their owners.
  void to_local(N_Vector y);
  // Every particle's temperature from the state, into T_global_ (collective).
  void gather();
  void check(int flag, const char* call) const;
  [[noreturn]] void fail(int flag, const char* call) const;

  ThermalSystem& system_;
  IntegratorSettings settings_;
  std::size_t owned_ = 0;
  std::vector<std::int32_t> node_;          // local index -> global node id
  std::vector<std::int32_t> node_at_row_;   // global row -> node id
  std::vector<int> counts_, displacements_;  // rows per process, first row per process
  GhostExchange ghosts_;
  BoomerAmgPreconditioner amg_;
  std::vector<double> scale_;               // sqrt(C) per local node
  std::vector<double> T_local_, rate_local_, v_local_, Jv_local_;  // per local node
  std::vector<double> T_owned_, T_rows_, T_global_;
  JacobianEvaluation jacobian_;
  std::vector<double> jacobian_values_;     // local pattern order, scaled
  std::vector<double> newton_shift_;        // 1 per local node (CVODES: M = I - gamma J)
  bool analysed_ = false;
  PreconditionerReuse amg_reuse_{true};     // keep the V-cycle over small changes of gamma
  double t_ = 0.0;
  double boundary_heat0_J_ = 0.0;
  IntegratorStats history_;
  std::string last_error_;

  // Destroyed in reverse: the solver memory first, then the linear solver, vectors, context.
  SundialsContext ctx_;
  NVectorPtr y_, abstol_, yQ_;
  LinearSolverPtr LS_;
  struct MemoryFree {
    void operator()(void* mem) const;  // CVodeFree
  };
  std::unique_ptr<void, MemoryFree> mem_;
};

}  // namespace tmdem::thermal

#pragma once
// What the CVODES and IDAS integrators share: the state vectors (y = sqrt(C) T with "pcg" and
// "amg", y = T with "klu"), the linear solver objects, the boundary-heat quadrature, error capture and
// statistics across re-initialisations. Each derived class adds its solver's memory and
// trampolines.
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "thermal/integrators/NewtonPreconditioner.h"
#include "thermal/integrators/SundialsContext.h"
#include "thermal/integrators/SundialsHandles.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::thermal {

inline std::span<double> nvector_view(N_Vector v) {
  return {N_VGetArrayPointer(v), std::size_t(N_VGetLength(v))};
}

class SundialsIntegratorBase : public ThermalIntegrator {
 public:
  // Shared with DistributedCvodeIntegrator.
  static constexpr int kMaxPcgIterations = 200;
  // CG stops on an absolute residual; at SUNDIALS' default (0.05) a near-equilibrium state
  // drifts by ~1e-8 relative (measured), so the linear tolerance factor is tighter.
  static constexpr double kPcgEpsLin = 1e-4;
  // Absolute tolerance of the boundary-heat quadrature, J: with error control on (so the solver
  // keeps its history consistent with the state's, CvodeIntegrator::initialize) but never binding.
  static constexpr double kQuadratureTolerance = 1e300;

  double time_s() const override { return t_; }
  std::span<const double> temperatures_K() const override { return T_out_; }
  double boundary_heat_J() const override;
  double dissipation_heat_J() const override;
  void restore_stats(const IntegratorStats& earlier) override;

 protected:
  SundialsIntegratorBase(ThermalSystem& system, const IntegratorSettings& settings);
  // Members go in reverse declaration order, and a derived class's (its solver memory) before
  // these: see the owners' order below.
  ~SundialsIntegratorBase() override = default;
  SundialsIntegratorBase(const SundialsIntegratorBase&) = delete;
  SundialsIntegratorBase& operator=(const SundialsIntegratorBase&) = delete;

  // Resets the run state and fills y = s T0, abstol = s atol, quadrature 0. Returns false when
  // there are no particles (nothing to integrate).
  bool begin(double t0_s, std::span<const double> T0_K, double boundary_heat0_J);
  // KLU on a CSC matrix of the system's pattern, or CG with at most kMaxPcgIterations.
  void create_linear_solver();
  // After a contact-graph shape change: KLU gets a new pattern size and a fresh symbolic
  // factorization. Returns true when the derived class must re-initialise its solver.
  bool pattern_changed();
  // T_work_ = y / scale (enthalpy state: T_i with E_i(T_i) = y_i).
  void unscale(N_Vector y);
  // d y_i / d T_i at T_work_: scale_[i], C_i(T_work_i) for the enthalpy state, else 1. The
  // state's rate is this factor times dT/dt.
  double state_factor(std::size_t i) const {
    if (energy_state_) return system_.network().heat_capacity_at(i, T_work_[i]);
    return scale_.empty() ? 1.0 : scale_[i];
  }
  // The S of S J S^-1 for jacobian_values / jacobian_times at T_work_ (see state_factor).
  std::span<const double> jacobian_scale();
  // Writes the system's pattern and J = d(dT/dt)/dT (scaled) at y into the sparse matrix.
  bool fill_jacobian(N_Vector y, SUNMatrix J);
  // "pcg" / "amg" preconditioner: IC(0) or a BoomerAMG V-cycle of the Newton matrix
  //   M = jacobian_factor * J + diag(free particles: diagonal_free, held: diagonal_held)
  // (CVODES: -gamma, 1, 1; IDAS: -1, cj, 1). reuse_jacobian: keep the J values of the last
  // setup (only the shift changed). Returns false if the factorization broke down.
  bool setup_preconditioner(N_Vector y, bool reuse_jacobian, double jacobian_factor,
                            double diagonal_free, double diagonal_held);
  void apply_preconditioner(N_Vector r, N_Vector z);
  void record_reinitialization(const IntegratorStats& current);
  IntegratorStats with_history(IntegratorStats current) const;

  // "<solver> failed in <call> with <flag name> (<flag>) at t = ... s, step size ... s after
  // ... steps: <detail>" (detail: failure_detail).
  [[noreturn]] void throw_failure(const char* solver, char* flag_name, int flag, const char* call,
                                  double step_s, long steps, const std::string& detail) const;
  // The last SUNDIALS message, and when the linear-solver setup failed (CV_LSETUP_FAIL,
  // IDA_LSETUP_FAIL: `linear_setup_failed`) in KLU's factorisation, what that means and the
  // solvers to choose instead (klu_failure_hint).
  std::string failure_detail(bool linear_setup_failed) const;
  // SUNDIALS error handler (same signature for CVODES and IDAS): keeps the message for the
  // exception instead of printing it.
  static void error_handler(int code, const char* module, const char* function, char* msg,
                            void* self);

  ThermalSystem& system_;
  IntegratorSettings settings_;
  bool cg_ = false;  // "pcg" or "amg": conjugate gradients on y = sqrt(C) T, else KLU on y = T
  // Declaration order is destruction order reversed: the solver (refers to A_ and y_) goes
  // first, then the matrix, the vectors, and the context they were all created in last.
  SundialsContext ctx_;
  NVectorPtr y_, yQ_, abstol_;
  MatrixPtr A_;
  LinearSolverPtr LS_;
  std::vector<double> scale_;  // sqrt(C) for pcg, empty for klu
  // Temperature-dependent capacities: the state is the enthalpy y_i = E_i(T_i) = int_0^T_i C_i,
  // whose rate is q_i, so sum_i y_i is a linear invariant the BDF/Newton steps keep to
  // round-off (the energy balance closes as for constant C). Jacobian d q / d E = (dq/dT) C^-1.
  bool energy_state_ = false;
  std::vector<double> jacobian_scale_;  // C(T_work_) for the enthalpy state
  std::vector<double> T_work_, dT_work_;
  JacobianEvaluation mode_jacobian_;     // d q / d T at the last Jacobian or preconditioner setup
  std::unique_ptr<NewtonPreconditioner> preconditioner_;  // IC(0) or BoomerAMG, with cg_
  std::vector<double> jacobian_values_;  // pattern order, scaled
  std::vector<double> newton_shift_;     // diagonal added to scale * J, per particle
  std::uint64_t preconditioner_topology_ = ~std::uint64_t{0};
  std::vector<double> T_out_;
  double t_ = 0.0;
  double boundary_heat0_J_ = 0.0;
  std::uint64_t topology_seen_ = 0;
  IntegratorStats before_reinit_;  // counters of the runs before the last re-initialisation
  long reinitializations_ = 0;
  std::string last_error_;
};

}  // namespace tmdem::thermal

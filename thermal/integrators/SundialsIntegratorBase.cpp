#include "thermal/integrators/SundialsIntegratorBase.h"

#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_pcg.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "thermal/integrators/BoomerAmgPreconditioner.h"
#include "thermal/integrators/IncompleteCholesky.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/ThermalSolverError.h"
#include "thermal/integrators/ThreadedVector.h"
#include "thermal/network/NodeLoopThreads.h"

namespace tmdem::thermal {

SundialsIntegratorBase::SundialsIntegratorBase(ThermalSystem& system,
                                               const IntegratorSettings& settings)
    : system_(system), settings_(settings),
      cg_(is_conjugate_gradients(settings.linear_solver)) {
  if (cg_ && !system_.symmetric_jacobian())
    throw std::invalid_argument(
        "thermal.linear_solver = \"" + std::string(name_of(settings.linear_solver)) +
        "\" needs a symmetric Jacobian, but " +
        std::string(system_.network().temperature_dependent()
                        ? "temperature-dependent material properties (a conductivity or "
                          "heat_capacity table) make it one-sided"
                        : "a switched-on mode (particle-particle radiation) couples T^4 terms "
                          "one-sidedly") +
        "; use \"klu\"");
  energy_state_ = system_.network().temperature_dependent();
  if (cg_) {
    scale_.resize(system_.size());
    for (std::size_t i = 0; i < scale_.size(); ++i)
      scale_[i] = std::sqrt(system_.network().heat_capacity_J_per_K[i]);
    if (settings.linear_solver == LinearSolverKind::Amg) {
      auto amg = std::make_unique<BoomerAmgPreconditioner>();
      amg->set_state_scale(scale_);
      preconditioner_ = std::move(amg);
    } else {
      preconditioner_ = std::make_unique<IncompleteCholesky>();
    }
  }
}

bool SundialsIntegratorBase::begin(double t0_s, std::span<const double> T0_K,
                                   double boundary_heat0_J) {
  const std::size_t n = system_.size();
  if (T0_K.size() != n)
    throw std::invalid_argument(std::string(name()) + ": initial temperatures have the wrong size");
  LS_.reset();  // the solver before the matrix it refers to
  A_.reset();
  t_ = t0_s;
  boundary_heat0_J_ = boundary_heat0_J;
  T_out_.assign(T0_K.begin(), T0_K.end());
  T_work_.assign(n, 0.0);
  dT_work_.assign(n, 0.0);
  preconditioner_topology_ = ~std::uint64_t{0};
  topology_seen_ = system_.topology_version();
  before_reinit_ = {};
  reinitializations_ = 0;
  if (n == 0) return false;
  if (!y_) {
    y_ = make_state_vector(sunindextype(n), ctx_, "state y");
    abstol_ = make_state_vector(sunindextype(n), ctx_, "absolute tolerances");
    // [0] boundary heat, [1] its part from the dissipation modes (friction heat).
    yQ_ = make_serial_vector(2, ctx_, "boundary-heat quadrature");
  }
  auto y = nvector_view(y_.get()), atol = nvector_view(abstol_.get());
  for (std::size_t i = 0; i < n; ++i) {
    T_work_[i] = T0_K[i];
    const double s = state_factor(i);
    y[i] = energy_state_ ? system_.network().thermal_energy_at(i, T0_K[i]) : s * T0_K[i];
    atol[i] = s * settings_.absolute_tolerance_K;
  }
  NV_Ith_S(yQ_.get(), 0) = 0.0;
  NV_Ith_S(yQ_.get(), 1) = 0.0;
  return true;
}

void SundialsIntegratorBase::create_linear_solver() {
  const auto n = sunindextype(system_.size());
  if (cg_) {
    LS_ = checked_sundials_object<LinearSolverPtr>(
        SUNLinSol_PCG(y_.get(), SUN_PREC_LEFT, std::min<int>(kMaxPcgIterations, int(n) + 1), ctx_),
        "SUNLinSol_PCG");
    return;
  }
  A_ = checked_sundials_object<MatrixPtr>(
      SUNSparseMatrix(n, n, sunindextype(system_.pattern().nonzeros()), CSC_MAT, ctx_),
      "SUNSparseMatrix");
  LS_ = checked_sundials_object<LinearSolverPtr>(SUNLinSol_KLU(y_.get(), A_.get(), ctx_),
                                                 "SUNLinSol_KLU");
  // The Newton matrix has the symmetric pattern of the conductance Laplacian: AMD, not the
  // SUNDIALS default COLAMD (meant for unsymmetric patterns). On a 22^3 lattice it cuts the
  // factor time 5x and the memory 2x (bench/bench_thermal.cpp).
  if (SUNLinSol_KLUSetOrdering(LS_.get(), 0) != 0) throw ThermalSolverError("SUNLinSol_KLUSetOrdering failed");
}

bool SundialsIntegratorBase::pattern_changed() {
  if (system_.topology_version() == topology_seen_) return false;
  if (!cg_) {
    const auto nnz = sunindextype(system_.pattern().nonzeros());
    if (SUNLinSol_KLUReInit(LS_.get(), A_.get(), nnz, SUNKLU_REINIT_FULL) != 0)
      throw ThermalSolverError("SUNLinSol_KLUReInit failed for " + std::to_string(nnz) +
                               " non-zeros", 0, t_);
  }
  topology_seen_ = system_.topology_version();
  return true;
}

void SundialsIntegratorBase::unscale(N_Vector y) {
  const double* yd = N_VGetArrayPointer(y);
  const std::int64_t n = std::int64_t(T_work_.size());
  // Element by element: the same bits on any thread count.
#pragma omp parallel for schedule(static) num_threads(node_loop_threads(T_work_.size()))
  for (std::int64_t k = 0; k < n; ++k) {
    const auto i = std::size_t(k);
    if (energy_state_)
      T_work_[i] = system_.network().temperature_at_energy(i, yd[i]);
    else
      T_work_[i] = scale_.empty() ? yd[i] : yd[i] / scale_[i];
  }
}

std::span<const double> SundialsIntegratorBase::jacobian_scale() {
  if (!energy_state_) return scale_;
  jacobian_scale_.resize(T_work_.size());
  for (std::size_t i = 0; i < T_work_.size(); ++i) jacobian_scale_[i] = state_factor(i);
  return jacobian_scale_;
}

bool SundialsIntegratorBase::fill_jacobian(N_Vector y, SUNMatrix J) {
  const auto& p = system_.pattern();
  if (SM_NNZ_S(J) < sunindextype(p.nonzeros())) return false;
  unscale(y);
  system_.evaluate_jacobian(T_work_, mode_jacobian_);
  // SUNDIALS zeroes the whole matrix (pattern included) before each evaluation: rewrite it.
  std::copy(p.column_start.begin(), p.column_start.end(), SM_INDEXPTRS_S(J));
  std::copy(p.row_index.begin(), p.row_index.end(), SM_INDEXVALS_S(J));
  system_.jacobian_values(mode_jacobian_, {SM_DATA_S(J), p.nonzeros()}, jacobian_scale());
  return true;
}

bool SundialsIntegratorBase::setup_preconditioner(N_Vector y, bool reuse_jacobian,
                                                  double jacobian_factor, double diagonal_free,
                                                  double diagonal_held) {
  const auto& p = system_.pattern();
  if (preconditioner_topology_ != system_.topology_version()) {
    preconditioner_->analyse(p);
    jacobian_values_.assign(p.nonzeros(), 0.0);
    preconditioner_topology_ = system_.topology_version();
    reuse_jacobian = false;
  }
  if (!reuse_jacobian) {
    unscale(y);
    system_.evaluate_jacobian(T_work_, mode_jacobian_);
    system_.jacobian_values(mode_jacobian_, jacobian_values_, jacobian_scale());
  }
  const auto& held = system_.network().held;
  newton_shift_.resize(held.size());
  for (std::size_t i = 0; i < held.size(); ++i) newton_shift_[i] = held[i] ? diagonal_held : diagonal_free;
  return preconditioner_->factor(jacobian_values_, jacobian_factor, newton_shift_);
}

void SundialsIntegratorBase::apply_preconditioner(N_Vector r, N_Vector z) {
  preconditioner_->solve(nvector_view(r), nvector_view(z));
}

double SundialsIntegratorBase::boundary_heat_J() const {
  return boundary_heat0_J_ + (yQ_ ? NV_Ith_S(yQ_.get(), 0) : 0.0);
}

double SundialsIntegratorBase::dissipation_heat_J() const {
  return yQ_ ? NV_Ith_S(yQ_.get(), 1) : 0.0;
}

void SundialsIntegratorBase::record_reinitialization(const IntegratorStats& current) {
  before_reinit_ = current;
  before_reinit_.reinitializations = 0;
  ++reinitializations_;
}

void SundialsIntegratorBase::restore_stats(const IntegratorStats& earlier) {
  // Called right after initialize(): the solver's own counters are 0, all of `earlier` is
  // history, added to what the solver counts from now on.
  before_reinit_ = earlier;
  before_reinit_.reinitializations = 0;
  reinitializations_ = earlier.reinitializations;
}

IntegratorStats SundialsIntegratorBase::with_history(IntegratorStats current) const {
  current.add_counters(before_reinit_);
  current.reinitializations = reinitializations_;
  return current;
}

void SundialsIntegratorBase::throw_failure(const char* solver, char* flag_name, int flag,
                                           const char* call, double step_s, long steps,
                                           const std::string& detail) const {
  throw ThermalSolverError::from_solver(solver, flag_name, flag, call, t_, step_s, steps, detail);
}

std::string SundialsIntegratorBase::failure_detail(bool linear_setup_failed) const {
  if (!linear_setup_failed || cg_ || !LS_) return last_error_;
  // KLU's status is KLU_OK unless its own analysis or factorisation failed (the setup also
  // fails when the Jacobian cannot be evaluated: no hint then).
  const auto* common = SUNLinSol_KLUGetCommon(LS_.get());
  if (!common || common->status == KLU_OK) return last_error_;
  const std::string hint =
      klu_failure_hint(int(common->status), system_.size(), system_.symmetric_jacobian());
  return last_error_.empty() ? hint : last_error_ + "; " + hint;
}

void SundialsIntegratorBase::error_handler(int code, const char* module, const char* function,
                                           char* msg, void* self) {
  if (code < 0) {
    auto* me = static_cast<SundialsIntegratorBase*>(self);
    me->last_error_ = std::string(module) + "/" + function + ": " + msg;
  }
}

}  // namespace tmdem::thermal

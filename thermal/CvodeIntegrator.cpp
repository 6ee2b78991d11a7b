#include "thermal/CvodeIntegrator.h"

#include <cvodes/cvodes.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_pcg.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "thermal/ThermalSolverError.h"

namespace tmdem::thermal {

namespace {
std::span<double> view(N_Vector v) { return {N_VGetArrayPointer(v), std::size_t(N_VGetLength(v))}; }
// CG iterations per linear solve before CVODE counts a linear convergence failure.
constexpr int kMaxPcgIterations = 200;
}  // namespace

CvodeIntegrator::CvodeIntegrator(ThermalSystem& system, const IntegratorSettings& settings)
    : system_(system), settings_(settings), pcg_(settings.linear_solver == "pcg") {
  if (pcg_) {
    scale_.resize(system_.size());
    for (std::size_t i = 0; i < scale_.size(); ++i)
      scale_[i] = std::sqrt(system_.network().heat_capacity_J_per_K[i]);
  }
}

CvodeIntegrator::~CvodeIntegrator() {
  if (mem_) CVodeFree(&mem_);
  if (LS_) SUNLinSolFree(LS_);
  if (A_) SUNMatDestroy(A_);
  if (y_) N_VDestroy(y_);
  if (yQ_) N_VDestroy(yQ_);
  if (abstol_) N_VDestroy(abstol_);
}

void CvodeIntegrator::check(int flag, const char* call) const {
  if (flag < 0) fail(flag, call);
}

void CvodeIntegrator::fail(int flag, const char* call) const {
  std::ostringstream msg;
  char* flag_name = CVodeGetReturnFlagName(flag);
  msg << "CVODE failed in " << call << " with " << (flag_name ? flag_name : "?") << " (" << flag
      << ") at t = " << t_ << " s";
  std::free(flag_name);
  if (mem_) {
    sunrealtype h = 0.0;
    long steps = 0;
    CVodeGetCurrentStep(mem_, &h);
    CVodeGetNumSteps(mem_, &steps);
    msg << ", step size " << h << " s after " << steps << " steps";
  }
  if (!last_error_.empty()) msg << ": " << last_error_;
  throw ThermalSolverError(msg.str(), flag, t_);
}

void CvodeIntegrator::error_handler(int code, const char* module, const char* function, char* msg,
                                    void* self) {
  // Errors are reported through the exception; SUNDIALS would otherwise print them itself.
  if (code < 0) {
    auto* me = static_cast<CvodeIntegrator*>(self);
    me->last_error_ = std::string(module) + "/" + function + ": " + msg;
  }
}

void CvodeIntegrator::unscale(N_Vector y) {
  const double* yd = N_VGetArrayPointer(y);
  if (scale_.empty()) {
    std::copy(yd, yd + T_work_.size(), T_work_.begin());
  } else {
    for (std::size_t i = 0; i < T_work_.size(); ++i) T_work_[i] = yd[i] / scale_[i];
  }
}

void CvodeIntegrator::initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) {
  const std::size_t n = system_.size();
  if (T0_K.size() != n) throw std::invalid_argument("cvode: initial temperatures have the wrong size");
  if (mem_) CVodeFree(&mem_);
  if (LS_) { SUNLinSolFree(LS_); LS_ = nullptr; }
  if (A_) { SUNMatDestroy(A_); A_ = nullptr; }
  t_ = t0_s;
  boundary_heat0_J_ = boundary_heat0_J;
  T_out_.assign(T0_K.begin(), T0_K.end());
  T_work_.assign(n, 0.0);
  dT_work_.assign(n, 0.0);
  precond_diag_.assign(n, 0.0);
  topology_seen_ = system_.topology_version();
  before_reinit_ = {};
  reinitializations_ = 0;
  if (n == 0) return;

  if (!y_) {
    y_ = N_VNew_Serial(sunindextype(n), ctx_);
    abstol_ = N_VNew_Serial(sunindextype(n), ctx_);
    yQ_ = N_VNew_Serial(1, ctx_);
  }
  auto y = view(y_), atol = view(abstol_);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = scale_.empty() ? 1.0 : scale_[i];
    y[i] = s * T0_K[i];
    atol[i] = s * settings_.absolute_tolerance_K;
  }
  NV_Ith_S(yQ_, 0) = 0.0;

  mem_ = CVodeCreate(CV_BDF, ctx_);
  if (!mem_) throw ThermalSolverError("CVodeCreate failed");
  check(CVodeSetErrHandlerFn(mem_, &CvodeIntegrator::error_handler, this), "CVodeSetErrHandlerFn");
  check(CVodeInit(mem_, &CvodeIntegrator::rhs, t0_s, y_), "CVodeInit");
  check(CVodeSetUserData(mem_, this), "CVodeSetUserData");
  check(CVodeSVtolerances(mem_, settings_.relative_tolerance, abstol_), "CVodeSVtolerances");
  check(CVodeSetMaxNumSteps(mem_, settings_.max_steps_per_call), "CVodeSetMaxNumSteps");
  // The boundary heat rides along as a quadrature: same steps, no say in step-size control.
  check(CVodeQuadInit(mem_, &CvodeIntegrator::boundary_rhs, yQ_), "CVodeQuadInit");
  check(CVodeSetQuadErrCon(mem_, SUNFALSE), "CVodeSetQuadErrCon");

  if (pcg_) {
    LS_ = SUNLinSol_PCG(y_, SUN_PREC_LEFT, std::min<int>(kMaxPcgIterations, int(n) + 1), ctx_);
    if (!LS_) throw ThermalSolverError("SUNLinSol_PCG failed");
    check(CVodeSetLinearSolver(mem_, LS_, nullptr), "CVodeSetLinearSolver");
    check(CVodeSetJacTimes(mem_, &CvodeIntegrator::jtimes_setup, &CvodeIntegrator::jtimes),
          "CVodeSetJacTimes");
    // A tighter linear tolerance than the default 0.05: CG stops on an absolute residual, and
    // at the default a near-equilibrium state drifts by ~1e-8 relative (measured).
    check(CVodeSetEpsLin(mem_, 1e-4), "CVodeSetEpsLin");
    check(CVodeSetPreconditioner(mem_, &CvodeIntegrator::precond_setup,
                                 &CvodeIntegrator::precond_solve),
          "CVodeSetPreconditioner");
  } else {
    const auto nnz = sunindextype(system_.pattern().nonzeros());
    A_ = SUNSparseMatrix(sunindextype(n), sunindextype(n), nnz, CSC_MAT, ctx_);
    LS_ = SUNLinSol_KLU(y_, A_, ctx_);
    if (!A_ || !LS_) throw ThermalSolverError("SUNSparseMatrix/SUNLinSol_KLU failed");
    // The Newton matrix has the symmetric pattern of the conductance Laplacian: AMD, not the
    // SUNDIALS default COLAMD (meant for unsymmetric patterns). On a 22^3 lattice it cuts the
    // factor time 5x and the memory 2x (bench/bench_thermal.cpp).
    check(SUNLinSol_KLUSetOrdering(LS_, 0), "SUNLinSol_KLUSetOrdering");
    check(CVodeSetLinearSolver(mem_, LS_, A_), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(mem_, &CvodeIntegrator::jacobian), "CVodeSetJacFn");
  }
}

void CvodeIntegrator::reanalyse() {
  // The contact graph changed shape: new pattern, new symbolic factorization, fresh history.
  if (!pcg_) {
    const auto nnz = sunindextype(system_.pattern().nonzeros());
    check(SUNLinSol_KLUReInit(LS_, A_, nnz, SUNKLU_REINIT_FULL), "SUNLinSol_KLUReInit");
  }
  topology_seen_ = system_.topology_version();
  reinit_at_current_state();
}

void CvodeIntegrator::reinit_at_current_state() {
  before_reinit_ = stats();
  before_reinit_.reinitializations = 0;
  // yQ_ already holds the boundary heat at t_ (read after every advance); asking SUNDIALS
  // again before its first step would interpolate with h = 0.
  check(CVodeReInit(mem_, t_, y_), "CVodeReInit");
  check(CVodeQuadReInit(mem_, yQ_), "CVodeQuadReInit");
  ++reinitializations_;
}

void CvodeIntegrator::restart() {
  if (mem_) reinit_at_current_state();
}

void CvodeIntegrator::advance_to(double t_s) {
  if (!mem_) {  // no particles
    t_ = t_s;
    return;
  }
  if (t_s <= t_) return;
  if (system_.topology_version() != topology_seen_) reanalyse();
  if (settings_.stop_at_each_time) check(CVodeSetStopTime(mem_, t_s), "CVodeSetStopTime");
  sunrealtype t_reached = t_;
  last_error_.clear();
  const int flag = CVode(mem_, t_s, y_, &t_reached, CV_NORMAL);
  if (flag < 0) {
    sunrealtype t_internal = t_;
    CVodeGetCurrentTime(mem_, &t_internal);
    t_ = t_internal;
    fail(flag, "CVode");
  }
  t_ = t_reached;
  unscale(y_);
  T_out_ = T_work_;
  sunrealtype tq = t_;
  check(CVodeGetQuad(mem_, &tq, yQ_), "CVodeGetQuad");
}

double CvodeIntegrator::boundary_heat_J() const {
  return boundary_heat0_J_ + (yQ_ ? NV_Ith_S(yQ_, 0) : 0.0);
}

IntegratorStats CvodeIntegrator::stats() const {
  IntegratorStats s = before_reinit_;
  s.reinitializations = reinitializations_;
  if (!mem_) return s;
  long v = 0;
  CVodeGetNumSteps(mem_, &v);               s.steps += v;
  CVodeGetNumRhsEvals(mem_, &v);            s.rhs_evals += v;
  CVodeGetNumLinRhsEvals(mem_, &v);         s.rhs_evals += v;
  if (pcg_) { CVodeGetNumPrecEvals(mem_, &v); } else { CVodeGetNumJacEvals(mem_, &v); }
  s.jacobian_evals += v;
  CVodeGetNumLinSolvSetups(mem_, &v);       s.linear_setups += v;
  CVodeGetNumLinIters(mem_, &v);            s.linear_iterations += v;
  CVodeGetNumErrTestFails(mem_, &v);        s.error_test_failures += v;
  CVodeGetNumNonlinSolvConvFails(mem_, &v); s.convergence_failures += v;
  return s;
}

// ---- trampolines -------------------------------------------------------------------------

int CvodeIntegrator::rhs(sunrealtype, N_Vector y, N_Vector ydot, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->unscale(y);
  auto out = view(ydot);
  double boundary_W = 0.0;
  if (!me->system_.time_derivative(me->T_work_, out, boundary_W)) return 1;  // recoverable
  double sum = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!me->scale_.empty()) out[i] *= me->scale_[i];
    sum += out[i];
  }
  return std::isfinite(sum) ? 0 : 1;
}

int CvodeIntegrator::boundary_rhs(sunrealtype, N_Vector y, N_Vector qdot, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->unscale(y);
  double boundary_W = 0.0;
  if (!me->system_.heat_flow(me->T_work_, me->dT_work_, boundary_W)) return 1;
  NV_Ith_S(qdot, 0) = boundary_W;
  return std::isfinite(boundary_W) ? 0 : 1;
}

int CvodeIntegrator::jacobian(sunrealtype, N_Vector y, N_Vector, SUNMatrix J, void* self, N_Vector,
                              N_Vector, N_Vector) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  const auto& p = me->system_.pattern();
  if (SM_NNZ_S(J) < sunindextype(p.nonzeros())) return -1;
  me->unscale(y);
  me->system_.prepare_jacobian(me->T_work_);
  // CVODE zeroes the whole matrix (pattern included) before each evaluation: rewrite it.
  std::copy(p.column_start.begin(), p.column_start.end(), SM_INDEXPTRS_S(J));
  std::copy(p.row_index.begin(), p.row_index.end(), SM_INDEXVALS_S(J));
  me->system_.jacobian_values({SM_DATA_S(J), p.nonzeros()}, me->scale_);
  return 0;
}

int CvodeIntegrator::jtimes_setup(sunrealtype, N_Vector y, N_Vector, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->unscale(y);
  me->system_.prepare_jacobian(me->T_work_);
  return 0;
}

int CvodeIntegrator::jtimes(N_Vector v, N_Vector Jv, sunrealtype, N_Vector, N_Vector, void* self,
                            N_Vector) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->system_.jacobian_times(view(v), view(Jv), me->scale_);
  return 0;
}

int CvodeIntegrator::precond_setup(sunrealtype, N_Vector y, N_Vector, sunbooleantype jok,
                                   sunbooleantype* jcur, sunrealtype, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  if (!jok) {
    me->unscale(y);
    me->system_.prepare_jacobian(me->T_work_);
  }
  *jcur = jok ? SUNFALSE : SUNTRUE;
  me->system_.jacobian_diagonal(me->precond_diag_);  // the diagonal is unchanged by scaling
  return 0;
}

int CvodeIntegrator::precond_solve(sunrealtype, N_Vector, N_Vector, N_Vector r, N_Vector z,
                                   sunrealtype gamma, sunrealtype, int, void* self) {
  // Jacobi: z = r / diag(I - gamma J).
  auto* me = static_cast<CvodeIntegrator*>(self);
  auto rr = view(r), zz = view(z);
  for (std::size_t i = 0; i < rr.size(); ++i) zz[i] = rr[i] / (1.0 - gamma * me->precond_diag_[i]);
  return 0;
}

}  // namespace tmdem::thermal

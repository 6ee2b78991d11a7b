#include "thermal/integrators/CvodeIntegrator.h"

#include <cvodes/cvodes.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cmath>

#include "thermal/integrators/ThermalSolverError.h"
#include "thermal/network/NodeLoopThreads.h"

namespace tmdem::thermal {

CvodeIntegrator::CvodeIntegrator(ThermalSystem& system, const IntegratorSettings& settings)
    : SundialsIntegratorBase(system, settings),
      amg_reuse_(settings.linear_solver == LinearSolverKind::Amg) {}

void CvodeIntegrator::MemoryFree::operator()(void* mem) const { CVodeFree(&mem); }

void CvodeIntegrator::check(int flag, const char* call) const {
  if (flag < 0) fail(flag, call);
}

ThermalSolverError cvode_failure(void* mem, const std::string& solver, int flag,
                                 const char* call, double t_s, const std::string& detail) {
  sunrealtype h = 0.0;
  long steps = -1;
  if (mem) {
    CVodeGetCurrentStep(mem, &h);
    CVodeGetNumSteps(mem, &steps);
  }
  return ThermalSolverError::from_solver(solver, CVodeGetReturnFlagName(flag), flag, call, t_s, h,
                                         steps, detail);
}

void CvodeIntegrator::fail(int flag, const char* call) const {
  throw cvode_failure(mem_.get(), "CVODE", flag, call, t_,
                      failure_detail(flag == CV_LSETUP_FAIL));
}

void CvodeIntegrator::initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) {
  mem_.reset();  // before begin() frees the linear solver it uses
  if (!begin(t0_s, T0_K, boundary_heat0_J)) return;

  mem_.reset(CVodeCreate(CV_BDF, ctx_));
  if (!mem_) throw ThermalSolverError("CVodeCreate failed");
  check(CVodeSetErrHandlerFn(mem_.get(), &SundialsIntegratorBase::error_handler,
                             static_cast<SundialsIntegratorBase*>(this)),
        "CVodeSetErrHandlerFn");
  check(CVodeInit(mem_.get(), &CvodeIntegrator::rhs, t0_s, y_.get()), "CVodeInit");
  check(CVodeSetUserData(mem_.get(), this), "CVodeSetUserData");
  check(CVodeSVtolerances(mem_.get(), settings_.relative_tolerance, abstol_.get()), "CVodeSVtolerances");
  check(CVodeSetMaxNumSteps(mem_.get(), settings_.max_steps_per_call), "CVodeSetMaxNumSteps");
  // The boundary heat rides along as a quadrature: same steps, no say in step-size control.
  check(CVodeQuadInit(mem_.get(), &CvodeIntegrator::boundary_rhs, yQ_.get()), "CVodeQuadInit");
  // Error control on, but with a tolerance no quadrature error reaches, so the quadrature still
  // has no say in the step size or order (its norms, ~1e-300 of the state's, lose every max).
  // Why on: at an order increase CVODES (cvChooseEta, 6.4.1 to 7.5.0) stores the step's
  // correction into the history column of order q+1 for the state, but for the quadrature only
  // with its error control on; without it the quadrature's column is built from the previous
  // step's correction, its history stops being the energy of the state's history, and the
  // balance error jumps from 1e-15 to 3e-8 (examples/column_in_air.toml at q 4 -> 5).
  check(CVodeQuadSStolerances(mem_.get(), 0.0, kQuadratureTolerance), "CVodeQuadSStolerances");
  check(CVodeSetQuadErrCon(mem_.get(), SUNTRUE), "CVodeSetQuadErrCon");

  create_linear_solver();
  check(CVodeSetLinearSolver(mem_.get(), LS_.get(), A_.get()), "CVodeSetLinearSolver");
  if (cg_) {
    check(CVodeSetJacTimes(mem_.get(), &CvodeIntegrator::jtimes_setup, &CvodeIntegrator::jtimes),
          "CVodeSetJacTimes");
    check(CVodeSetEpsLin(mem_.get(), kPcgEpsLin), "CVodeSetEpsLin");
    check(CVodeSetPreconditioner(mem_.get(), &CvodeIntegrator::precond_setup,
                                 &CvodeIntegrator::precond_solve),
          "CVodeSetPreconditioner");
  } else {
    check(CVodeSetJacFn(mem_.get(), &CvodeIntegrator::jacobian), "CVodeSetJacFn");
    // A new Newton matrix at every change of gamma = h l_1 (CVODES' default: beyond 30 %). With
    // an older one the Newton iteration stops at its convergence test, short of the solution,
    // and the state's energy change differs from the boundary-heat quadrature (evaluated at that
    // state) by the residual's energy. With this the balance of a linear network (exact
    // Jacobian) closes to round-off at any tolerance: examples/column_in_air.toml at rtol 1e-5
    // 1.7e-15 instead of 4.4e-6, for one more setup (12 instead of 11 in 56 steps).
    check(CVodeSetDeltaGammaMaxLSetup(mem_.get(), 0.0), "CVodeSetDeltaGammaMaxLSetup");
  }
}

void CvodeIntegrator::reinit_at_current_state() {
  record_reinitialization(stats());
  // yQ_ already holds the boundary heat at t_ (read after every advance); asking CVODES again
  // before its first step would interpolate with h = 0.
  check(CVodeReInit(mem_.get(), t_, y_.get()), "CVodeReInit");
  check(CVodeQuadReInit(mem_.get(), yQ_.get()), "CVodeQuadReInit");
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
  if (pattern_changed()) reinit_at_current_state();
  if (settings_.stop_at_each_time) check(CVodeSetStopTime(mem_.get(), t_s), "CVodeSetStopTime");
  last_error_.clear();
  if (const int flag = cvode_advance(mem_.get(), y_.get(), t_s, t_); flag < 0) fail(flag, "CVode");
  unscale(y_.get());
  T_out_ = T_work_;
  sunrealtype tq = t_;
  check(CVodeGetQuad(mem_.get(), &tq, yQ_.get()), "CVodeGetQuad");
}

int cvode_advance(void* mem, N_Vector y, double target_s, double& t_s) {
  sunrealtype t = t_s;
  const int flag = CVode(mem, target_s, y, &t, CV_NORMAL);
  if (flag < 0) CVodeGetCurrentTime(mem, &t);
  t_s = t;
  return flag;
}

IntegratorStats cvode_stats(void* mem, bool preconditioned) {
  IntegratorStats s;
  long v = 0;
  CVodeGetNumSteps(mem, &v);               s.steps = v;
  CVodeGetNumRhsEvals(mem, &v);            s.rhs_evals = v;
  CVodeGetNumLinRhsEvals(mem, &v);         s.rhs_evals += v;
  if (preconditioned) { CVodeGetNumPrecEvals(mem, &v); } else { CVodeGetNumJacEvals(mem, &v); }
  s.jacobian_evals = v;
  CVodeGetNumLinSolvSetups(mem, &v);       s.linear_setups = v;
  CVodeGetNumLinIters(mem, &v);            s.linear_iterations = v;
  CVodeGetNumErrTestFails(mem, &v);        s.error_test_failures = v;
  CVodeGetNumNonlinSolvConvFails(mem, &v); s.convergence_failures = v;
  return s;
}

IntegratorStats CvodeIntegrator::stats() const {
  return with_history(mem_ ? cvode_stats(mem_.get(), cg_) : IntegratorStats{});
}

// ---- trampolines -------------------------------------------------------------------------

int CvodeIntegrator::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->system_.set_time(t);
  me->unscale(y);
  auto out = nvector_view(ydot);
  double boundary_W = 0.0;
  if (!me->system_.time_derivative(me->T_work_, out, boundary_W)) return 1;  // recoverable
  // Element by element (the same bits on any thread count); a non-finite rate is a
  // recoverable failure.
  bool finite = true;
  const std::int64_t n = std::int64_t(out.size());
#pragma omp parallel for schedule(static) num_threads(node_loop_threads(out.size())) \
    reduction(&& : finite)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto i = std::size_t(k);
    out[i] *= me->state_factor(i);
    finite = finite && std::isfinite(out[i]);
  }
  return finite ? 0 : 1;
}

int CvodeIntegrator::boundary_rhs(sunrealtype t, N_Vector y, N_Vector qdot, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->system_.set_time(t);
  me->unscale(y);
  double boundary_W = 0.0;
  if (!me->system_.heat_flow(me->T_work_, me->dT_work_, boundary_W)) return 1;
  NV_Ith_S(qdot, 0) = boundary_W;
  NV_Ith_S(qdot, 1) = me->system_.dissipation_boundary_W();
  return std::isfinite(boundary_W) ? 0 : 1;
}

int CvodeIntegrator::jacobian(sunrealtype, N_Vector y, N_Vector, SUNMatrix J, void* self, N_Vector,
                              N_Vector, N_Vector) {
  return static_cast<CvodeIntegrator*>(self)->fill_jacobian(y, J) ? 0 : -1;
}

int CvodeIntegrator::jtimes_setup(sunrealtype, N_Vector y, N_Vector, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->unscale(y);
  me->system_.evaluate_jacobian(me->T_work_, me->mode_jacobian_);
  return 0;
}

int CvodeIntegrator::jtimes(N_Vector v, N_Vector Jv, sunrealtype, N_Vector, N_Vector, void* self,
                            N_Vector) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  me->system_.jacobian_times(me->mode_jacobian_, nvector_view(v), nvector_view(Jv),
                             me->jacobian_scale());
  return 0;
}

int CvodeIntegrator::precond_setup(sunrealtype, N_Vector y, N_Vector, sunbooleantype jok,
                                   sunbooleantype* jcur, sunrealtype gamma, void* self) {
  auto* me = static_cast<CvodeIntegrator*>(self);
  *jcur = jok ? SUNFALSE : SUNTRUE;
  const auto version = me->system_.values_version();
  if (me->amg_reuse_.may_keep(jok, gamma, version)) return 0;
  // M = I - gamma J; a breakdown is recoverable (CVODE retries with a smaller step).
  const bool ok = me->setup_preconditioner(y, jok, -gamma, 1.0, 1.0);
  me->amg_reuse_.factored(ok, gamma, version);
  return ok ? 0 : 1;
}

int CvodeIntegrator::precond_solve(sunrealtype, N_Vector, N_Vector, N_Vector r, N_Vector z,
                                   sunrealtype, sunrealtype, int, void* self) {
  static_cast<CvodeIntegrator*>(self)->apply_preconditioner(r, z);
  return 0;
}

}  // namespace tmdem::thermal

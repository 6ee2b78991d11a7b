#include "thermal/integrators/IdaIntegrator.h"

#include <idas/idas.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>

#include "thermal/integrators/ThermalSolverError.h"
#include "thermal/integrators/ThreadedVector.h"

namespace tmdem::thermal {

IdaIntegrator::IdaIntegrator(ThermalSystem& system, const IntegratorSettings& settings)
    : SundialsIntegratorBase(system, settings) {}

void IdaIntegrator::MemoryFree::operator()(void* mem) const { IDAFree(&mem); }

void IdaIntegrator::check(int flag, const char* call) const {
  if (flag < 0) fail(flag, call);
}

void IdaIntegrator::fail(int flag, const char* call) const {
  sunrealtype h = 0.0;
  long steps = -1;
  if (mem_) {
    IDAGetCurrentStep(mem_.get(), &h);
    IDAGetNumSteps(mem_.get(), &steps);
  }
  throw_failure("IDA", IDAGetReturnFlagName(flag), flag, call, h, steps,
                failure_detail(flag == IDA_LSETUP_FAIL));
}

void IdaIntegrator::consistent_derivative() {
  unscale(y_.get());
  double boundary_W = 0.0;
  auto yp = nvector_view(yp_.get());
  system_.set_time(t_);
  if (!system_.time_derivative(T_work_, yp, boundary_W))
    throw ThermalSolverError("IDA: heat flow undefined at the initial temperatures", 0, t_);
  for (std::size_t i = 0; i < yp.size(); ++i) yp[i] *= state_factor(i);
}

void IdaIntegrator::initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) {
  mem_.reset();  // before begin() frees the linear solver it uses
  held_value_.assign(system_.size(), 0.0);
  if (!begin(t0_s, T0_K, boundary_heat0_J)) return;
  const std::size_t n = system_.size();
  if (!yp_) {
    yp_ = make_state_vector(sunindextype(n), ctx_, "state derivative y'");
    id_ = make_state_vector(sunindextype(n), ctx_, "differential/algebraic ids");
  }
  auto y = nvector_view(y_.get()), id = nvector_view(id_.get());
  const auto& held = system_.network().held;
  for (std::size_t i = 0; i < n; ++i) {
    held_value_[i] = y[i];
    id[i] = held[i] ? 0.0 : 1.0;  // 0: algebraic (held), 1: differential
  }
  consistent_derivative();

  mem_.reset(IDACreate(ctx_));
  if (!mem_) throw ThermalSolverError("IDACreate failed");
  check(IDASetErrHandlerFn(mem_.get(), &SundialsIntegratorBase::error_handler,
                            static_cast<SundialsIntegratorBase*>(this)),
        "IDASetErrHandlerFn");
  check(IDAInit(mem_.get(), &IdaIntegrator::residual, t0_s, y_.get(), yp_.get()), "IDAInit");
  check(IDASetUserData(mem_.get(), this), "IDASetUserData");
  check(IDASVtolerances(mem_.get(), settings_.relative_tolerance, abstol_.get()), "IDASVtolerances");
  check(IDASetMaxNumSteps(mem_.get(), settings_.max_steps_per_call), "IDASetMaxNumSteps");
  check(IDASetId(mem_.get(), id_.get()), "IDASetId");
  // Held values are exact by construction; keep them out of the local error test.
  check(IDASetSuppressAlg(mem_.get(), SUNTRUE), "IDASetSuppressAlg");
  check(IDAQuadInit(mem_.get(), &IdaIntegrator::boundary_rhs, yQ_.get()), "IDAQuadInit");
  check(IDASetQuadErrCon(mem_.get(), SUNFALSE), "IDASetQuadErrCon");

  create_linear_solver();
  check(IDASetLinearSolver(mem_.get(), LS_.get(), A_.get()), "IDASetLinearSolver");
  if (cg_) {
    check(IDASetJacTimes(mem_.get(), &IdaIntegrator::jtimes_setup, &IdaIntegrator::jtimes),
          "IDASetJacTimes");
    check(IDASetEpsLin(mem_.get(), kPcgEpsLin), "IDASetEpsLin");
    check(IDASetPreconditioner(mem_.get(), &IdaIntegrator::precond_setup, &IdaIntegrator::precond_solve),
          "IDASetPreconditioner");
  } else {
    check(IDASetJacFn(mem_.get(), &IdaIntegrator::jacobian), "IDASetJacFn");
    // A new Newton matrix at every change of c_j (IDAS' default: beyond 25 %), for the reason
    // given in CvodeIntegrator::initialize: examples/column_in_air.toml balance error at rtol
    // 1e-6 1.4e-15 instead of 3.1e-7 (22 setups and Jacobians in 81 steps instead of 19 in 83).
    check(IDASetDeltaCjLSetup(mem_.get(), 0.0), "IDASetDeltaCjLSetup");
  }
}

void IdaIntegrator::reinit_at_current_state() {
  record_reinitialization(stats());
  // yQ_ already holds the boundary heat at t_ (read after every advance); asking SUNDIALS
  // again before its first step would interpolate with h = 0.
  consistent_derivative();
  check(IDAReInit(mem_.get(), t_, y_.get(), yp_.get()), "IDAReInit");
  check(IDAQuadReInit(mem_.get(), yQ_.get()), "IDAQuadReInit");
}

void IdaIntegrator::restart() {
  if (mem_) reinit_at_current_state();
}

void IdaIntegrator::advance_to(double t_s) {
  if (!mem_) {
    t_ = t_s;
    return;
  }
  if (t_s <= t_) return;
  if (pattern_changed()) reinit_at_current_state();
  if (settings_.stop_at_each_time) check(IDASetStopTime(mem_.get(), t_s), "IDASetStopTime");
  sunrealtype t_reached = t_;
  last_error_.clear();
  const int flag = IDASolve(mem_.get(), t_s, &t_reached, y_.get(), yp_.get(), IDA_NORMAL);
  if (flag < 0) {
    sunrealtype t_internal = t_;
    IDAGetCurrentTime(mem_.get(), &t_internal);
    t_ = t_internal;
    fail(flag, "IDASolve");
  }
  t_ = t_reached;
  unscale(y_.get());
  T_out_ = T_work_;
  sunrealtype tq = t_;
  check(IDAGetQuad(mem_.get(), &tq, yQ_.get()), "IDAGetQuad");
}

IntegratorStats IdaIntegrator::stats() const {
  IntegratorStats s;
  if (mem_) {
    long v = 0;
    IDAGetNumSteps(mem_.get(), &v);               s.steps = v;
    IDAGetNumResEvals(mem_.get(), &v);            s.rhs_evals = v;
    IDAGetNumLinResEvals(mem_.get(), &v);         s.rhs_evals += v;
    if (cg_) { IDAGetNumPrecEvals(mem_.get(), &v); } else { IDAGetNumJacEvals(mem_.get(), &v); }
    s.jacobian_evals = v;
    IDAGetNumLinSolvSetups(mem_.get(), &v);       s.linear_setups = v;
    IDAGetNumLinIters(mem_.get(), &v);            s.linear_iterations = v;
    IDAGetNumErrTestFails(mem_.get(), &v);        s.error_test_failures = v;
    IDAGetNumNonlinSolvConvFails(mem_.get(), &v); s.convergence_failures = v;
  }
  return with_history(s);
}

// ---- trampolines -------------------------------------------------------------------------

int IdaIntegrator::residual(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  auto* me = static_cast<IdaIntegrator*>(self);
  me->system_.set_time(t);
  me->unscale(y);
  auto rr = nvector_view(r), ypd = nvector_view(yp), yd = nvector_view(y);
  double boundary_W = 0.0;
  if (!me->system_.time_derivative(me->T_work_, rr, boundary_W)) return 1;
  const auto& held = me->system_.network().held;
  double sum = 0.0;
  for (std::size_t i = 0; i < rr.size(); ++i) {
    rr[i] = held[i] ? yd[i] - me->held_value_[i] : ypd[i] - me->state_factor(i) * rr[i];
    sum += rr[i];
  }
  return std::isfinite(sum) ? 0 : 1;
}

int IdaIntegrator::boundary_rhs(sunrealtype t, N_Vector y, N_Vector, N_Vector qdot, void* self) {
  auto* me = static_cast<IdaIntegrator*>(self);
  me->system_.set_time(t);
  me->unscale(y);
  double boundary_W = 0.0;
  if (!me->system_.heat_flow(me->T_work_, me->dT_work_, boundary_W)) return 1;
  NV_Ith_S(qdot, 0) = boundary_W;
  NV_Ith_S(qdot, 1) = me->system_.dissipation_boundary_W();
  return std::isfinite(boundary_W) ? 0 : 1;
}

int IdaIntegrator::jacobian(sunrealtype, sunrealtype cj, N_Vector y, N_Vector, N_Vector,
                            SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector) {
  auto* me = static_cast<IdaIntegrator*>(self);
  if (!me->fill_jacobian(y, J)) return -1;
  const auto& p = me->system_.pattern();
  std::span<double> values{SM_DATA_S(J), p.nonzeros()};
  for (double& v : values) v = -v;  // dF/dy + cj dF/dy' = cj I - J
  const auto& held = me->system_.network().held;
  for (std::size_t i = 0; i < held.size(); ++i) values[p.diagonal_slot[i]] += held[i] ? 1.0 : cj;
  return 0;
}

int IdaIntegrator::jtimes_setup(sunrealtype, N_Vector y, N_Vector, N_Vector, sunrealtype,
                                void* self) {
  auto* me = static_cast<IdaIntegrator*>(self);
  me->unscale(y);
  me->system_.evaluate_jacobian(me->T_work_, me->mode_jacobian_);
  return 0;
}

int IdaIntegrator::jtimes(sunrealtype, N_Vector, N_Vector, N_Vector, N_Vector v, N_Vector Jv,
                          sunrealtype cj, void* self, N_Vector, N_Vector) {
  auto* me = static_cast<IdaIntegrator*>(self);
  auto vv = nvector_view(v), out = nvector_view(Jv);
  me->system_.jacobian_times(me->mode_jacobian_, vv, out, me->jacobian_scale());
  const auto& held = me->system_.network().held;
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = (held[i] ? 1.0 : cj) * vv[i] - out[i];
  return 0;
}

int IdaIntegrator::precond_setup(sunrealtype, N_Vector y, N_Vector, N_Vector, sunrealtype cj,
                                 void* self) {
  // M = cj I - J for free particles, the identity row for held ones.
  return static_cast<IdaIntegrator*>(self)->setup_preconditioner(y, false, -1.0, cj, 1.0) ? 0 : 1;
}

int IdaIntegrator::precond_solve(sunrealtype, N_Vector, N_Vector, N_Vector, N_Vector rv, N_Vector z,
                                 sunrealtype, sunrealtype, void* self) {
  static_cast<IdaIntegrator*>(self)->apply_preconditioner(rv, z);
  return 0;
}

}  // namespace tmdem::thermal

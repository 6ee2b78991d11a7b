#include "thermal/integrators/DistributedCvodeIntegrator.h"

#include <cvodes/cvodes.h>
#include <mpi.h>
#include <nvector/nvector_parallel.h>
#include <sunlinsol/sunlinsol_pcg.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "thermal/integrators/CvodeIntegrator.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/MpiWorld.h"
#include "thermal/integrators/SundialsIntegratorBase.h"
#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {
namespace {

// This process's entries of a parallel vector.
std::span<double> owned_view(N_Vector v) {
  return {NV_DATA_P(v), std::size_t(NV_LOCLENGTH_P(v))};
}

NVectorPtr make_parallel_vector(std::size_t owned, std::size_t total, SUNContext ctx,
                                const char* what) {
  NVectorPtr v(N_VNew_Parallel(MPI_COMM_WORLD, sunindextype(owned), sunindextype(total), ctx));
  if (!v)
    throw ThermalSolverError(std::string("N_VNew_Parallel failed for the ") + what + " (" +
                             std::to_string(owned) + " of " + std::to_string(total) + " entries)");
  return v;
}

}  // namespace

void DistributedCvodeIntegrator::MemoryFree::operator()(void* mem) const { CVodeFree(&mem); }

DistributedCvodeIntegrator::DistributedCvodeIntegrator(ThermalSystem& local,
                                                       const LocalNetwork& layout,
                                                       const NetworkPartition& partition,
                                                       const IntegratorSettings& settings)
    : system_(local), settings_(settings), owned_(layout.owned), node_(layout.node),
      ghosts_(layout) {
  if (!system_.symmetric_jacobian())
    throw std::invalid_argument(
        "heating over MPI needs a symmetric Jacobian (conjugate gradients), but temperature-"
        "dependent properties or particle-particle radiation make it one-sided");
  if (system_.size() != layout.node.size())
    throw std::invalid_argument("DistributedCvodeIntegrator: system and layout differ in size");
  const std::size_t n = system_.size();
  node_at_row_.resize(partition.node_count());
  for (std::int32_t r = 0; r < std::int32_t(partition.node_count()); ++r)
    node_at_row_[std::size_t(r)] = partition.node_at_row(r);
  for (int r = 0; r < partition.ranks(); ++r) {
    counts_.push_back(partition.owned_count(r));
    displacements_.push_back(partition.first_row(r));
  }
  scale_.resize(n);
  for (std::size_t i = 0; i < n; ++i) scale_[i] = std::sqrt(system_.network().heat_capacity_J_per_K[i]);
  amg_.set_state_scale(scale_);
  amg_.set_distribution(owned_, layout.row);
  T_local_.assign(n, 0.0);
  rate_local_.assign(n, 0.0);
  v_local_.assign(n, 0.0);
  Jv_local_.assign(n, 0.0);
  newton_shift_.assign(n, 1.0);
  T_owned_.assign(owned_, 0.0);
  T_rows_.assign(partition.node_count(), 0.0);
  T_global_.assign(partition.node_count(), 0.0);
}

DistributedCvodeIntegrator::~DistributedCvodeIntegrator() = default;

void DistributedCvodeIntegrator::check(int flag, const char* call) const {
  if (flag < 0) fail(flag, call);
}

void DistributedCvodeIntegrator::fail(int flag, const char* call) const {
  throw cvode_failure(mem_.get(), "CVODE (over " + std::to_string(MpiWorld::size()) + " MPI processes)",
                      flag, call, t_, last_error_);
}

void DistributedCvodeIntegrator::error_handler(int code, const char* module, const char* function,
                                               char* msg, void* self) {
  if (code < 0)
    static_cast<DistributedCvodeIntegrator*>(self)->last_error_ =
        std::string(module) + "/" + function + ": " + msg;
}

void DistributedCvodeIntegrator::initialize(double t0_s, std::span<const double> T0_K,
                                            double boundary_heat0_J) {
  if (T0_K.size() != T_global_.size())
    throw std::invalid_argument("DistributedCvodeIntegrator: initial temperatures have the wrong size");
  mem_.reset();
  LS_.reset();
  t_ = t0_s;
  boundary_heat0_J_ = boundary_heat0_J;
  analysed_ = false;
  T_global_.assign(T0_K.begin(), T0_K.end());
  for (std::size_t i = 0; i < node_.size(); ++i) T_local_[i] = T0_K[std::size_t(node_[i])];
  if (!y_) {
    y_ = make_parallel_vector(owned_, T_global_.size(), ctx_, "state y");
    abstol_ = make_parallel_vector(owned_, T_global_.size(), ctx_, "absolute tolerances");
    // [0] boundary heat (the same on every process), [1] unused here (no friction heat).
    yQ_ = make_serial_vector(2, ctx_, "boundary-heat quadrature");
  }
  auto y = owned_view(y_.get()), atol = owned_view(abstol_.get());
  for (std::size_t i = 0; i < owned_; ++i) {
    y[i] = scale_[i] * T_local_[i];
    atol[i] = scale_[i] * settings_.absolute_tolerance_K;
  }
  NV_Ith_S(yQ_.get(), 0) = 0.0;
  NV_Ith_S(yQ_.get(), 1) = 0.0;

  mem_.reset(CVodeCreate(CV_BDF, ctx_));
  if (!mem_) throw ThermalSolverError("CVodeCreate failed");
  check(CVodeSetErrHandlerFn(mem_.get(), &DistributedCvodeIntegrator::error_handler, this),
        "CVodeSetErrHandlerFn");
  check(CVodeInit(mem_.get(), &DistributedCvodeIntegrator::rhs, t0_s, y_.get()), "CVodeInit");
  check(CVodeSetUserData(mem_.get(), this), "CVodeSetUserData");
  check(CVodeSVtolerances(mem_.get(), settings_.relative_tolerance, abstol_.get()),
        "CVodeSVtolerances");
  check(CVodeSetMaxNumSteps(mem_.get(), settings_.max_steps_per_call), "CVodeSetMaxNumSteps");
  // As in CvodeIntegrator::initialize: error control on, never binding.
  check(CVodeQuadInit(mem_.get(), &DistributedCvodeIntegrator::boundary_rhs, yQ_.get()),
        "CVodeQuadInit");
  check(CVodeQuadSStolerances(mem_.get(), 0.0, SundialsIntegratorBase::kQuadratureTolerance),
        "CVodeQuadSStolerances");
  check(CVodeSetQuadErrCon(mem_.get(), SUNTRUE), "CVodeSetQuadErrCon");
  const int max_iterations =
      int(std::min<std::size_t>(SundialsIntegratorBase::kMaxPcgIterations, T_global_.size() + 1));
  LS_ = checked_sundials_object<LinearSolverPtr>(
      SUNLinSol_PCG(y_.get(), SUN_PREC_LEFT, max_iterations, ctx_), "SUNLinSol_PCG");
  check(CVodeSetLinearSolver(mem_.get(), LS_.get(), nullptr), "CVodeSetLinearSolver");
  check(CVodeSetJacTimes(mem_.get(), &DistributedCvodeIntegrator::jtimes_setup,
                         &DistributedCvodeIntegrator::jtimes),
        "CVodeSetJacTimes");
  check(CVodeSetEpsLin(mem_.get(), SundialsIntegratorBase::kPcgEpsLin), "CVodeSetEpsLin");
  check(CVodeSetPreconditioner(mem_.get(), &DistributedCvodeIntegrator::precond_setup,
                               &DistributedCvodeIntegrator::precond_solve),
        "CVodeSetPreconditioner");
}

void DistributedCvodeIntegrator::restart() {
  if (!mem_) return;
  history_ = stats();  // CVodeReInit sets the solver's counters to 0
  ++history_.reinitializations;
  check(CVodeReInit(mem_.get(), t_, y_.get()), "CVodeReInit");
  check(CVodeQuadReInit(mem_.get(), yQ_.get()), "CVodeQuadReInit");
}

void DistributedCvodeIntegrator::advance_to(double t_s) {
  if (!mem_ || t_s <= t_) return;
  if (settings_.stop_at_each_time) check(CVodeSetStopTime(mem_.get(), t_s), "CVodeSetStopTime");
  last_error_.clear();
  if (const int flag = cvode_advance(mem_.get(), y_.get(), t_s, t_); flag < 0) fail(flag, "CVode");
  gather();
  sunrealtype tq = t_;
  check(CVodeGetQuad(mem_.get(), &tq, yQ_.get()), "CVodeGetQuad");
}

double DistributedCvodeIntegrator::boundary_heat_J() const {
  return boundary_heat0_J_ + (yQ_ ? NV_Ith_S(yQ_.get(), 0) : 0.0);
}

IntegratorStats DistributedCvodeIntegrator::stats() const {
  IntegratorStats s = mem_ ? cvode_stats(mem_.get(), true) : IntegratorStats{};
  s.add_counters(history_);
  s.reinitializations = history_.reinitializations;
  return s;
}

void DistributedCvodeIntegrator::to_local(N_Vector y) {
  const auto owned = owned_view(y);
  for (std::size_t i = 0; i < owned_; ++i) T_local_[i] = owned[i] / scale_[i];
  ghosts_.exchange(T_local_);
}

void DistributedCvodeIntegrator::gather() {
  const auto owned = owned_view(y_.get());
  for (std::size_t i = 0; i < owned_; ++i) T_owned_[i] = owned[i] / scale_[i];
  MpiWorld::all_gather(T_owned_, T_rows_, counts_, displacements_);
  for (std::size_t r = 0; r < T_rows_.size(); ++r) T_global_[std::size_t(node_at_row_[r])] = T_rows_[r];
}

// ---- trampolines: every process calls each one together (CVODES' control flow depends only on
// global norms), and each answers with the verdict of all (one process's domain error is all's).

int DistributedCvodeIntegrator::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* self) {
  auto* me = static_cast<DistributedCvodeIntegrator*>(self);
  me->system_.set_time(t);
  me->to_local(y);
  double boundary_W = 0.0;
  bool ok = me->system_.time_derivative(me->T_local_, me->rate_local_, boundary_W);
  auto out = owned_view(ydot);
  double sum = 0.0;
  for (std::size_t i = 0; i < me->owned_; ++i) {
    out[i] = me->rate_local_[i] * me->scale_[i];
    sum += out[i];
  }
  ok = ok && std::isfinite(sum);
  return MpiWorld::all(ok) ? 0 : 1;  // recoverable
}

int DistributedCvodeIntegrator::boundary_rhs(sunrealtype t, N_Vector y, N_Vector qdot, void* self) {
  auto* me = static_cast<DistributedCvodeIntegrator*>(self);
  me->system_.set_time(t);
  me->to_local(y);
  double modes_boundary_W = 0.0;  // counts the ghosts' flows too: not used
  const bool ok = me->system_.heat_flow(me->T_local_, me->rate_local_, modes_boundary_W);
  // What the free particles gain, sum q_i: the pair flows between them cancel, what remains is
  // the power from outside them (HeatTransferMode::add_heat_flow's boundary_W, summed without
  // counting a ghost's flows twice).
  double mine_W = 0.0;
  const auto& held = me->system_.network().held;
  for (std::size_t i = 0; i < me->owned_; ++i)
    if (!held[i]) mine_W += me->rate_local_[i];
  const double boundary_W = MpiWorld::sum(ok ? mine_W : std::nan(""));
  NV_Ith_S(qdot, 0) = boundary_W;
  NV_Ith_S(qdot, 1) = 0.0;
  return std::isfinite(boundary_W) ? 0 : 1;
}

int DistributedCvodeIntegrator::jtimes_setup(sunrealtype, N_Vector y, N_Vector, void* self) {
  auto* me = static_cast<DistributedCvodeIntegrator*>(self);
  me->to_local(y);
  me->system_.evaluate_jacobian(me->T_local_, me->jacobian_);
  return 0;
}

int DistributedCvodeIntegrator::jtimes(N_Vector v, N_Vector Jv, sunrealtype, N_Vector, N_Vector,
                                       void* self, N_Vector) {
  auto* me = static_cast<DistributedCvodeIntegrator*>(self);
  const auto v_owned = owned_view(v);
  std::copy(v_owned.begin(), v_owned.end(), me->v_local_.begin());
  me->ghosts_.exchange(me->v_local_);
  me->system_.jacobian_times(me->jacobian_, me->v_local_, me->Jv_local_, me->scale_);
  auto out = owned_view(Jv);
  std::copy(me->Jv_local_.begin(), me->Jv_local_.begin() + std::ptrdiff_t(me->owned_), out.begin());
  return 0;
}

int DistributedCvodeIntegrator::precond_setup(sunrealtype, N_Vector y, N_Vector, sunbooleantype jok,
                                              sunbooleantype* jcur, sunrealtype gamma, void* self) {
  auto* me = static_cast<DistributedCvodeIntegrator*>(self);
  if (!me->analysed_) {  // frozen: one contact graph for the whole run
    me->amg_.analyse(me->system_.pattern());
    me->jacobian_values_.assign(me->system_.pattern().nonzeros(), 0.0);
    me->analysed_ = true;
    jok = SUNFALSE;
  }
  *jcur = jok ? SUNFALSE : SUNTRUE;
  // Every process takes the same steps, so all keep or all rebuild.
  if (me->amg_reuse_.may_keep(jok, gamma, me->system_.values_version())) return 0;
  if (!jok) {
    me->to_local(y);
    me->system_.evaluate_jacobian(me->T_local_, me->jacobian_);
    me->system_.jacobian_values(me->jacobian_, me->jacobian_values_, me->scale_);
  }
  // M = I - gamma J; a breakdown anywhere is recoverable (CVODE retries with a smaller step).
  const bool ok = MpiWorld::all(me->amg_.factor(me->jacobian_values_, -gamma, me->newton_shift_));
  me->amg_reuse_.factored(ok, gamma, me->system_.values_version());
  return ok ? 0 : 1;
}

int DistributedCvodeIntegrator::precond_solve(sunrealtype, N_Vector, N_Vector, N_Vector r,
                                              N_Vector z, sunrealtype, sunrealtype, int, void* self) {
  auto* me = static_cast<DistributedCvodeIntegrator*>(self);
  me->amg_.solve(owned_view(r), owned_view(z));
  return 0;
}

}  // namespace tmdem::thermal

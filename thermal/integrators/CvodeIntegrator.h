#pragma once
// BDF with Newton through CVODES: sparse analytic Jacobian with KLU (symbolic factorization kept
// while the contact graph keeps its shape), or matrix-free Jacobian products with CG
// preconditioned by an incomplete Cholesky factor (IncompleteCholesky). The boundary heat is a
// CVODES quadrature, integrated with the same steps.
//
// CG needs a symmetric Newton matrix; I - gamma C^-1 K is not (C varies), but its similarity
// transform in y = sqrt(C) T is. So with "pcg" the state is y = sqrt(C) T, with "klu" y = T.
#include <memory>
#include <string>

#include "thermal/integrators/PreconditionerReuse.h"
#include "thermal/integrators/SundialsIntegratorBase.h"
#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {

// The counters of a CVODES memory (preconditioned: the conjugate-gradient solvers, whose
// "Jacobian evaluations" are preconditioner setups), without earlier segments.
IntegratorStats cvode_stats(void* cvode_mem, bool preconditioned);
// CVode (CV_NORMAL) from t_s to target_s; t_s becomes the time reached, or after a failure
// CVODES' internal time. Returns CVode's flag (< 0: failed).
int cvode_advance(void* cvode_mem, N_Vector y, double target_s, double& t_s);
// The error of a CVODES call that returned `flag`, with the step figures of cvode_mem (null:
// none) and `detail` (the last SUNDIALS message).
ThermalSolverError cvode_failure(void* cvode_mem, const std::string& solver, int flag,
                                 const char* call, double t_s, const std::string& detail);

class CvodeIntegrator final : public SundialsIntegratorBase {
 public:
  CvodeIntegrator(ThermalSystem& system, const IntegratorSettings& settings);

  IntegratorKind kind() const override { return IntegratorKind::Cvode; }
  void initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) override;
  void advance_to(double t_s) override;
  void restart() override;
  IntegratorStats stats() const override;

 private:
  // C trampolines: CVODES calls these with the integrator as user data.
  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* self);
  static int boundary_rhs(sunrealtype t, N_Vector y, N_Vector qdot, void* self);
  static int jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* self, N_Vector,
                      N_Vector, N_Vector);
  static int jtimes_setup(sunrealtype t, N_Vector y, N_Vector fy, void* self);
  static int jtimes(N_Vector v, N_Vector Jv, sunrealtype t, N_Vector y, N_Vector fy, void* self,
                    N_Vector tmp);
  static int precond_setup(sunrealtype t, N_Vector y, N_Vector fy, sunbooleantype jok,
                           sunbooleantype* jcur, sunrealtype gamma, void* self);
  static int precond_solve(sunrealtype t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z,
                           sunrealtype gamma, sunrealtype delta, int lr, void* self);

  void reinit_at_current_state();
  void check(int flag, const char* call) const;

  PreconditionerReuse amg_reuse_;  // with "amg": keep the V-cycle over small changes of gamma
  [[noreturn]] void fail(int flag, const char* call) const;

  struct MemoryFree {
    void operator()(void* mem) const;  // CVodeFree
  };
  // A derived member, so it is destroyed before the base's linear solver, matrix, vectors and
  // context, which is the order SUNDIALS needs.
  std::unique_ptr<void, MemoryFree> mem_;
};

}  // namespace tmdem::thermal

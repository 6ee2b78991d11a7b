#pragma once
// BDF with Newton through CVODES: sparse analytic Jacobian with KLU (symbolic factorization kept
// while the contact graph keeps its shape), or matrix-free Jacobian products with Jacobi-
// preconditioned CG. The boundary heat is a CVODES quadrature, integrated with the same steps.
//
// CG needs a symmetric Newton matrix; I - gamma C^-1 K is not (C varies), but its similarity
// transform in y = sqrt(C) T is. So with "pcg" the state is y = sqrt(C) T, with "klu" y = T.
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <string>
#include <vector>

#include "thermal/SundialsContext.h"
#include "thermal/ThermalIntegrator.h"
#include "thermal/ThermalSystem.h"

namespace tmdem::thermal {

class CvodeIntegrator final : public ThermalIntegrator {
 public:
  CvodeIntegrator(ThermalSystem& system, const IntegratorSettings& settings);
  ~CvodeIntegrator() override;
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  std::string_view name() const override { return "cvode"; }
  void initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) override;
  void advance_to(double t_s) override;
  void restart() override;
  double time_s() const override { return t_; }
  std::span<const double> temperatures_K() const override { return T_out_; }
  double boundary_heat_J() const override;
  IntegratorStats stats() const override;

 private:
  // C trampolines: SUNDIALS calls these with the integrator as user data.
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
  static void error_handler(int code, const char* module, const char* function, char* msg,
                            void* self);

  void unscale(N_Vector y);             // T_work_ = y / scale
  void reanalyse();                     // after a contact-graph shape change
  void reinit_at_current_state();
  void check(int flag, const char* call) const;
  [[noreturn]] void fail(int flag, const char* call) const;

  ThermalSystem& system_;
  IntegratorSettings settings_;
  bool pcg_ = false;
  SundialsContext ctx_;
  void* mem_ = nullptr;
  N_Vector y_ = nullptr, yQ_ = nullptr, abstol_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
  std::vector<double> scale_;           // sqrt(C) for pcg, empty for klu
  std::vector<double> T_work_, dT_work_, precond_diag_;
  std::vector<double> T_out_;
  double t_ = 0.0;
  double boundary_heat0_J_ = 0.0;
  std::uint64_t topology_seen_ = 0;
  IntegratorStats before_reinit_;       // counters of runs before the last CVodeReInit
  long reinitializations_ = 0;
  std::string last_error_;
};

}  // namespace tmdem::thermal

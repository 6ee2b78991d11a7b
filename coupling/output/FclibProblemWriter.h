#pragma once
// One frictional contact problem in the FCLIB "local" format (fclib.h of the FCLIB project,
// Debian's libfclib-dev), from plain arrays: this room never sees the mechanics. FCLIB's
// local problem: find r, u with  u = W r + q  and  the Coulomb law with the De Saxce
// modification u^ = u + mu |u_t| n  in each contact's local frame (n, t...), spacedim values
// per contact. The file holds, as FCLIB writes them:
//   /fclib_local   W (compressed columns), q, mu, spacedim, info (title, description, math_info)
//   /solution      r and u = W r + q of the solution given here
//   /guesses       one guess (r, u), here the same reactions
// and, beside FCLIB's groups, /tmdem: what a reader needs to turn the local solution into
// global quantities (FCLIB has no place for them; FCLIB readers ignore the group):
//   body_i, body_j      per contact, int32; body_j < 0 names wall -1 - body_j
//   normal, tangent1,   per contact, 3 doubles each (global frame; tangent2 is z in 2D runs)
//   tangent2
//   gravity_impulse     3 doubles, N s: h sum_i m_i g over the moving particles
//   time_step, step, dimension, solver_tolerance, solver_residual, solver_iterations,
//   solver_seconds, siconos_residual (tmdem's own evaluation of Siconos' measure, SiconosResidual.h),
//   omitted_contacts    scalars (omitted: candidates between two immobile bodies, W_cc = 0)
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tmdem::coupling {

struct FclibLocalProblem {
  int spacedim = 3;  // 2 or 3: values per contact (n, t1) or (n, t1, t2)
  std::size_t contacts = 0;
  // W, m x m with m = spacedim x contacts, compressed sparse columns (row indices sorted).
  std::vector<int> column_start;  // m + 1
  std::vector<int> row;
  std::vector<double> value;      // 1/kg
  std::vector<double> q;          // m/s, m values
  std::vector<double> mu;         // contacts values
  std::vector<double> r;          // N s, m values: the solution (also written as the guess)
  std::vector<double> u;          // m/s, m values: W r + q
  std::string title, description, math_info;

  // /tmdem (see above).
  std::vector<std::int32_t> body_i, body_j;
  std::vector<std::array<double, 3>> normal, tangent1, tangent2;
  std::array<double, 3> gravity_impulse{};
  double time_step_s = 0.0;
  std::int64_t step = 0;
  int dimension = 3;
  double solver_tolerance = 0.0;
  double solver_residual = 0.0;
  double siconos_residual = 0.0;  // the step's StepReport::siconos_residual
  double solver_seconds = 0.0;  // wall time of the step's contact solve
  std::int64_t solver_iterations = 0;
  std::int64_t omitted_contacts = 0;
};

// Writes `problem` to `path`, replacing a file there. Throws OutputError (naming the file)
// when it cannot be written; a partly written file is removed.
void write_fclib_local_problem(const FclibLocalProblem& problem, const std::string& path);

}  // namespace tmdem::coupling

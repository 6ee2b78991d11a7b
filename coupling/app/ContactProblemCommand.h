#pragma once
// `tmdem contact-problem SCENE.toml --step N|last -o PROBLEM.hdf5 [--set KEY=VALUE]...
// [--overwrite]`: runs the scene's mechanics (settle or dynamic, as `tmdem run` does) up to
// mechanical step N and writes that step's contact problem in the FCLIB local format
// (coupling/output/FclibProblemWriter.h) with tmdem's reactions as its solution, so that other
// solvers (Siconos, tests/crosscheck) can check and solve the very problem tmdem solved.
// Exit codes: 0; 2 for a scene without mechanics, with rolling resistance (not expressible in
// FCLIB), a step beyond the scene's steps, a step whose problem has no contact, an existing
// output without --overwrite; 4 for an output that cannot be written.
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "coupling/output/FclibProblemWriter.h"
#include "coupling/scene/Scene.h"
#include "mechanics/contact/ContactProblem.h"

namespace tmdem::coupling {

struct ContactProblemOptions {
  std::string step;  // a step number >= 1, or "last"
  std::string output_path;
  bool overwrite = false;
};

int run_contact_problem_command(const Scene& scene, const ContactProblemOptions& options,
                                std::ostream& out, std::ostream& log);

// The local problem of `problem` with `reactions` (one per contact, N s) as its solution:
// W_cd = H_c^T M^-1 H_d assembled column by column from unit impulses (ContactKinematics.h: apply_impulse, then
// local_velocity of every contact sharing a body), q = U(r = 0), u = U(r). Contacts between two
// immobile bodies (W_cc = 0: no reaction) are left out and counted in omitted_contacts.
// spacedim 2 for a 2D problem (n, t1), else 3. Throws std::invalid_argument for a problem with
// rolling resistance. The /tmdem extras other than the frames and bodies are left to the caller.
FclibLocalProblem fclib_local_problem(const mechanics::ContactProblem& problem,
                                      const std::vector<Eigen::Vector3d>& reactions);

}  // namespace tmdem::coupling

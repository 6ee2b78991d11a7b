#pragma once
// Contact solvers by name (mechanics.solver). Adding a solver: its own file implementing
// ContactSolver, plus one line in the table of ContactSolverRegistry.cpp.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::mechanics {

// Registered names, in registration order.
const std::vector<std::string>& contact_solver_names();

// The names of the solvers that solve compliant problems (ContactProblem::compliance: the
// "hertz" normal law), in registration order.
const std::vector<std::string>& compliant_contact_solver_names();

// The solver of a scene or NscdParameters that names none: the one place this default is set.
const std::string& default_contact_solver();

// Adds a solver to the table (a test program's testing aids: tests/program/), before any scene
// is read; not compliant. Throws std::invalid_argument if the name is taken.
void register_contact_solver(std::string name,
                             std::unique_ptr<ContactSolver> (*make)(const SolverSettings&));

// Throws std::invalid_argument naming the bad value and listing the valid names.
std::unique_ptr<ContactSolver> make_contact_solver(std::string_view name,
                                                   const SolverSettings& settings);

}  // namespace tmdem::mechanics

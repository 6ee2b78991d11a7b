#pragma once
// The names of the thermal integrators and linear solvers, parsed once into enums, so the code
// compares kinds, never strings. The names are the scene's values (thermal.integrator,
// thermal.linear_solver) and the accuracy-study CSV's `method` / `linear_solver` columns.
#include <array>
#include <stdexcept>
#include <string>
#include <string_view>

#include "thermal/network/KindName.h"

namespace tmdem::thermal {

enum class IntegratorKind { Cvode, Ida, Explicit };
enum class LinearSolverKind { Klu, Pcg, Amg };

inline constexpr std::array<std::string_view, 3> kIntegratorNames{"cvode", "ida", "explicit"};
inline constexpr std::array<std::string_view, 3> kLinearSolverNames{"klu", "pcg", "amg"};
// pcg and amg: conjugate gradients, preconditioned by IC(0) or by an algebraic-multigrid V-cycle.
constexpr bool is_conjugate_gradients(LinearSolverKind k) { return k != LinearSolverKind::Klu; }

// A scene that names no integrator or linear solver gets these: the one place they are set.
inline constexpr IntegratorKind kDefaultIntegrator = IntegratorKind::Cvode;
// thermal.linear_solver = "auto" is no kind: coupling turns it, once per run, into one of the
// kinds above from the problem's size, dimension, processes and symmetry
// (coupling/run/LinearSolverChoice.h), so the thermal side only ever sees klu, pcg or amg.
inline constexpr std::string_view kAutoLinearSolverName = "auto";
inline constexpr std::string_view kDefaultLinearSolverName = kAutoLinearSolverName;

constexpr std::string_view name_of(IntegratorKind k) { return kind_name(k, kIntegratorNames); }
constexpr std::string_view name_of(LinearSolverKind k) { return kind_name(k, kLinearSolverNames); }

// Unknown names throw std::invalid_argument listing the valid ones.
inline IntegratorKind parse_integrator_kind(std::string_view name) {
  return parse_kind<IntegratorKind>(name, kIntegratorNames, "thermal integrator");
}
// "auto" reaching here is a bug of the caller (it resolves it first), hence logic_error.
inline LinearSolverKind parse_linear_solver_kind(std::string_view name) {
  if (name == kAutoLinearSolverName)
    throw std::logic_error("linear solver \"auto\" reached the thermal side unresolved; it is "
                           "turned into klu, pcg or amg by coupling/run/LinearSolverChoice.h");
  return parse_kind<LinearSolverKind>(name, kLinearSolverNames, "linear solver");
}

}  // namespace tmdem::thermal

#include "mechanics/solvers/ContactSolverRegistry.h"

#include <stdexcept>

#include "mechanics/solvers/ApgdSolver.h"
#include "mechanics/solvers/BlockGaussSeidelSolver.h"
#include "mechanics/solvers/ColouredGaussSeidelSolver.h"
#include "mechanics/solvers/FallbackContactSolver.h"
#include "mechanics/solvers/GaussSeidelSolver.h"
#include "mechanics/solvers/InteriorPointSolver.h"
#include "mechanics/solvers/NncgSolver.h"
#include "mechanics/solvers/SubspaceGaussSeidelSolver.h"

namespace tmdem::mechanics {
namespace {

struct Entry {
  std::string name;
  std::unique_ptr<ContactSolver> (*make)(const SolverSettings&);
  // Solves compliant problems (ContactProblem::compliance): its local blocks go through
  // gauss_seidel_visit (GaussSeidelUpdate.h), its subspace steps add the compliance to W_AA
  // (ActiveSetSubspaceStep.h). The others build W's blocks themselves without it.
  bool compliant = false;
};

template <class Solver>
std::unique_ptr<ContactSolver> make(const SolverSettings& settings) {
  return std::make_unique<Solver>(settings);
}

std::unique_ptr<ContactSolver> make_coloured_nncg(const SolverSettings& settings) {
  NncgSolver::Options options;
  options.coloured = true;
  return std::make_unique<NncgSolver>(settings, options);
}

std::unique_ptr<ContactSolver> make_subspace_nncg(const SolverSettings& settings) {
  NncgSolver::Options options;
  options.subspace = true;
  return std::make_unique<NncgSolver>(settings, options);
}

std::unique_ptr<ContactSolver> make_nncg_ipm(const SolverSettings& settings) {
  // 30,000 unknowns: 5,000 spheres, 10,000 disks; nncg once more within 2x the tolerance
  // (FallbackContactSolver.h).
  auto solver = std::make_unique<FallbackContactSolver>("nncg_ipm", std::make_unique<NncgSolver>(settings),
                                                        std::make_unique<InteriorPointSolver>(settings), 30000,
                                                        settings.tolerance, 2.0);
  // A near miss nncg left twice: plain sweeps in runs of 500, Siconos' residual checked after
  // each, up to 20,000 (FallbackContactSolver::set_polisher).
  SolverSettings sweeps = settings;
  sweeps.tolerance = 0.0;
  sweeps.max_iterations = 500;
  sweeps.stall_sweeps = 1000;  // longer than a run: a run is never cut short by the stall test
  sweeps.full_sweep_every = 1;
  solver->set_polisher(std::make_unique<GaussSeidelSolver>(sweeps), 20000);
  return solver;
}

std::vector<Entry>& entries() {
  static std::vector<Entry> table = {
      {"nlgs", &make<GaussSeidelSolver>, true},
      {"apgd", &make<ApgdSolver>},
      {"nlgs_coloured", &make<ColouredGaussSeidelSolver>, true},
      {"nlgs_block", &make<BlockGaussSeidelSolver>},
      {"nncg", &make<NncgSolver>, true},
      {"nncg_coloured", &make_coloured_nncg, true},
      {"nlgs_subspace", &make<SubspaceGaussSeidelSolver>, true},
      {"nncg_subspace", &make_subspace_nncg, true},
      {"ipm", &make<InteriorPointSolver>},
      {"nncg_ipm", &make_nncg_ipm, true},
  };
  return table;
}

}  // namespace

const std::string& default_contact_solver() {
  // nncg_ipm: nncg (of the Gauss-Seidel family the fastest to rest with the most steps converged
  // on every example), and the interior point on the steps of beds up to 5,000 spheres that nncg
  // leaves unconverged; the same bits as nncg wherever nncg converges (docs/mechanics.md).
  static const std::string name = "nncg_ipm";
  return name;
}

namespace {
// The table's names, all and the compliant ones: collected again when a solver is registered.
struct Names {
  std::vector<std::string> all, compliant;
};
Names collect_names() {
  Names out;
  for (const auto& e : entries()) {
    out.all.push_back(e.name);
    if (e.compliant) out.compliant.push_back(e.name);
  }
  return out;
}
Names& names() {
  static Names table_names = collect_names();
  return table_names;
}
}  // namespace

const std::vector<std::string>& contact_solver_names() { return names().all; }

const std::vector<std::string>& compliant_contact_solver_names() { return names().compliant; }

void register_contact_solver(std::string name,
                             std::unique_ptr<ContactSolver> (*make)(const SolverSettings&)) {
  for (const auto& e : entries())
    if (e.name == name) throw std::invalid_argument("mechanics: solver \"" + name + "\" is already registered");
  entries().push_back({std::move(name), make, false});
  names() = collect_names();
}

std::unique_ptr<ContactSolver> make_contact_solver(std::string_view name,
                                                   const SolverSettings& settings) {
  for (const auto& e : entries()) {
    if (e.name == name) return e.make(settings);
  }
  std::string valid;
  for (const auto& n : contact_solver_names()) valid += (valid.empty() ? "" : ", ") + ("\"" + n + "\"");
  throw std::invalid_argument("mechanics: unknown solver \"" + std::string(name) +
                              "\" (valid: " + valid + ")");
}

}  // namespace tmdem::mechanics

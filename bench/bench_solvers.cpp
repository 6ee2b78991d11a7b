// Contact solvers side by side ("nlgs", "apgd", "nlgs_coloured") on the same settled 3D pile: residual
// reached, wall time and ns per contact per iteration, at 1 and 2 OpenMP threads.
//
// Pile: BenchLattice.h, 10 layers of touching spheres, mu = 0.3, after one step; each timed
// solve starts cold (reactions zero), the hard case: warm-started from the last step's
// reactions a pile at rest converges in one or two sweeps whichever the solver. Every solver
// stops on its own test at tolerance 1e-6; "residual" is the common measure of both answers
// (NaturalMapResidual.h), so the columns compare like with like.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>
#include <ctime>
#include <limits>
#include <random>

#include "BenchLattice.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/contact/SiconosResidual.h"
#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/solvers/NncgSolver.h"
#include "mechanics/solvers/SpatialContactOrder.h"
#include "mechanics/solvers/SubspaceGaussSeidelSolver.h"

using namespace tmdem::mechanics;

namespace {

// Args: solver (index into contact_solver_names()), spheres, threads.
void BM_ColdSolve(benchmark::State& state) {
  const std::string name = contact_solver_names().at(static_cast<std::size_t>(state.range(0)));
  const int layers = 10;
  NscdParameters parameters;
  parameters.max_iterations = 100000;
  NscdIntegrator sim(tmdem::bench::lattice(tmdem::bench::width_for(state.range(1), layers), layers),
                     {Material{7800.0, 2.1e11, 0.3, 0.3}},
                     {Wall::through({0, 0, 0}, {0, 1, 0}, 0)}, Eigen::Vector3d(0, -9.81, 0), 3,
                     parameters);
  sim.step();
  const ContactProblem& problem = sim.problem();
  SolverSettings settings;
  settings.tolerance = 1e-6;
  settings.max_iterations = 100000;
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(2)));
  std::vector<Eigen::Vector3d> r, v, w;
  double seconds = 0.0, residual = 0.0;
  std::int64_t iterations = 0, solves = 0, converged = 0;
  for (auto _ : state) {
    auto solver = make_contact_solver(name, settings);  // fresh: no state from the last solve
    r.assign(problem.size(), Eigen::Vector3d::Zero());
    const auto start = std::chrono::steady_clock::now();
    const SolveReport report = solver->solve(problem, r, v, w);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    iterations += report.sweeps;
    converged += report.converged ? 1 : 0;
    ++solves;
    residual = natural_map_residual(problem, r, v, w);
  }
  omp_set_num_threads(threads_before);
  state.SetLabel(name);
  state.counters["contacts"] = static_cast<double>(problem.size());
  state.counters["threads"] = static_cast<double>(state.range(2));
  state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(solves);
  state.counters["converged"] = static_cast<double>(converged) / static_cast<double>(solves);
  state.counters["residual"] = residual;
  state.counters["ms_per_solve"] = seconds * 1e3 / static_cast<double>(solves);
  state.counters["ns_per_contact_iteration"] =
      seconds * 1e9 / (static_cast<double>(iterations) * static_cast<double>(problem.size()));
}
BENCHMARK(BM_ColdSolve)
    ->ArgsProduct({{0, 1, 2}, {1000, 10000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// Solves from zero, `sweeps` sweeps each (no stop test can end them), of the problem of
// `pile` on a floor after one step (friction 0.3, rolling friction as given), with solver
// `name` at `threads` threads, either as numbered or through SpatialContactOrder (its copies
// in and out included). Counters: contacts and cpu_ns_sweep, ns per contact per sweep of CPU
// time (all threads: on a shared machine the wall time of one thread includes the time it
// waited for a core).
void time_fixed_sweeps(benchmark::State& state, ParticleSet pile, double rolling_friction,
                       const std::string& name, int threads, bool spatial_order) {
  const int sweeps = 100;
  Material material{7800.0, 2.1e11, 0.3, 0.3};
  material.rolling_friction = rolling_friction;
  NscdParameters parameters;
  parameters.spatial_order_from = std::numeric_limits<std::size_t>::max();  // the problem as numbered
  NscdIntegrator sim(std::move(pile), {material}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Eigen::Vector3d(0, -9.81, 0), 3, parameters);
  sim.step();
  const ContactProblem& problem = sim.problem();
  SolverSettings settings;
  settings.tolerance = 1e-300;
  settings.max_iterations = sweeps;
  settings.stall_sweeps = 1 << 30;
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(threads);
  auto solver = make_contact_solver(name, settings);
  SpatialContactOrder order;
  if (spatial_order) order.update(problem, sim.particles().position, 2.0 * sim.particles().max_radius());
  std::vector<Eigen::Vector3d> r, m, v, w;
  double seconds = 0.0;
  std::int64_t visits = 0;
  for (auto _ : state) {
    r.assign(problem.size(), Eigen::Vector3d::Zero());
    m.assign(problem.size(), Eigen::Vector3d::Zero());
    const std::clock_t start = std::clock();
    const SolveReport report = spatial_order ? order.solve(*solver, problem, r, m, v, w)
                                             : solver->solve_with_rolling(problem, r, m, v, w);
    seconds += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    visits += static_cast<std::int64_t>(report.sweeps) * static_cast<std::int64_t>(problem.size());
  }
  omp_set_num_threads(threads_before);
  state.counters["contacts"] = static_cast<double>(problem.size());
  state.counters["threads"] = static_cast<double>(threads);
  state.counters["cpu_ns_sweep"] = seconds * 1e9 / static_cast<double>(visits);
}

// The cost of one Gauss-Seidel visit on the lattice pile, with rolling resistance as in
// examples/pour_3d.toml (friction 0.3, rolling friction 0.05) or without. Every candidate of
// the pile is a contact, so active-set sweeps (ActiveContactSet.h) visit all of them and the
// counter is the visit itself. Note that two thirds of the pile's contacts are side contacts
// that carry nothing: a visit of such a contact returns at the open test
// (GaussSeidelUpdate.h), so the mean visit here is cheaper than on a poured bed, where most
// candidates close in a cold solve (measured with nlgs, 100 sweeps, rolling: 34% of the
// lattice's visits solve their contact against 69% of the 2,000 pour bed's at rest).
// Args: solver (index into contact_solver_names()), spheres, threads, rolling (0/1).
//   OMP_NUM_THREADS=1 build/bench/bench_solvers --benchmark_filter=BM_Sweeps/
void BM_Sweeps(benchmark::State& state) {
  const std::string name = contact_solver_names().at(static_cast<std::size_t>(state.range(0)));
  const int layers = 10;
  const bool rolling = state.range(3) != 0;
  time_fixed_sweeps(state, tmdem::bench::lattice(tmdem::bench::width_for(state.range(1), layers), layers),
                    rolling ? 0.05 : 0.0, name, static_cast<int>(state.range(2)), false);
  state.SetLabel(name + (rolling ? " rolling" : ""));
}
BENCHMARK(BM_Sweeps)
    ->ArgsProduct({{0, 2}, {10000}, {1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// What the particles' numbering costs (SpatialContactOrder.h): BM_Sweeps's pile with rolling
// resistance, "nlgs", one thread, with the particles numbered as built (layer by layer:
// neighbours have near numbers), numbered at random (as RandomPlacement leaves a poured bed),
// and numbered at random but solved through SpatialContactOrder. Args: spheres, numbering
// (0 as built, 1 random, 2 random then spatial order).
//   OMP_NUM_THREADS=1 build/bench/bench_solvers --benchmark_filter=BM_SweepsOrder
void BM_SweepsOrder(benchmark::State& state) {
  const int layers = 10;
  const int numbering = static_cast<int>(state.range(1));
  const ParticleSet built = tmdem::bench::lattice(tmdem::bench::width_for(state.range(0), layers), layers);
  std::vector<std::size_t> ids(built.size());
  for (std::size_t p = 0; p < ids.size(); ++p) ids[p] = p;
  if (numbering > 0) {
    // Fisher-Yates with our own draws (std::shuffle's are implementation-defined).
    std::mt19937_64 random(7);
    for (std::size_t p = ids.size(); p > 1; --p) std::swap(ids[p - 1], ids[random() % p]);
  }
  ParticleSet set;
  for (const std::size_t p : ids) set.add(built.position[p], built.radius[p], built.mass[p], 0);
  time_fixed_sweeps(state, std::move(set), 0.05, "nlgs", 1, numbering == 2);
  state.SetLabel(numbering == 0 ? "as built" : numbering == 1 ? "random ids" : "random ids, spatial order");
}
BENCHMARK(BM_SweepsOrder)
    ->ArgsProduct({{2000, 10000, 20000, 100000}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// Issue 24: does a solve's work grow with the bed's height or load? Lattice piles (BenchLattice.h)
// of 4 x 4 columns and 10, 40 or 160 layers (mu = 0.3), after one step from rest, solved cold
// (reactions zero: the load has to travel the whole chain) to 1e-6 by "nlgs", "nncg",
// "nlgs_subspace", "nncg_subspace" and "ipm"; loaded: the top layer 100x heavier (a piston's load on a bed).
// "nncg_ipm", the default, is solved as a run solves a step: the scene defaults' tolerance and
// sweep budget (NscdParameters), Siconos' residual as the stop test (its fallback only acts on
// a step nncg does not converge within the budget). Counters:
// sweeps (Gauss-Seidel sweeps of the solve), subspace (subspace steps of "nlgs_subspace":
// tried, kept, numeric factorisations), converged, residual (NaturalMapResidual.h) and
// cpu_ms (CPU time of one solve).
// Args: solver (0 nlgs, 1 nncg, 2 nlgs_subspace, 3 nncg_subspace, 4 ipm, 5 nncg_ipm), layers,
// loaded (0/1).
//   OMP_NUM_THREADS=1 build/bench/bench_solvers --benchmark_filter=BM_PileHeight
void BM_PileHeight(benchmark::State& state) {
  static const char* const names[] = {"nlgs", "nncg", "nlgs_subspace", "nncg_subspace", "ipm", "nncg_ipm"};
  const std::string name = names[state.range(0)];
  const int layers = static_cast<int>(state.range(1));
  const bool loaded = state.range(2) != 0;
  NscdParameters parameters;
  parameters.solver = "nncg";
  NscdIntegrator sim(tmdem::bench::lattice(4, layers, 1.0, loaded ? 100.0 : 1.0),
                     {Material{7800.0, 2.1e11, 0.3, 0.3}}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Eigen::Vector3d(0, -9.81, 0), 3, parameters);
  sim.step();
  const ContactProblem& problem = sim.problem();
  SolverSettings settings;
  settings.tolerance = 1e-6;
  settings.max_iterations = 200000;
  if (name == "nncg_ipm") {
    settings.tolerance = parameters.tolerance;
    settings.max_iterations = parameters.max_iterations;
    settings.siconos_stop = true;
  }
  std::vector<Eigen::Vector3d> r, v, w;
  double seconds = 0.0, residual = 0.0, siconos = 0.0;
  std::int64_t sweeps = 0, solves = 0, converged = 0, tried = 0, kept = 0, factorised = 0;
  for (auto _ : state) {
    auto solver = make_contact_solver(name, settings);
    r.assign(problem.size(), Eigen::Vector3d::Zero());
    const std::clock_t start = std::clock();
    const SolveReport report = solver->solve(problem, r, v, w);
    seconds += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    sweeps += report.sweeps;
    converged += report.converged ? 1 : 0;
    ++solves;
    residual = natural_map_residual(problem, r, v, w);
    const std::vector<Eigen::Vector3d> no_rolling;
    siconos = siconos_residual(problem, r, no_rolling, v, w, free_velocity_norm(problem));
    const ActiveSetSubspaceStep* subspace = nullptr;
    if (const auto* gs = dynamic_cast<const SubspaceGaussSeidelSolver*>(solver.get())) subspace = &gs->subspace();
    if (const auto* cg = dynamic_cast<const NncgSolver*>(solver.get())) subspace = &cg->subspace();
    if (subspace != nullptr) {
      tried += subspace->tried();
      kept += subspace->accepted();
      factorised += subspace->factorisations();
    }
  }
  const auto per_solve = [&](double x) { return x / static_cast<double>(solves); };
  state.SetLabel(name + (loaded ? " loaded" : ""));
  state.counters["contacts"] = static_cast<double>(problem.size());
  state.counters["sweeps"] = per_solve(static_cast<double>(sweeps));
  state.counters["subspace_tried"] = per_solve(static_cast<double>(tried));
  state.counters["subspace_kept"] = per_solve(static_cast<double>(kept));
  state.counters["factorisations"] = per_solve(static_cast<double>(factorised));
  state.counters["converged"] = per_solve(static_cast<double>(converged));
  state.counters["residual"] = residual;
  state.counters["siconos_residual"] = siconos;
  state.counters["cpu_ms"] = per_solve(seconds * 1e3);
}
BENCHMARK(BM_PileHeight)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {10, 40, 160}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();

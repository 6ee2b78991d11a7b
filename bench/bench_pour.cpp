// Pour and settle: examples/pour_3d.toml scaled to N spheres. Not in ctest. BM_Deposit: the
// same bed laid by sequential deposition, then settled; BM_PourLiggghts: the same pour in
// LIGGGHTS (soft spheres), where it is installed.
//
// The scene is examples/pour_3d.toml itself (materials, radii 0.5 and 1 mm, half steel and
// half glass, [mechanics] settings) with three changes: N/2 spheres per material, and the
// box's x and z widths scaled by sqrt(N / 2000) (fill region and side walls alike), so the
// bed keeps the example's depth (about 20 mm once settled) and only its footprint grows.
// Each benchmark settles once: steps until the scene's rest test says at rest
// (mechanics.rest_test: by default the contact network's forces stationary and the load
// carriers still, SettleRestTest.h) or mechanics.settle_time runs out, as `tmdem run`'s
// settle phase does (coupling/run/ThermalProblem.cpp).
//
//   build/bench/bench_pour --benchmark_filter=BM_Pour/2000/1/ --benchmark_counters_tabular=true
//
// Args: N, OpenMP threads. Environment:
//   TMDEM_POUR_MAX_STEPS   stop after this many steps (partial measurement of large N)
//   TMDEM_POUR_MAX_WALL_S  stop after this much wall time, s
//   TMDEM_POUR_SET         scene overrides as `tmdem run --set`, separated by ';'
//                          (e.g. "mechanics.solver=nlgs_coloured;mechanics.tolerance=1e-5")
//   TMDEM_POUR_FULL_SWEEP_EVERY  the Gauss-Seidel solvers' full sweep period
//                          (NscdParameters::full_sweep_every, ActiveContactSet.h), as
//                          TMDEM_POUR_SET="mechanics.full_sweep_every=K"
//   TMDEM_POUR_SPATIAL_ORDER_FROM  NscdParameters::spatial_order_from (SpatialContactOrder.h;
//                          0: always, 1e18: never)
//   TMDEM_POUR_TRACE       if set, one line per step on stderr: step, sweeps, residual,
//                          converged, correction sweeps, candidates, active contacts,
//                          largest speed (m/s), largest travel / r_min, penetration / r_min,
//                          then the fastest sphere: index, radius (m), centre x y z (m),
//                          velocity x y z (m/s), contacts carrying a force on it; the
//                          largest speed of a sphere with a loaded contact (m/s) and the
//                          number of spheres at or above settle_velocity; the step's
//                          kinetic + gravitational energy change and contact dissipation, J;
//                          the solver tolerance in force (mechanics.fall_tolerance schedule);
//                          the network rest test's force change over its window, load
//                          carriers' mean speed (m/s), load carriers and rattlers
//   TMDEM_POUR_PROBE_STEP  after this step, re-solve its problem from zero with plain
//                          symmetric Gauss-Seidel and print where it is slow (SlowModeProbe.h;
//                          TMDEM_POUR_PROBE_SWEEPS sweeps, default 400)
// Counters: particles; contacts (active, at the end) and candidates; settle_steps; sim_time_s;
// at_rest (1/0, by the scene's rest test); rattlers (of the network test, last step); mean_sweeps; converged_pct (steps whose solver converged); pen_rmin (largest
// penetration during the run / smallest radius) and pen_end_rmin (after the last step);
// fall_steps, fall_unconv, tight_step (the tolerance schedule: steps at fall_tolerance, of
// those unconverged, first step at the tight tolerance after the fall, 0: none);
// wall_s (wall time of the steps: to rest when at_rest = 1) and its parts detect_s, solve_s, correct_s; s_per_step; ns_step (wall time
// of the steps per candidate per sweep: detection and set-up included); ns_sweep (the
// solver alone: 40 sweeps of a fresh solver of the same kind on the last step's problem,
// per candidate per sweep, in the integrator's order); cpu_s and cpu_ns_sweep (the same in CPU time); cpu_ns_sweep_ids (that solve again on the problem in the particles' own numbering, without SpatialContactOrder); colours (of the last problem, ContactColouring.h); threads.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/run/SceneRestTest.h"
#include "coupling/scene/SceneLoader.h"
#include "mechanics/solvers/ContactColouring.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/solvers/SpatialContactOrder.h"
#include "SlowModeProbe.h"

using namespace tmdem;

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("bench_pour: cannot open " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void replace_all(std::string& text, const std::string& from, const std::string& to,
                 int expected) {
  int found = 0;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
    ++found;
  }
  if (found != expected) {
    throw std::runtime_error("bench_pour: examples/pour_3d.toml changed: expected " +
                             std::to_string(expected) + " x \"" + from + "\", found " +
                             std::to_string(found));
  }
}

// examples/pour_3d.toml with `count` spheres in a box `width` m wide in x and z; deposit: the
// generators of kind "deposit" instead of "random" (a bed laid by sequential deposition, then
// settled, instead of a pour).
coupling::Scene pour_scene(std::int64_t count, double width, bool deposit) {
  std::string text = read_file(std::string(TMDEM_SOURCE_DIR) + "/examples/pour_3d.toml");
  if (deposit) replace_all(text, "kind = \"random\"", "kind = \"deposit\"", 2);
  std::ostringstream w;
  w.precision(17);
  w << width;
  replace_all(text, "count = 1000", "count = " + std::to_string(count / 2), 2);
  replace_all(text, "max = [0.02, 0.06, 0.02]", "max = [" + w.str() + ", 0.06, " + w.str() + "]", 2);
  replace_all(text, "point = [0.02, 0.0, 0.0]", "point = [" + w.str() + ", 0.0, 0.0]", 1);
  replace_all(text, "point = [0.0, 0.0, 0.02]", "point = [0.0, 0.0, " + w.str() + "]", 1);
  std::vector<std::string> overrides;
  if (const char* set = std::getenv("TMDEM_POUR_SET")) {
    std::stringstream list(set);
    for (std::string item; std::getline(list, item, ';');) {
      if (!item.empty()) overrides.push_back(item);
    }
  }
  return coupling::load_scene_text(text, "pour_3d.toml (bench_pour)", overrides);
}

double env_number(const char* name, double fallback) {
  const char* value = std::getenv(name);
  return value ? std::stod(value) : fallback;
}

void run_pour(benchmark::State& state, bool deposit) {
  const std::int64_t count = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  const double width = 0.02 * std::sqrt(static_cast<double>(count) / 2000.0);
  const double max_steps = env_number("TMDEM_POUR_MAX_STEPS", 1e18);
  const double max_wall_s = env_number("TMDEM_POUR_MAX_WALL_S", 1e18);
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(threads);
  for (auto _ : state) {
    const auto build_start = std::chrono::steady_clock::now();
    const coupling::Scene scene = pour_scene(count, width, deposit);
    const double build_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
    // The scene's integrator (coupling::make_nscd_integrator), TMDEM_POUR_FULL_SWEEP_EVERY
    // overriding the scene's mechanics.full_sweep_every.
    mechanics::NscdParameters parameters = coupling::make_nscd_parameters(scene);
    parameters.full_sweep_every =
        static_cast<int>(env_number("TMDEM_POUR_FULL_SWEEP_EVERY", parameters.full_sweep_every));
    parameters.spatial_order_from = static_cast<std::size_t>(
        env_number("TMDEM_POUR_SPATIAL_ORDER_FROM", static_cast<double>(parameters.spatial_order_from)));
    const auto& g = scene.gravity_m_per_s2;
    auto sim = std::make_unique<mechanics::NscdIntegrator>(
        coupling::make_particle_set(scene), coupling::make_mechanics_materials(scene),
        coupling::make_mechanics_walls(scene), Eigen::Vector3d(g[0], g[1], g[2]), scene.dimension,
        parameters);
    const double h = scene.mechanics.time_step_s;
    const double r_min = sim->particles().min_radius();
    double t = 0.0, wall = 0.0, contact_sweeps = 0.0, pen_end = 0.0;
    std::int64_t steps = 0, converged = 0;
    bool at_rest = false;
    const bool trace = std::getenv("TMDEM_POUR_TRACE") != nullptr;
    const auto probe_step = static_cast<std::int64_t>(env_number("TMDEM_POUR_PROBE_STEP", -1));
    // The scene's rest test (mechanics.rest_test), as tmdem run's settle phase asks it.
    coupling::SceneRestTest rest(scene, *sim);
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    while (t < scene.mechanics.settle_time_s - 0.5 * h && steps < max_steps && wall < max_wall_s) {
      const mechanics::StepReport report = sim->step(h);
      t += h;
      ++steps;
      converged += report.converged ? 1 : 0;
      contact_sweeps += static_cast<double>(report.sweeps) * static_cast<double>(report.candidates);
      pen_end = report.max_penetration_m;
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const bool rested = rest.after_step();
      if (trace) {
        // The fastest sphere: which one, where, how it moves, how many contacts hold it.
        const auto& p = sim->particles();
        std::size_t fastest = 0;
        for (std::size_t k = 1; k < p.size(); ++k)
          if (p.velocity[k].squaredNorm() > p.velocity[fastest].squaredNorm()) fastest = k;
        int touching = 0;
        for (const auto& c : sim->contacts())
          if (c.normal_force_N > 0.0 && (c.i == static_cast<std::int64_t>(fastest) || c.j == static_cast<std::int64_t>(fastest)))
            ++touching;
        // What a settle criterion that discounts rattlers would see: the largest speed of a
        // sphere held by at least one loaded contact, and how many spheres move faster than
        // settle_velocity.
        std::vector<int> loaded(p.size(), 0);
        for (const auto& c : sim->contacts()) {
          if (!(c.normal_force_N > 0.0)) continue;
          ++loaded[static_cast<std::size_t>(c.i)];
          if (c.j >= 0 && c.j < static_cast<std::int64_t>(p.size())) ++loaded[static_cast<std::size_t>(c.j)];
        }
        double held_speed = 0.0;
        int moving = 0;
        for (std::size_t k = 0; k < p.size(); ++k) {
          const double speed = p.velocity[k].norm();
          if (loaded[k] > 0) held_speed = std::max(held_speed, speed);
          if (speed >= scene.mechanics.settle_velocity_m_per_s) ++moving;
        }
        const Eigen::Vector3d& x = p.position[fastest];
        const Eigen::Vector3d& u = p.velocity[fastest];
        std::fprintf(stderr, "%lld %d %.3e %d %d %zu %zu %.3e %.3f %.5f %zu %.1e %.5f %.5f %.5f %.3e %.3e %.3e %d %.3e %d %.4e %.4e %.1e %.3e %.3e %lld %lld\n",
                     static_cast<long long>(steps), report.sweeps, report.residual,
                     report.converged ? 1 : 0, report.correction_sweeps, report.candidates,
                     report.active_contacts, sim->max_speed(), report.max_travel_m / r_min,
                     report.max_penetration_m / r_min, fastest, p.radius[fastest], x.x(), x.y(),
                     x.z(), u.x(), u.y(), u.z(), touching, held_speed, moving,
                     report.energy_change_J, report.contact_dissipation_J, report.tolerance,
                     rest.network().force_change(), rest.network().load_speed_m_s(),
                     static_cast<long long>(rest.network().load_carriers()),
                     static_cast<long long>(rest.network().rattlers()));
      }
      if (steps == probe_step) {
        bench::print_slow_mode(sim->problem(), static_cast<int>(env_number("TMDEM_POUR_PROBE_SWEEPS", 400)), stderr);
        bench::print_solver_sweeps(sim->problem(), {"nlgs", "nlgs_block", "nncg"}, stderr);
        bench::print_block_ratios(sim->problem(), stderr);
      }
      if (rested) {
        at_rest = true;
        break;
      }
    }
    const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    // The solver alone on the last problem: 40 sweeps from zero reactions.
    mechanics::SolverSettings fixed;
    fixed.tolerance = 1e-300;
    fixed.max_iterations = 40;
    fixed.stall_sweeps = 1 << 30;
    auto solver = mechanics::make_contact_solver(scene.mechanics.solver, fixed);
    const mechanics::ContactProblem& problem = sim->problem();
    std::vector<Eigen::Vector3d> r(problem.size(), Eigen::Vector3d::Zero()), v, w;
    std::vector<Eigen::Vector3d> m(problem.size(), Eigen::Vector3d::Zero());  // rolling
    const auto solve_start = std::chrono::steady_clock::now();
    const std::clock_t solve_cpu_start = std::clock();
    // In the order the integrator hands its solver (SpatialContactOrder.h), copies included.
    mechanics::SpatialContactOrder order;
    const bool ordered = sim->particles().size() >= parameters.spatial_order_from;
    if (ordered) order.update(problem, sim->particles().position, 2.0 * sim->particles().max_radius());
    const mechanics::SolveReport solved = ordered ? order.solve(*solver, problem, r, m, v, w)
                                                  : solver->solve_with_rolling(problem, r, m, v, w);
    const double solve_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count();
    const double solve_cpu_s = static_cast<double>(std::clock() - solve_cpu_start) / CLOCKS_PER_SEC;

    state.SetIterationTime(wall);
    state.SetLabel(scene.mechanics.solver + (deposit ? " (deposit)" : ""));
    state.counters["build_s"] = build_s;  // reading the scene: the deposition for BM_Deposit
    state.counters["particles"] = static_cast<double>(sim->particles().size());
    state.counters["contacts"] = static_cast<double>(sim->contacts().size());
    state.counters["candidates"] = static_cast<double>(problem.size());
    state.counters["settle_steps"] = static_cast<double>(steps);
    state.counters["sim_time_s"] = t;
    state.counters["at_rest"] = at_rest ? 1.0 : 0.0;
    state.counters["rattlers"] = static_cast<double>(rest.network().rattlers());
    state.counters["max_speed"] = sim->max_speed();
    state.counters["mean_sweeps"] = sim->stats().mean_sweeps();
    state.counters["converged_pct"] = 100.0 * static_cast<double>(converged) / static_cast<double>(steps);
    // The tolerance schedule (mechanics.fall_tolerance): steps solved at fall_tolerance, of
    // those unconverged, and the first step at the tight tolerance after the fall (0: none).
    state.counters["fall_steps"] = static_cast<double>(sim->stats().fall_steps);
    state.counters["fall_unconv"] = static_cast<double>(sim->stats().fall_unconverged_steps);
    state.counters["tight_step"] = static_cast<double>(sim->tolerance_schedule().landed_step());
    state.counters["pen_rmin"] = sim->stats().max_penetration_m / r_min;
    state.counters["pen_end_rmin"] = pen_end / r_min;
    state.counters["wall_s"] = wall;
    // The wall time's parts (NscdIntegrator's own clocks): detection and contact set-up, the
    // contact solve, the penetration correction, s.
    state.counters["detect_s"] = sim->stats().detection_s;
    state.counters["solve_s"] = sim->stats().solve_s;
    state.counters["correct_s"] = sim->stats().correction_s;
    state.counters["s_per_step"] = wall / static_cast<double>(steps);
    state.counters["ns_step"] = wall * 1e9 / contact_sweeps;
    state.counters["ns_sweep"] =
        solve_s * 1e9 / (static_cast<double>(std::max(solved.sweeps, 1)) * static_cast<double>(problem.size()));
    // CPU time of the process (all threads): on a shared machine the wall time of one thread
    // includes the time it waited for a core.
    state.counters["cpu_s"] = cpu_s;
    state.counters["cpu_ns_sweep"] =
        solve_cpu_s * 1e9 / (static_cast<double>(std::max(solved.sweeps, 1)) * static_cast<double>(problem.size()));
    // The same solve in the particles' own numbering (the scene's ids): what the order saves.
    {
      auto plain = mechanics::make_contact_solver(scene.mechanics.solver, fixed);
      std::fill(r.begin(), r.end(), Eigen::Vector3d::Zero());
      std::fill(m.begin(), m.end(), Eigen::Vector3d::Zero());
      const std::clock_t plain_start = std::clock();
      const mechanics::SolveReport report = plain->solve_with_rolling(problem, r, m, v, w);
      state.counters["cpu_ns_sweep_ids"] =
          static_cast<double>(std::clock() - plain_start) / CLOCKS_PER_SEC * 1e9 /
          (static_cast<double>(std::max(report.sweeps, 1)) * static_cast<double>(problem.size()));
    }
    mechanics::ContactColouring colouring;  // what "nlgs_coloured" would use on that problem
    colouring.update(problem);
    state.counters["colours"] = static_cast<double>(colouring.colour_count());
    state.counters["threads"] = threads;
  }
  omp_set_num_threads(threads_before);
}

void BM_Pour(benchmark::State& state) { run_pour(state, false); }
BENCHMARK(BM_Pour)
    ->ArgsProduct({{2000, 10000, 20000, 100000}, {1, 2}})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// The same bed laid by sequential deposition ([[generate]] kind = "deposit"), then settled.
void BM_Deposit(benchmark::State& state) { run_pour(state, true); }
BENCHMARK(BM_Deposit)
    ->ArgsProduct({{2000, 10000, 20000, 100000}, {1, 2}})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// The same pour in LIGGGHTS 3.8 (Debian `liggghts`), the soft-sphere peer: pour_3d's spheres
// (radii 0.5 and 1 mm, a quarter each of steel and glass at each radius, by number; LIGGGHTS
// takes the classes' mass fractions), friction 0.3 and rolling friction 0.05 (its "cdt" model),
// restitution 0.3 (LIGGGHTS needs one above 0; tmdem's contacts are perfectly inelastic), in
// the same box. Young's moduli softened 21,000x (1e7 and 3e6 Pa) for a time step of 1e-5 s, as
// soft-sphere users do (at the real moduli the stable step is about 100x smaller). Inserted at
// once at random in the fill region (insert/pack, as the random generators), 0.5 s simulated.
// Counters: liggghts_s (its loop time, wall), ke_end_J, rest_time_s (the first thermo output,
// every 0.01 s, with kinetic energy below 5e-11 J; -1: none), threads (1: serial LIGGGHTS).
// Skipped when `liggghts` is not on the PATH.
std::string liggghts_input(std::int64_t count, double width) {
  const double volume[2] = {0.0005 * 0.0005 * 0.0005, 0.001 * 0.001 * 0.001};
  const double density[2] = {7800.0, 2500.0};
  double mass[4], total = 0.0;
  for (int k = 0; k < 4; ++k) total += mass[k] = density[k / 2] * volume[k % 2];
  std::ostringstream in;
  in.precision(10);
  in << "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
     << "communicate single vel yes\nunits si\nsoft_particles yes\n"
     << "region box block 0 " << width << " 0 0.062 0 " << width << " units box\n"
     << "create_box 2 box\nneighbor 0.0005 bin\nneigh_modify delay 0\n"
     << "fix m1 all property/global youngsModulus peratomtype 1.0e7 3.0e6\n"
     << "fix m2 all property/global poissonsRatio peratomtype 0.3 0.22\n"
     << "fix m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3\n"
     << "fix m4 all property/global coefficientFriction peratomtypepair 2 0.3 0.3 0.3 0.3\n"
     << "fix m5 all property/global coefficientRollingFriction peratomtypepair 2 0.05 0.05 0.05 0.05\n"
     << "pair_style gran model hertz tangential history rolling_friction cdt\npair_coeff * *\n"
     << "timestep 1.e-5\nfix gravity all gravity 9.81 vector 0 -1 0\n";
  const char* planes[5][2] = {{"yplane", "0.0"}, {"xplane", "0.0"}, {"xplane", "W"}, {"zplane", "0.0"}, {"zplane", "W"}};
  for (int k = 0; k < 5; ++k)
    in << "fix wall" << k << " all wall/gran model hertz tangential history rolling_friction cdt "
       << "primitive type 1 " << planes[k][0] << " " << (planes[k][1][0] == 'W' ? width : 0.0) << "\n";
  const char* seeds[4] = {"15485863", "15485867", "32452843", "32452867"};
  for (int k = 0; k < 4; ++k)
    in << "fix t" << k << " all particletemplate/sphere " << seeds[k] << " atom_type " << k / 2 + 1
       << " density constant " << density[k / 2] << " radius constant " << (k % 2 ? 0.001 : 0.0005) << "\n";
  in << "fix pdd all particledistribution/discrete 49979687 4";
  for (int k = 0; k < 4; ++k) in << " t" << k << " " << mass[k] / total;
  in << "\nregion fill block 0 " << width << " 0 0.06 0 " << width << " units box\n"
     << "fix ins all insert/pack seed 67867967 distributiontemplate pdd maxattempt 1000 "
     << "insert_every once overlapcheck yes all_in yes particles_in_region " << count << " region fill\n"
     << "fix integr all nve/sphere\ncompute ke all ke\nthermo_style custom step atoms c_ke\n"
     << "thermo 1000\nthermo_modify lost ignore norm no\nrun 50000\n";
  return in.str();
}

void BM_PourLiggghts(benchmark::State& state) {
  const std::int64_t count = state.range(0);
  const double width = 0.02 * std::sqrt(static_cast<double>(count) / 2000.0);
  if (std::system("command -v liggghts > /dev/null 2>&1") != 0) {
    state.SkipWithError("liggghts is not installed (Debian: apt-get install liggghts)");
    return;
  }
  for (auto _ : state) {
    char folder[] = "/tmp/bench_pour_liggghtsXXXXXX";
    if (!mkdtemp(folder)) throw std::runtime_error("bench_pour: cannot make a temporary folder");
    const std::string dir = folder;
    std::ofstream(dir + "/pour.in") << liggghts_input(count, width);
    const std::string command = "cd " + dir + " && liggghts -in pour.in -log log.lammps -echo none > out.txt 2>&1";
    if (std::system(command.c_str()) != 0) {
      state.SkipWithError(("liggghts failed; see " + dir + "/out.txt").c_str());
      return;
    }
    std::ifstream log(dir + "/log.lammps");
    double loop_s = -1.0, ke_end = -1.0, rest_time = -1.0;
    for (std::string line; std::getline(log, line);) {
      if (line.rfind("Loop time of ", 0) == 0) loop_s = std::stod(line.substr(13));
      std::istringstream fields(line);
      long step = 0, atoms = 0;
      double ke = 0.0;
      if (fields >> step >> atoms >> ke && atoms == count) {
        ke_end = ke;
        if (rest_time < 0.0 && ke < 5e-11) rest_time = static_cast<double>(step) * 1e-5;
      }
    }
    std::system(("rm -rf " + dir).c_str());
    state.SetIterationTime(loop_s);
    state.SetLabel("liggghts");
    state.counters["particles"] = static_cast<double>(count);
    state.counters["liggghts_s"] = loop_s;
    state.counters["ke_end_J"] = ke_end;
    state.counters["rest_time_s"] = rest_time;
    state.counters["threads"] = 1;
  }
}
BENCHMARK(BM_PourLiggghts)
    ->Arg(2000)
    ->Arg(10000)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();

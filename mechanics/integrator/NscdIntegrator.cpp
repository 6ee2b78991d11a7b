#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/integrator/StaticWarmStart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/contact/SiconosResidual.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("mechanics: " + message);
}

}  // namespace

NscdIntegrator::NscdIntegrator(ParticleSet particles, std::vector<Material> materials,
                               std::vector<Wall> walls, const Eigen::Vector3d& gravity_m_per_s2,
                               int dimension, NscdParameters parameters)
    : particles_(std::move(particles)),
      materials_(std::move(materials)),
      walls_(std::move(walls)),
      gravity_(gravity_m_per_s2),
      dimension_(dimension),
      parameters_(parameters),
      detector_(parameters.min_margin_fraction * std::max(particles_.max_radius(), 1e-300),
                parameters.max_margin_fraction * std::max(particles_.max_radius(), 1e-300),
                parameters.parallel_from) {
  particles_.validate();
  require(dimension == 2 || dimension == 3, "dimension must be 2 or 3");
  require(gravity_.allFinite(), "gravity must be finite");
  require(parameters_.time_step > 0.0 && std::isfinite(parameters_.time_step),
          "time_step must be positive");
  require(parameters_.theta > 0.0 && parameters_.theta <= 1.0, "theta must be in (0, 1]");
  require(parameters_.tolerance > 0.0, "tolerance must be positive");
  require(parameters_.max_iterations >= 1, "max_iterations must be at least 1");
  require(parameters_.penetration_slop_fraction >= 0.0 &&
              parameters_.penetration_slop_fraction < 1.0,
          "penetration_slop_fraction must be in [0, 1)");
  require(parameters_.recovery_speed >= 0.0 && std::isfinite(parameters_.recovery_speed),
          "recovery_speed must be >= 0");
  require(parameters_.relaxation > 0.0 && parameters_.relaxation < 2.0,
          "relaxation must be in (0, 2)");
  for (std::size_t m = 0; m < materials_.size(); ++m) {
    require(materials_[m].friction >= 0.0 && std::isfinite(materials_[m].friction),
            "material " + std::to_string(m) + ": friction must be >= 0");
    require(materials_[m].rolling_friction >= 0.0 && std::isfinite(materials_[m].rolling_friction),
            "material " + std::to_string(m) + ": rolling_friction must be >= 0");
    rolling_ = rolling_ || materials_[m].rolling_friction > 0.0;
  }
  const auto material_count = static_cast<int>(materials_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    require(particles_.material[i] < material_count,
            "particle " + std::to_string(i) + ": material index out of range");
  }
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    require(walls_[w].material >= 0 && walls_[w].material < material_count,
            "wall " + std::to_string(w) + ": material index out of range");
    require(walls_[w].point.allFinite() && walls_[w].normal.allFinite() &&
                std::abs(walls_[w].normal.norm() - 1.0) < 1e-12,
            "wall " + std::to_string(w) + ": normal must be a unit vector");
    if (walls_[w].moves()) {
      require(walls_[w].shape == WallShape::Plane, "wall " + std::to_string(w) + ": a piston must be a plane");
      require(std::isfinite(walls_[w].mass_kg) && std::isfinite(walls_[w].load_N) &&
                  std::isfinite(walls_[w].velocity_m_per_s),
              "wall " + std::to_string(w) + ": piston mass, load and velocity must be finite");
      has_piston_ = true;
    } else {
      walls_[w].velocity_m_per_s = 0.0;
    }
  }
  if (dimension_ == 2) {
    gravity_.z() = 0.0;
    // A wall normal with a z component would push particles out of the plane.
    for (auto& wall : walls_) {
      require(wall.shape == WallShape::Plane, "a cylinder wall needs 3D");
      wall.normal.z() = 0.0;
      require(wall.normal.norm() > 0.0, "a wall normal along z makes no sense in 2D");
      wall.normal.normalize();
    }
  }

  const std::size_t n = particles_.size();
  inverse_mass_.resize(n);
  inverse_inertia_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool fixed = particles_.fixed[i] != 0;
    inverse_mass_[i] = fixed ? 0.0 : 1.0 / particles_.mass[i];
    inverse_inertia_[i] = fixed ? 0.0 : 1.0 / particles_.inertia[i];
    if (fixed) {
      particles_.velocity[i].setZero();
      particles_.angular_velocity[i].setZero();
    }
  }
  keep_in_plane();
  for (int a = 0; a < 3; ++a) {
    if (!particles_.box.along(a)) continue;
    require(a < dimension_, "a 2D run cannot be periodic along z");
    for (std::size_t w = 0; w < walls_.size(); ++w)
      require(walls_[w].shape == WallShape::Plane && walls_[w].normal[a] == 0.0,
              "wall " + std::to_string(w) + " crosses periodic axis " + std::to_string(a) +
                  " (only plane walls parallel to a periodic axis are allowed)");
  }
  // Start inside the periodic box (the scene wraps its particles; a hand-built set may not).
  for (auto& x : particles_.position) x = particles_.box.wrap(x);
  slop_m_ = parameters_.penetration_slop_fraction * particles_.min_radius();
  // Validates fall_tolerance, fall_speed and tighten_steps (std::invalid_argument).
  require(parameters_.fall_speed >= 0.0 && std::isfinite(parameters_.fall_speed),
          "fall_speed must be >= 0 (m/s; 0: automatic)");
  require(parameters_.fall_share >= 0.0 && parameters_.fall_share <= 1.0,
          "fall_share must be in [0, 1] (0: the fastest particle alone)");
  require(!parameters_.compaction_speed ||
              (*parameters_.compaction_speed >= 0.0 && std::isfinite(*parameters_.compaction_speed)),
          "compaction_speed must be >= 0 (m/s; 0: off; absent: automatic)");
  require(parameters_.compaction_fraction >= 0.0 && std::isfinite(parameters_.compaction_fraction),
          "compaction_fraction must be >= 0 (0: off)");
  require(parameters_.retry_parts >= 1 && parameters_.retry_parts <= NscdParameters::kMaxRetryParts,
          "retry_parts must be in [1, " + std::to_string(NscdParameters::kMaxRetryParts) + "] (1: never retaken)");
  require(parameters_.fall_travel_fraction > 0.0 && std::isfinite(parameters_.fall_travel_fraction),
          "fall_travel_fraction must be > 0");
  const double fall_speed_m_per_s =
      parameters_.fall_speed > 0.0
          ? parameters_.fall_speed
          : parameters_.fall_travel_fraction * particles_.min_radius() / parameters_.time_step;
  // Without particles there is no automatic fall speed, and nothing to fall.
  if (fall_speed_m_per_s > 0.0 || parameters_.fall_tolerance <= 0.0)
    schedule_ = ToleranceSchedule(parameters_.tolerance, parameters_.fall_tolerance,
                                  fall_speed_m_per_s, parameters_.tighten_steps);
  SolverSettings& settings = solver_settings_;
  settings.tolerance = parameters_.tolerance;
  settings.max_iterations = parameters_.max_iterations;
  settings.relaxation = parameters_.relaxation;
  settings.stall_sweeps = parameters_.stall_sweeps;
  settings.full_sweep_every = parameters_.full_sweep_every;
  settings.siconos_stop = parameters_.siconos_stop && (parameters_.solver == "nncg" || parameters_.solver == "nncg_ipm");
  settings.residual_check_every = parameters_.residual_check_every;
  settings.parallel_from = parameters_.parallel_from;
  solver_ = make_contact_solver(parameters_.solver, settings);
  if (compliant()) {
    const auto& names = compliant_contact_solver_names();
    std::string valid;
    for (const auto& name : names) valid += (valid.empty() ? "\"" : ", \"") + name + "\"";
    require(std::find(names.begin(), names.end(), parameters_.solver) != names.end(),
            "normal_law \"hertz\" needs a Gauss-Seidel solver, not \"" + parameters_.solver +
                "\" (valid: " + valid + ")");
    for (std::size_t m = 0; m < materials_.size(); ++m)
      require(materials_[m].young_modulus > 0.0 && std::isfinite(materials_[m].young_modulus) &&
                  materials_[m].poisson_ratio > -1.0 && materials_[m].poisson_ratio < 0.5,
              "material " + std::to_string(m) +
                  ": normal_law \"hertz\" needs young_modulus > 0 Pa and poisson_ratio in (-1, 0.5)");
    problem_.compliant = true;
  }
  order_ = SpatialContactOrder(parameters_.parallel_from);
  problem_.rolling = rolling_;
  require(parameters_.stop_travel_fraction >= 0.0 && std::isfinite(parameters_.stop_travel_fraction),
          "stop_travel_fraction must be >= 0 (0: off)");
  stop_speed_m_per_s_ = parameters_.stop_travel_fraction * particles_.min_radius() / parameters_.time_step;
  // Built once with `tolerance`: the position solve stops at max(tolerance, 1e-2) anyway.
  SolverSettings correction_settings = settings;  // a copy: solver_settings_ stays the solver's
  correction_settings.full_sweep_every = parameters_.correction_full_sweep_every;
  correction_ = PenetrationCorrection(correction_settings);
  problem_.dimension = dimension_;
  problem_.particle_count = n;
  problem_.inverse_mass = inverse_mass_;
  problem_.inverse_inertia = inverse_inertia_;
  for (const auto& wall : walls_) {
    problem_.inverse_mass.push_back(wall.moves() ? 1.0 / wall.mass_kg : 0.0);
    problem_.inverse_inertia.push_back(0.0);
  }
  const std::size_t bodies = problem_.body_count();
  problem_.free_velocity.assign(bodies, Eigen::Vector3d::Zero());
  problem_.free_angular_velocity.assign(bodies, Eigen::Vector3d::Zero());
  old_velocity_.assign(bodies, Eigen::Vector3d::Zero());
  old_angular_velocity_.assign(bodies, Eigen::Vector3d::Zero());
  body_velocity_.assign(bodies, Eigen::Vector3d::Zero());
  body_angular_velocity_.assign(bodies, Eigen::Vector3d::Zero());
  lookahead_.resize(n);
  if (has_piston_) {
    wall_lookahead_.assign(walls_.size(), 0.0);
    wall_listing_lookahead_.assign(walls_.size(), 0.0);
    wall_carried_N_.assign(walls_.size(), 0.0);
    wall_travel_m_.assign(walls_.size(), 0.0);
  }
}

void NscdIntegrator::set_piston_load(std::size_t wall, double load_N) {
  require(wall < walls_.size() && walls_[wall].moves(),
          "wall " + std::to_string(wall) + " is not a piston");
  require(std::isfinite(load_N), "wall " + std::to_string(wall) + ": piston load must be finite");
  // A landed bed given a new load compacts as after a landing: the tolerance ramps again
  // (ToleranceSchedule::ramp_again_from). Through piston_cylinder's study the 1e4 Pa load
  // began with steps stalled just above 1e-5 (docs/mechanics.md "A tolerance schedule").
  if (load_N != walls_[wall].load_N) schedule_.ramp_again_from(stats_.steps + 1);
  walls_[wall].load_N = load_N;
}

void NscdIntegrator::invalidate_contacts() { detector_.invalidate(); }

void NscdIntegrator::keep_in_plane() {
  if (dimension_ != 2) return;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    particles_.velocity[i].z() = 0.0;
    particles_.angular_velocity[i].x() = 0.0;
    particles_.angular_velocity[i].y() = 0.0;
  }
}

StepReport NscdIntegrator::step() { return step(parameters_.time_step); }

StepReport NscdIntegrator::step_in_parts(double part_s, int parts, bool landing_parts) {
  StepReport report = step(part_s, landing_parts);
  for (int part = 1; part < parts; ++part) report = merged(report, step(part_s, landing_parts));
  return report;
}

StepReport NscdIntegrator::step(double h, bool landing_parts) {
  if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("mechanics: step must be > 0");
  // A step too long for the periods is taken as two halves, before anything changes (the
  // schedule's phase included). Only where the run would otherwise stop: a landing piston on a
  // narrow periodic bed that kicks two spheres sideways (bench/beds/periodic_landing.toml, seed
  // 7: 5.2 mm of look-aheads across 14 mm periods that leave 5 mm).
  // The look-aheads across the periods are those refresh_candidates hands the detector: the
  // velocities do not change before it.
  if (particles_.box.any()) {
    fill_periodic_lookahead(h);
    if (h > std::ldexp(parameters_.time_step, -kMaxHalvings) * (1.0 + 1e-9) &&
        !detector_.fits_periods(particles_, periodic_lookahead_)) {
      ++stats_.halved_steps;
      const StepReport first = step(0.5 * h, landing_parts);
      return merged(first, step(0.5 * h, landing_parts));
    }
  }
  // A piston landing at metres per second hands its speed to the bed within the step, so every
  // pair within its reach (2 h |v|, 14 mm at 7 m/s and 1 ms) is listed and solved
  // (periodic_pressed: every pair of its 1,000 spheres, 501,500 candidates, 45 s a step). In
  // 2^k equal parts (the fewest whose reach fits, at most 2^kMaxHalvings) the piston lands
  // within a part, on a table of neighbours. Equal parts, not halves of halves: a part longer
  // than the one before activates contacts whose gap the wall closes within the part's first
  // half (theta = 1/2), and the wall overshoots them (a column's landing in parts of 1/8, 1/8,
  // 1/4 and 1/2 of the step left the piston 7% of a radius into it; in 8 parts of 1/8 it rests
  // on the column's top, as in one step).
  if (landing_parts && has_piston_ && wall_lands_too_fast(h)) {
    int halvings = 1;
    while (halvings < kMaxHalvings && wall_lands_too_fast(std::ldexp(h, -halvings))) ++halvings;
    ++stats_.landing_halved_steps;
    const int parts = 1 << halvings;
    in_landing_parts_ = true;
    const StepReport report = step_in_parts(std::ldexp(h, -halvings), parts, false);
    in_landing_parts_ = false;
    return report;
  }
  StepReport report;
  report.time_step_s = h;
  const std::size_t n = particles_.size();
  // Only the schedule reads it (and the cap, while the schedule says falling).
  const double start_speed_m_per_s = schedule_.enabled() ? max_speed() : 0.0;
  report.tolerance = schedule_.enabled()
                         ? schedule_.tolerance_for_step(
                               // Only a fall's start reads the share's speed.
                               schedule_.phase() == ToleranceSchedule::Phase::Before
                                   ? fall_judged_speed()
                                   : start_speed_m_per_s,
                               start_speed_m_per_s, stats_.steps + 1, piston_compacting(h))
                         : parameters_.tolerance;
  report.fall = schedule_.falling();
  use_tolerance(report.tolerance);
  // While falling, impulses are mostly impacts of bodies at the speeds present, and the cap
  // is the impulse at the largest of them: with r_min / h alone pour_3d's first 100 steps
  // took 46% more sweeps; with none, a heavy piston landing on a light sphere (its impulse 300
  // times the sphere's m v) sank 25 um into it (test_e2e_piston).
  problem_.stop_speed = stop_speed_m_per_s_ > 0.0 && report.fall
                            ? std::max(stop_speed_m_per_s_, start_speed_m_per_s)
                            : stop_speed_m_per_s_;
  const std::size_t rebuilds_before = detector_.rebuild_count();
  auto clock = std::chrono::steady_clock::now();
  // Seconds since the last lap, and a new lap (no allocation: a clock read).
  auto lap = [&clock] {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - clock).count();
    clock = now;
    return seconds;
  };
  if (has_piston_) refresh_wall_bodies(h);
  refresh_candidates(h);
  report.rebuilt_candidates = detector_.rebuild_count() != rebuilds_before;
  report.detection_s = lap();

  // Free velocities (gravity only; no external torque).
  for (std::size_t i = 0; i < n; ++i) {
    old_velocity_[i] = particles_.velocity[i];
    old_angular_velocity_[i] = particles_.angular_velocity[i];
    problem_.free_velocity[i] = particles_.velocity[i];
    if (inverse_mass_[i] > 0.0) problem_.free_velocity[i] += h * gravity_;
    problem_.free_angular_velocity[i] = particles_.angular_velocity[i];
  }
  lap();
  setup_contacts(h);
  if (compliant()) set_hertz_laws(h);
  // Where the particles are, for a solver that cuts the contacts into slabs (ContactSlabs.h).
  problem_.particle_position.assign(particles_.position.begin(), particles_.position.end());
  problem_.split_axis = split_axis();
  problem_.split_period = particles_.box.along(problem_.split_axis)
                              ? std::array<double, 2>{particles_.box.low[problem_.split_axis],
                                                      particles_.box.high[problem_.split_axis]}
                              : std::array<double, 2>{0.0, 0.0};
  if (!holds_overlap_.empty()) take_initial_overlaps();
  if (static_start_pending_) {
    static_start_pending_ = false;
    // Heights along a periodic axis have no order.
    bool periodic_gravity = false;
    for (int a = 0; a < 3; ++a) periodic_gravity |= particles_.box.along(a) && gravity_[a] != 0.0;
    if (parameters_.static_warm_start && !periodic_gravity)
      static_warm_start(problem_, gap_, particles_.position, gravity_, h, reactions_,
                        parameters_.static_balance_rounds);
  }
  report.detection_s += lap();
  report.candidates = problem_.size();
  SolveReport solved = solve_contacts();
  // A table listed with a piston's likely reach (estimate_wall_reach) must hold every pair the
  // step's travel could close; where it does not (the bed gave way under the load), the step is
  // listed again with the bound and solved again, from the same warm start.
  if (listing_estimated_ && !listing_covers_travel(h)) {
    const int first_sweeps = solved.sweeps;
    report.relisted = true;  // counted by MechanicsStats::add
    report.solve_s = lap();
    relist_with_bound(h);
    setup_contacts(h);
    if (compliant()) set_hertz_laws(h);
    report.detection_s += lap();
    report.candidates = problem_.size();
    solved = solve_contacts();
    solved.sweeps += first_sweeps;
  }
  report.solve_s += lap();
  std::copy_n(body_velocity_.begin(), n, particles_.velocity.begin());
  std::copy_n(body_angular_velocity_.begin(), n, particles_.angular_velocity.begin());
  report.sweeps = solved.sweeps;
  report.residual = solved.residual;
  report.converged = solved.converged;
  report.stalled = solved.stalled;
  // Siconos' measure of the reactions the step goes on with, whatever the solver's own stop test
  // (SiconosResidual.h): one pass over the candidates, before keep_in_plane trims anything.
  report.siconos_residual = siconos_residual(problem_, reactions_, rolling_impulse_, body_velocity_,
                                             body_angular_velocity_, free_velocity_norm(problem_));
  // (The form with rolling impulses reads them only when the problem has rolling resistance.)
  report.natural_map_residual =
      natural_map_residual(problem_, reactions_, rolling_impulse_, body_velocity_, body_angular_velocity_);
  // With the "siconos" stop test a step counts as converged when this residual is within the
  // tolerance in force, whatever the sweep test said (docs/mechanics.md "Honest convergence"):
  // a solve that ran out of sweeps or stalled on its sweep change with e within the tolerance
  // has converged by the measure the run reports.
  if (solver_settings_.siconos_stop) {
    report.converged = report.siconos_residual <= report.tolerance;
    report.stalled = solved.stalled && !report.converged;
  }
  if (solved.fallback_stage != SolveReport::kNoFallback) {
    report.fallback.solves = 1;
    report.fallback.sweeps = solved.fallback_sweeps;
    report.fallback.seconds = solved.fallback_s;
    report.fallback.first_sweeps = solved.fallback_first_sweeps;
    report.fallback.first_seconds = solved.fallback_first_s;
    if (solved.fallback_stage == SolveReport::kWithinWhenHandedOn) {
      report.fallback.within_when_handed_on = 1;
    } else if (report.converged) {
      if (solved.fallback_stage == SolveReport::kSecondSolver) report.fallback.converged_by_second = 1;
      if (solved.fallback_stage == SolveReport::kFirstAgain) report.fallback.converged_by_first_again = 1;
      if (solved.fallback_stage == SolveReport::kPlainSweeps) report.fallback.converged_by_sweeps = 1;
    }
  }
  keep_in_plane();
  // The bodies' view again (keep_in_plane may have trimmed the particles'), for the energy
  // account and the contacts' dissipation below.
  std::copy_n(particles_.velocity.begin(), n, body_velocity_.begin());
  std::copy_n(particles_.angular_velocity.begin(), n, body_angular_velocity_.begin());
  account_energy(h, report);

  // Positions: q_{n+1} = q_n + h (theta v_{n+1} + (1 - theta) v_n).
  const double theta = parameters_.theta;
  double travel_squared = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    const Eigen::Vector3d dx = h * (theta * particles_.velocity[i] + (1.0 - theta) * old_velocity_[i]);
    particles_.position[i] += dx;
    travel_squared = std::max(travel_squared, dx.squaredNorm());
  }
  report.max_travel_m = std::sqrt(travel_squared);
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    Wall& wall = walls_[w];
    if (!wall.moves()) continue;
    const double before = wall.velocity_m_per_s;
    wall.velocity_m_per_s = body_velocity_[n + w].dot(wall.normal);
    wall.point += h * (theta * wall.velocity_m_per_s + (1.0 - theta) * before) * wall.normal;
  }
  // Then overlaps deeper than the slop are removed by moving positions only.
  lap();
  gaps_after_step(gap_after_);
  if (compliant()) add_elastic_overlaps(h, gap_after_);  // a compliant law's overlaps are its own
  if (!held_overlap_.empty()) add_held_overlaps(gap_after_);  // and a held one the packing's
  // Each pass solves the position problem to PenetrationCorrection::kTolerance, which leaves a
  // share of a deep overlap. The parts of a landing leave overlaps of a fifth of a radius
  // (periodic_pressed, parts in halves of halves: 0.26 mm before the correction, 58 um after
  // one pass, 7% of the smallest radius), so there a rigid step's overlap still beyond
  // kDeepOverlapSlops slops after a pass gets another, up to kCorrectionPasses. Only in a
  // landing's parts: on whole steps one pass leaves about 1% of the smallest radius at most on
  // the beds measured (polydisperse: 1.1%), and another pass there only changes a trajectory
  // (polydisperse then no longer came to rest within 300 s, against 55 s).
  // The gaps above are the rigid ones (no compliant law's or held overlaps added): the extra
  // passes and the piston's pass below judge depths only on those.
  const bool rigid_gaps = !compliant() && held_overlap_.empty();
  auto correct = [&](bool move_pistons) {
    const SolveReport corrected = correction_.correct(problem_, gap_after_, slop_m_,
                                                      parameters_.recovery_speed, h,
                                                      particles_.position, move_pistons);
    report.correction_sweeps += corrected.sweeps;
    if (!corrected.converged) {
      report.converged = false;
      report.stalled = report.stalled || corrected.stalled;
      report.residual = std::max(report.residual, corrected.residual);
    }
    if (corrected.sweeps > 0) {
      const auto& pseudo = correction_.pseudo_velocity();
      for (std::size_t i = 0; i < n; ++i) {
        if (inverse_mass_[i] > 0.0)
          report.correction_potential_J -= particles_.mass[i] * gravity_.dot(h * pseudo[i]);
      }
      // A piston's share, along its normal; its potential is that of the constant force on it
      // (load plus weight), as in the energy account.
      for (std::size_t w = 0; move_pistons && w < walls_.size(); ++w) {
        Wall& wall = walls_[w];
        if (!wall.moves()) continue;
        const Eigen::Vector3d dx = h * pseudo[n + w].dot(wall.normal) * wall.normal;
        wall.point += dx;
        report.correction_potential_J -= (wall.load_N * wall.normal + wall.mass_kg * gravity_).dot(dx);
      }
    }
    if (corrected.sweeps > 0 || !rigid_gaps) gaps_after_step(gap_after_);
    return corrected.sweeps > 0;
  };
  // Depth beyond the trigger, summed over the contacts (m): a correction that can move what it
  // corrects removes nearly all of it (its tolerance leaves about 1%).
  const auto depth_beyond_trigger_m = [&] {
    double sum = 0.0;
    for (std::size_t k = 0; k < problem_.size(); ++k)
      if (problem_.solvable(k)) sum += std::max(0.0, -gap_after_[k] - PenetrationCorrection::kTrigger * slop_m_);
    return sum;
  };
  const double depth_before_m = has_piston_ && rigid_gaps ? depth_beyond_trigger_m() : 0.0;
  bool corrected = correct(false);
  for (int pass = 1; corrected && in_landing_parts_ && rigid_gaps && pass < kCorrectionPasses; ++pass) {
    double deepest_m = 0.0;
    for (const double gap : gap_after_) deepest_m = std::max(deepest_m, -gap);
    if (!(deepest_m > kDeepOverlapSlops * slop_m_)) break;
    corrected = correct(false);
  }
  // A correction that left half the depth or more could not move what it corrects: particles
  // pinned between a fixed wall and a piston the correction holds (a piston inside a column
  // standing on the floor: the column's total overlap stays the piston's depth, only shared
  // out). Then one more pass in which the pistons take their share (PenetrationCorrection.h).
  // Rigid contacts only, as the extra passes: with a compliant law or held overlaps the gaps
  // measured here carry the law's or the packing's overlaps, and there the pass only changed a
  // trajectory (thermal_cycling's settle: 179 steps instead of 93, 20 unconverged instead of 16).
  if (corrected && has_piston_ && rigid_gaps && depth_beyond_trigger_m() > 0.5 * depth_before_m) {
    correct(true);
    ++stats_.piston_corrections;
  }
  report.correction_s = lap();
  // Back into the periodic box: pairs are (i, j) ids and their vectors minimum images, so a
  // wrapped particle keeps its candidates, warm starts and contacts.
  if (particles_.box.any())
    for (auto& x : particles_.position) x = particles_.box.wrap(x);

  // Forces for the warm start and the contact list; penetration after the step.
  contacts_.clear();
  double penetration = 0.0;
  for (std::size_t k = 0; k < problem_.size(); ++k) {
    const Eigen::Vector3d& r = reactions_[k];
    const std::int32_t i = problem_.body_i[k], j = problem_.body_j[k];
    force_[k] = global_impulse(problem_, k, r) / h;
    penetration = std::max(penetration, -gap_after_[k]);
    // -r . u_theta, u_theta the relative velocity the position update uses (bias removed).
    const Eigen::Vector3d u_theta =
        theta * local_velocity<Eigen::Vector3d>(problem_, k, body_velocity_, body_angular_velocity_) +
        (1.0 - theta) * local_velocity<Eigen::Vector3d>(problem_, k, old_velocity_, old_angular_velocity_) -
        Eigen::Vector3d(problem_.bias[k], 0.0, 0.0);
    double dissipated_J = -r.dot(u_theta);
    if (rolling_) {
      // Rolling work: -m . (theta w_rel+ + (1 - theta) w_rel-), w_rel = omega_i - omega_j.
      const Eigen::Vector3d& m = rolling_impulse_[k];
      torque_[k] = m / h;
      dissipated_J -= m.dot(theta * rolling_velocity<Eigen::Vector3d>(problem_, k, body_angular_velocity_) +
                            (1.0 - theta) * rolling_velocity<Eigen::Vector3d>(problem_, k, old_angular_velocity_));
    }
    report.contact_dissipation_J += dissipated_J;
    if (r[0] > 0.0) {
      ContactForce out;
      out.i = i;
      out.j = j;
      out.normal = problem_.normal[k];
      out.gap_m = gap_[k];
      out.normal_impulse_Ns = r[0];
      out.normal_force_N = r[0] / h;
      out.tangential_force_N = (r[1] * problem_.tangent1[k] + r[2] * problem_.tangent2[k]) / h;
      out.dissipated_power_W = dissipated_J / h;
      contacts_.push_back(out);
    }
  }
  report.max_penetration_m = penetration;
  report.active_contacts = contacts_.size();
  stats_.add(report);
  return report;
}

int NscdIntegrator::split_axis() const {
  // Slabs stand upright: a cut across gravity would break every force chain at each slab
  // boundary, while upright slabs keep a chain inside one slab, swept in one pass.
  int vertical = -1;
  if (gravity_.head(dimension_).squaredNorm() > 0.0) gravity_.head(dimension_).cwiseAbs().maxCoeff(&vertical);
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
  for (const Eigen::Vector3d& x : particles_.position) {
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  int axis = vertical == 0 ? 1 : 0;
  for (int a = 0; a < dimension_; ++a) {
    if (a != vertical && high[a] - low[a] > high[axis] - low[axis]) axis = a;
  }
  return axis;
}

void NscdIntegrator::use_tolerance(double tolerance) {
  if (tolerance == solver_settings_.tolerance) return;
  // A new solver of the same kind with the other tolerance, carrying what the solver carries
  // between solves: what a restart does (restore_state), so the switch keeps restarts bitwise.
  const std::vector<double> carried = solver_->carried_state();
  solver_settings_.tolerance = tolerance;
  solver_ = make_contact_solver(parameters_.solver, solver_settings_);
  solver_->restore_carried_state(carried);
  solver_->set_hand_on(hand_on_);
}

void NscdIntegrator::set_hand_on(bool allowed) {
  hand_on_ = allowed;
  solver_->set_hand_on(allowed);
}

SolveReport NscdIntegrator::solve_contacts() {
  if (particles_.size() >= parameters_.spatial_order_from) {
    // The order of the table's reference positions (MechanicsState.h saves them): a restored
    // integrator computes the same order as the one it was saved from.
    if (!order_.valid())
      order_.update(problem_, detector_.reference_positions(), 2.0 * particles_.max_radius());
    return order_.solve(*solver_, problem_, reactions_, rolling_impulse_, body_velocity_,
                        body_angular_velocity_);
  }
  // Without rolling resistance rolling_impulse_ stays empty and is not read (ContactSolver.h),
  // as in the ordered call above.
  return solver_->solve_with_rolling(problem_, reactions_, rolling_impulse_, body_velocity_,
                                     body_angular_velocity_);
}

void NscdIntegrator::gaps_after_step(std::vector<double>& gap) const {
  gap.resize(problem_.size());
  const bool periodic = particles_.box.any();
  for (std::size_t k = 0; k < problem_.size(); ++k) {
    const std::int32_t i = problem_.body_i[k], j = problem_.body_j[k];
    if (!is_wall(j)) {
      const Eigen::Vector3d d = particles_.position[i] - particles_.position[j];
      gap[k] = (periodic ? particles_.box.minimum_image(d) : d).norm() - problem_.lever_i[k] -
               problem_.lever_j[k];
    } else {
      gap[k] = walls_[wall_index(j)].signed_distance(particles_.position[i]) - problem_.lever_i[k];
    }
  }
}

}  // namespace tmdem::mechanics

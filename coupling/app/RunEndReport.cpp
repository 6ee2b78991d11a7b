#include "coupling/app/RunEndReport.h"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace tmdem::coupling {

std::vector<TimingRow> timing_rows(const RunSummary& summary) {
  if (!summary.wall_time_parts) return {};
  const auto& w = *summary.wall_time_parts;
  // "other" also takes the mechanics step's own bookkeeping (free velocities, energy account,
  // position update, contact list): mechanics_s minus its three timed parts.
  const double step_rest_s =
      std::max(0.0, w.mechanics_s - w.detection_s - w.contact_solve_s - w.correction_s);
  std::vector<TimingRow> rows{{"contact detection", w.detection_s, 0.0},
                              {"contact solve", w.contact_solve_s, 0.0},
                              {"penetration correction", w.correction_s, 0.0},
                              {"thermal", w.thermal_s, 0.0},
                              {"output", w.output_s, 0.0},
                              {"other", w.other_s + step_rest_s, 0.0}};
  double total = 0.0;
  for (const auto& row : rows) total += row.seconds;
  for (auto& row : rows) row.share = total > 0.0 ? row.seconds / total : 0.0;
  return rows;
}

std::vector<WarningCount> warning_counts(const RunSummary& summary) {
  const auto& m = summary.mechanics;
  std::vector<WarningCount> kinds{
      {"contact solve not converged", m.unconverged_steps - m.stalled_steps,
       "the step goes on with the last iterate (Siconos' residual in each warning says how far "
       "from the law). Where a load compacts the bed (a piston or plate on a bed at the edge of "
       "jamming) the residual sits on a plateau that more sweeps (mechanics.max_iterations) do "
       "not lower (docs/mechanics.md \"Why loaded steps stay above the tolerance\"); elsewhere "
       "raise mechanics.max_iterations or loosen mechanics.tolerance"},
      {"contact solve stalled", m.stalled_steps,
       "no 10% gain over the stall window (500 sweeps; nncg 4,000, then restarted from the "
       "stalled reactions up to 3 times), typical of frictional piles creeping on a plateau "
       "(docs/mechanics.md \"Stopping\")"}};
  std::erase_if(kinds, [](const WarningCount& k) { return k.count <= 0; });
  return kinds;
}

namespace {

void print_timing(const RunSummary& summary, std::ostream& out) {
  const auto rows = timing_rows(summary);
  if (rows.empty()) return;
  out << "timing (wall time " << summary.wall_time_s << " s):\n";
  for (const auto& row : rows) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-38s %10.3f s %6.1f%%\n", row.part.c_str(), row.seconds,
                  100.0 * row.share);
    out << line;
  }
}

void print_warnings(const RunSummary& summary, std::ostream& out) {
  const auto kinds = warning_counts(summary);
  if (kinds.empty()) return;
  // One warning was printed per unconverged step of h (unconverged_time_steps), the first
  // kWarningsShown of them; unconverged_steps counts each unconverged part of a step taken in
  // parts (a landing, a retry), so it may be larger.
  const std::int64_t total = summary.mechanics.unconverged_steps;
  const std::int64_t warned = summary.mechanics.unconverged_time_steps;
  const std::string shown =
      warned > kWarningsShown ? "the first " + std::to_string(kWarningsShown) : std::string("all");
  out << "warnings: " << total << " mechanics steps unconverged, ";
  if (warned != total)
    out << "counting each part of a step taken in parts; of " << warned << " steps of the time step, ";
  out << shown << " printed above:\n";
  for (const auto& w : kinds) out << "  " << w.count << " x " << w.kind << ": " << w.advice << "\n";
}

}  // namespace

void print_run_end(const RunSummary& summary, const Scene& scene, const std::string& wrote_path,
                   bool quiet, std::ostream& out) {
  if (!quiet && !wrote_path.empty())
    out << "wrote " << wrote_path << " (" << summary.wall_time_s
        << " s wall time, energy balance error " << summary.energy.balance_error_rel << ")\n";
  if (!quiet) {
    print_timing(summary, out);
    print_warnings(summary, out);
  }
  const auto& m = summary.mechanics;
  if (!quiet && m.steps > 0) {
    double r_min_m = std::numeric_limits<double>::infinity();
    for (const auto& p : scene.particles) r_min_m = std::min(r_min_m, p.radius_m);
    out << "mechanics: " << m.steps << " steps, mean " << m.mean_iterations << " iterations, "
        << m.unconverged_steps << " unconverged (" << m.stalled_steps
        << " stalled), Siconos' residual up to " << m.max_siconos_residual << " ("
        << m.siconos_unconverged_steps << " steps above the tolerance), largest penetration "
        << m.max_penetration_m << " m";
    if (r_min_m > 0.0 && r_min_m < std::numeric_limits<double>::infinity())
      out << " (" << 100.0 * m.max_penetration_m / r_min_m << "% of the smallest radius)";
    if (m.correction_sweeps > 0) {
      out << ", penetration correction " << m.correction_sweeps << " sweeps";
      if (summary.energy.mechanical)
        out << " (potential energy " << summary.energy.mechanical->correction_potential_J << " J)";
    }
    if (m.halved_steps > 0)
      out << ", " << m.halved_steps << " steps halved: particles fast across the periods (docs/mechanics.md "
          << "\"Periodic boundaries\")";
    if (m.landing_halved_steps > 0)
      out << ", " << m.landing_halved_steps << " steps taken in parts: a moving wall landing faster than a radius per step "
          << "(docs/mechanics.md \"A falling piston's margin\")";
    if (m.retried_steps > 0)
      out << ", " << m.retried_steps << " unconverged steps retaken in parts (" << m.discarded_sweeps
          << " sweeps thrown away; mechanics.retry_parts, docs/mechanics.md \"Retaking an unconverged step\")";
    if (m.kept_parts_steps > 0)
      out << ", " << m.kept_parts_steps << " steps started in the parts a retry before them needed "
          << "(mechanics.retry_keep_steps, docs/mechanics.md \"Steps that start in the parts the last retry needed\")";
    if (m.relisted_steps > 0)
      out << ", " << m.relisted_steps << " steps listed again: the travel under a loaded piston "
          << "left the table its likely reach had listed (docs/mechanics.md \"A loaded piston's reach\")";
    if (m.piston_corrections > 0)
      out << ", " << m.piston_corrections << " corrections moved a piston: particles pinned under it "
          << "(docs/mechanics.md \"Penetration without speed\")";
    out << "\n";
    // The default solver's fallback, where it ran: what it cost and which stage converged.
    if (const auto& f = m.fallback; f && f->solves > 0) {
      const std::int64_t converged = f->converged_by_second + f->converged_by_first_again + f->converged_by_sweeps;
      out << "mechanics: " << f->solves << " solves handed on by the first solver, " << converged
          << " then converged (" << f->converged_by_second << " by the second solver, " << f->converged_by_first_again
          << " by the first once more, " << f->converged_by_sweeps << " by plain sweeps; "
          << f->within_when_handed_on << " more were within the tolerance already by Siconos' measure); " << f->sweeps
          << " iterations and " << f->seconds << " s in those stages, after " << f->first_sweeps << " and "
          << f->first_seconds << " s of the first solver's on them (docs/summary.md, mechanics.fallback)\n";
    }
    // Nothing to say of a schedule whose fall never began (on by default: most small scenes).
    if (const auto& ts = m.tolerance_schedule; ts && ts->fall_steps > 0) {
      // A piston's compaction keeps the schedule falling too (mechanics.compaction_speed; the
      // summary's is 0 without a piston, or off).
      const bool pistons = ts->compaction_speed_m_s > 0.0;
      out << "mechanics: tolerance " << ts->fall_tolerance
          << (pistons ? " while falling, compacting or collapsing (" : " while falling or collapsing (")
          << ts->fall_steps
          << " steps, " << ts->fall_unconverged_steps << " unconverged";
      if (ts->collapse_steps > 0)
        out << "; " << ts->collapse_steps << " steps that stalled at " << ts->tolerance
            << " while the bed crept retaken at " << ts->fall_tolerance
            << ", collapsing until its largest speed is below a tenth of mechanics.fall_speed";
      out << "), " << ts->tolerance;
      if (ts->tightened) {
        out << " from step " << ts->tightened_step + ts->tighten_steps - 1;
        if (ts->tighten_steps > 1)
          out << " (tightening over " << ts->tighten_steps << " steps from step " << ts->tightened_step << ")";
        out << "; the fall ended at t = " << ts->tightened_time_s
            << " s of mechanics (largest speed below mechanics.fall_speed = " << ts->fall_speed_m_s
            << " m/s";
        if (pistons)
          out << ", every piston below mechanics.compaction_speed = " << ts->compaction_speed_m_s << " m/s";
        out << ")\n";
      }
      else
        out << " not reached: the largest speed never dropped back below mechanics.fall_speed = "
            << ts->fall_speed_m_s << " m/s"
            << (pistons ? " with every piston below mechanics.compaction_speed" : "") << "\n";
    }
  }
  // A run interrupted while settling froze nothing: it stopped before t = 0.
  const bool stopped_settling = summary.status == "interrupted" && summary.simulated_time_s == 0.0;
  if (summary.settle && !summary.settle->at_rest && !stopped_settling) {
    out << "warning: the packing was frozen WITHOUT coming to rest (mechanics.rest_test = \""
        << scene.mechanics.rest_test << "\"): largest speed " << summary.settle->max_speed_m_s
        << " m/s after " << summary.settle->time_s << " s (" << summary.settle->steps
        << " steps), mechanics.settle_velocity = " << scene.mechanics.settle_velocity_m_per_s
        << " m/s; raise mechanics.settle_time or check the contact solver\n";
  }
  out.flush();
}

}  // namespace tmdem::coupling

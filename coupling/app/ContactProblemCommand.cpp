#include "coupling/app/ContactProblemCommand.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/common/ExitCode.h"
#include "coupling/output/OutputError.h"
#include "coupling/run/SceneRestTest.h"
#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/integrator/NscdIntegrator.h"

namespace tmdem::coupling {

namespace {

using mechanics::ContactProblem;

std::array<double, 3> array_of(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// Mechanical steps the scene's run takes at most: settling stops at rest earlier.
std::int64_t scene_step_limit(const Scene& scene) {
  const double h = scene.mechanics.time_step_s;
  std::int64_t steps = 0;
  // "coupled" settles first, as "settle": its first packing is that one.
  if (scene.effects.mechanics == MechanicsMode::Settle || scene.effects.mechanics == MechanicsMode::Coupled) {
    for (double t = 0.0; t < scene.mechanics.settle_time_s - 0.5 * h; t += h) ++steps;
  } else {  // dynamic, as CoupledRun::run_dynamic: steps of h, the last one cut at the duration
    for (double t = 0.0; t < scene.duration_s - 1e-9 * h; ++steps)
      t = std::min(double(steps + 1) * h, scene.duration_s);
  }
  return steps;
}

// "step N" as a number >= 1, or 0 for "last"; -1 when it is neither.
std::int64_t parse_step(const std::string& text) {
  if (text == "last") return 0;
  std::int64_t step = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), step);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || step < 1) return -1;
  return step;
}

// An error for the user: message and exit code.
struct CommandError {
  std::string message;
  int code;
};

// The output must be writable before minutes of mechanics run: create it (or open an
// existing one for appending, which changes nothing) and remove what was created.
void check_output(const ContactProblemOptions& options, const std::string& scene_source) {
  const std::string& path = options.output_path;
  if (path.empty()) throw CommandError{"-o needs a file name (got an empty one)", kExitInvalid};
  std::error_code ec;
  const bool existed = std::filesystem::exists(path, ec);
  if (existed && std::filesystem::equivalent(path, scene_source, ec))
    throw CommandError{"-o " + path + " names the scene file itself", kExitInvalid};
  if (existed && !options.overwrite)
    throw CommandError{path + " exists; give --overwrite to replace it", kExitInvalid};
  { std::ofstream probe(path, std::ios::binary | std::ios::app); if (!probe) {
      const auto folder = std::filesystem::path(path).parent_path();
      const bool no_folder = !folder.empty() && !std::filesystem::is_directory(folder, ec);
      throw CommandError{"cannot write '" + path + "'" +
                             (no_folder ? ": folder '" + folder.string() + "' does not exist" : ""),
                         kExitIo};
    } }
  if (!existed) std::filesystem::remove(path, ec);
}

void check_scene(const Scene& scene) {
  if (scene.effects.mechanics == MechanicsMode::Off)
    throw CommandError{"effects.mechanics = \"off\": the scene has no mechanical steps, hence no "
                       "contact problem", kExitInvalid};
  for (std::size_t k = 0; k < scene.materials.size(); ++k)
    if (scene.materials[k].rolling_friction > 0.0) {
      std::ostringstream msg;
      msg << "material[" << k << "].rolling_friction = " << scene.materials[k].rolling_friction
          << " (material '" << scene.materials[k].name
          << "'): rolling resistance has no place in an FCLIB problem (Coulomb friction only); "
             "export the scene without it, e.g. --set material["
          << k << "].rolling_friction=0";
      throw CommandError{msg.str(), kExitInvalid};
    }
}

struct StepOutcome {
  std::int64_t step = 0;
  double time_s = 0.0;
  double h_s = 0.0;  // the step's length
  mechanics::StepReport report;
};

// Runs the mechanics up to step `wanted` (0: the last one) as `tmdem run` would.
StepOutcome run_to_step(mechanics::NscdIntegrator& nscd, const Scene& scene, std::int64_t wanted) {
  const std::int64_t limit = scene_step_limit(scene);
  const bool settle = scene.effects.mechanics == MechanicsMode::Settle ||
                      scene.effects.mechanics == MechanicsMode::Coupled;
  if (wanted > limit) {
    std::ostringstream msg;
    msg << "--step " << wanted << " is beyond the scene's mechanical steps: "
        << (settle ? "it settles for at most " : "its run takes ") << limit << " steps of "
        << scene.mechanics.time_step_s << " s"
        << (settle ? " (mechanics.settle_time)" : " (simulation.duration)");
    throw CommandError{msg.str(), kExitInvalid};
  }
  StepOutcome outcome;
  const double h = scene.mechanics.time_step_s;
  const std::int64_t last = wanted == 0 ? limit : wanted;
  SceneRestTest rest(scene, nscd);
  while (outcome.step < last) {
    const double t_next = settle ? double(outcome.step + 1) * h
                                 : std::min(double(outcome.step + 1) * h, scene.duration_s);
    // Settling steps by h itself (settle_packing), a dynamic run to the next multiple of h
    // (CoupledRun::run_dynamic): t_next - t is not h to the bit (0.078 - 0.077 = 0.001 +
    // 9e-19), and steps of it had drifted from the run's trajectory (piston_cylinder's step 78
    // was still falling here, at the fall's tolerance, where the run had tightened).
    outcome.h_s = settle ? h : t_next - outcome.time_s;
    outcome.report = nscd.step(outcome.h_s);
    outcome.time_s = t_next;
    ++outcome.step;
    // Settling ends at rest by the scene's test, as settle_packing's: later steps are not the
    // scene's.
    if (settle && rest.after_step() && outcome.step < last) {
      if (wanted == 0) break;
      std::ostringstream msg;
      msg << "--step " << wanted << " is beyond the scene's mechanical steps: it comes to rest "
          << "(mechanics.rest_test = \"" << scene.mechanics.rest_test << "\") after step "
          << outcome.step
          << " (t = " << outcome.time_s << " s), where settling ends; --step " << outcome.step
          << " or --step last is the settled packing";
      throw CommandError{msg.str(), kExitInvalid};
    }
  }
  return outcome;
}

}  // namespace

FclibLocalProblem fclib_local_problem(const ContactProblem& problem,
                                      const std::vector<Eigen::Vector3d>& reactions) {
  if (problem.rolling)
    throw std::invalid_argument("a contact problem with rolling resistance has no FCLIB form");
  if (reactions.size() != problem.size())
    throw std::invalid_argument("fclib_local_problem: one reaction per contact needed");
  FclibLocalProblem out;
  const int d = problem.dimension == 2 ? 2 : 3;
  out.spacedim = d;
  out.dimension = problem.dimension;

  // The contacts that carry a reaction, numbered as in the file.
  std::vector<std::int64_t> slot(problem.size(), -1);
  std::vector<std::size_t> kept;
  for (std::size_t c = 0; c < problem.size(); ++c)
    if (problem.solvable(c)) {
      slot[c] = std::int64_t(kept.size());
      kept.push_back(c);
    }
  out.contacts = kept.size();
  out.omitted_contacts = std::int64_t(problem.size() - kept.size());

  // The contacts of each body that can move (only those couple contacts in W).
  const std::size_t bodies = problem.body_count();
  auto body_j = [&](std::size_t c) {
    const std::int32_t j = problem.body_j[c];
    return mechanics::is_wall(j) ? problem.wall_body(j) : std::size_t(j);
  };
  auto moves = [&](std::size_t b) {
    return problem.inverse_mass[b] > 0.0 || problem.inverse_inertia[b] > 0.0;
  };
  std::vector<std::vector<std::size_t>> contacts_of(bodies);
  for (std::size_t k = 0; k < kept.size(); ++k)
    for (const std::size_t b : {std::size_t(problem.body_i[kept[k]]), body_j(kept[k])})
      if (moves(b) && (contacts_of[b].empty() || contacts_of[b].back() != k)) contacts_of[b].push_back(k);

  // W column by column: U(e_a at contact k) - U(0) for every contact sharing a body with k.
  const std::vector<Eigen::Vector3d> zero(bodies, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> dv = zero, dw = zero;
  std::vector<std::size_t> stamp(kept.size(), std::numeric_limits<std::size_t>::max());
  std::vector<std::size_t> near;
  out.column_start.push_back(0);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const std::size_t c = kept[k];
    const std::size_t touched[2] = {std::size_t(problem.body_i[c]), body_j(c)};
    near.clear();
    for (const std::size_t b : touched)
      for (const std::size_t other : contacts_of[b])
        if (stamp[other] != k) {
          stamp[other] = k;
          near.push_back(other);
        }
    std::sort(near.begin(), near.end());
    for (int a = 0; a < d; ++a) {
      mechanics::apply_impulse(problem, c, Eigen::Vector3d(Eigen::Vector3d::Unit(a)), dv, dw);
      for (const std::size_t other : near) {
        const std::size_t e = kept[other];
        Eigen::Vector3d u = mechanics::local_velocity<Eigen::Vector3d>(problem, e, dv, dw);
        u[0] -= problem.bias[e];
        // A compliant contact's own normal column: W_nn + compliance (ContactProblem.h).
        if (problem.compliant && e == c && a == 0) u[0] += problem.compliance[c];
        for (int b = 0; b < d; ++b)
          if (u[b] != 0.0) {
            out.row.push_back(int(other) * d + b);
            out.value.push_back(u[b]);
          }
      }
      out.column_start.push_back(int(out.row.size()));
      for (const std::size_t b : touched) dv[b] = dw[b] = Eigen::Vector3d::Zero();
    }
  }

  // q = U(0) with the free velocities; u = U(r) with the velocities the reactions give.
  std::vector<Eigen::Vector3d> v, w;
  problem.velocities_from_reactions(reactions, v, w);
  for (const std::size_t c : kept) {
    const Eigen::Vector3d q =
        mechanics::local_velocity<Eigen::Vector3d>(problem, c, problem.free_velocity, problem.free_angular_velocity);
    Eigen::Vector3d u = mechanics::local_velocity<Eigen::Vector3d>(problem, c, v, w);
    if (problem.compliant) u[0] += problem.compliance[c] * reactions[c][0];
    for (int a = 0; a < d; ++a) {
      out.q.push_back(q[a]);
      out.r.push_back(reactions[c][a]);
      out.u.push_back(u[a]);
    }
    out.mu.push_back(problem.mu[c]);
    out.body_i.push_back(problem.body_i[c]);
    out.body_j.push_back(problem.body_j[c]);
    out.normal.push_back(array_of(problem.normal[c]));
    out.tangent1.push_back(array_of(problem.tangent1[c]));
    out.tangent2.push_back(array_of(problem.tangent2[c]));
  }
  return out;
}

int run_contact_problem_command(const Scene& scene, const ContactProblemOptions& options,
                                std::ostream& out, std::ostream& log) {
  try {
    const std::int64_t wanted = parse_step(options.step);
    if (wanted < 0)
      throw CommandError{"--step must be a step number >= 1 or \"last\" (got \"" + options.step + "\")",
                         kExitInvalid};
    check_scene(scene);
    check_output(options, scene.source);

    auto nscd = make_nscd_integrator(scene, make_particle_set(scene));
    const StepOutcome outcome = run_to_step(*nscd, scene, wanted);
    const ContactProblem& problem = nscd->problem();
    FclibLocalProblem local = fclib_local_problem(problem, nscd->reactions());
    if (local.contacts == 0) {
      std::ostringstream msg;
      msg << "step " << outcome.step << " (t = " << outcome.time_s
          << " s) has no contact: no pair of bodies is close enough to touch within the step"
          << (local.omitted_contacts > 0 ? " (only pairs of immobile bodies)" : "")
          << "; choose a later step";
      throw CommandError{msg.str(), kExitInvalid};
    }
    // The problem's own step: a step taken in halves (periodic scenes) wrote its last part's.
    const double h = outcome.report.time_step_s;
    const auto& particles = nscd->particles();
    Eigen::Vector3d weight = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (!particles.fixed[i]) weight += particles.mass[i] * nscd->gravity();
    local.gravity_impulse = array_of(h * weight);
    local.time_step_s = h;
    local.step = outcome.step;
    local.solver_tolerance = outcome.report.tolerance;
    local.solver_residual = outcome.report.residual;
    local.siconos_residual = outcome.report.siconos_residual;
    local.solver_iterations = outcome.report.sweeps;
    local.solver_seconds = outcome.report.solve_s;
    std::size_t active = 0;
    for (std::size_t k = 0; k < local.contacts; ++k) active += local.r[k * local.spacedim] > 0.0;
    std::ostringstream text;
    text << "tmdem " << TMDEM_VERSION << ", scene " << scene.source << ", mechanical step "
         << outcome.step << " (t = " << outcome.time_s << " s, h = " << h << " s), "
         << scene.dimension << "D";
    local.title = "tmdem contact problem: " + scene.source + ", step " + std::to_string(outcome.step);
    local.description =
        text.str() + ". Local Coulomb friction problem of one NSCD step (Moreau-Jean, theta " +
        std::to_string(scene.mechanics.theta) + "): W = H^T M^-1 H in 1/kg, q the local free "
        "velocity with the position (Signorini) bias in m/s, r impulses in N s; contacts are the "
        "step's candidate pairs (spheres, walls) in frames (n, t1[, t2]). Solution and guess: "
        "tmdem's reactions (solver " + scene.mechanics.solver + ").";
    local.math_info = "W symmetric positive semi-definite; reactions unique only where the "
                      "contact graph is not hyperstatic";
    write_fclib_local_problem(local, options.output_path);
    out << "wrote " << options.output_path << ": step " << outcome.step << " (t = "
        << outcome.time_s << " s), " << local.contacts << " contacts (" << active
        << " with a reaction" << (local.omitted_contacts > 0
                                      ? ", " + std::to_string(local.omitted_contacts) +
                                            " between immobile bodies left out"
                                      : std::string())
        << "), spacedim " << local.spacedim << ", W with " << local.value.size()
        << " non-zeros; tmdem's solve: " << outcome.report.sweeps << " sweeps, residual "
        << outcome.report.residual << " (tolerance " << outcome.report.tolerance << ")\n";
    if (!outcome.report.converged)
      log << "warning: tmdem's contact solver did not converge at this step; the written "
             "solution is its last iterate\n";
    return kExitOk;
  } catch (const CommandError& e) {
    log << "error: " << e.message << "\n";
    return e.code;
  }
}

}  // namespace tmdem::coupling

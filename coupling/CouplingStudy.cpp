#include "coupling/CouplingStudy.h"

#include <algorithm>
#include <cmath>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

#include "coupling/CoupledRun.h"

namespace tmdem::coupling {

namespace {

struct Variant {
  std::string strategy;    // continue | restart | explicit
  std::string integrator;  // cvode | explicit
  double parameter;        // rtol, or the explicit step (s)
};

struct Row {
  Variant v;
  RunOutcome outcome;
  double max_error_K = 0.0;
};

RunOutcome run_variant(const Scene& base, const Variant& v, const std::string& dir, std::ostream& log) {
  Scene s = base;
  s.thermal.integrator = v.integrator;
  s.thermal.linear_solver = "klu";
  if (v.integrator == "explicit") {
    s.thermal.explicit_step_s = v.parameter;
  } else {
    s.thermal.coupling = v.strategy;
    s.thermal.relative_tolerance = v.parameter;
    s.thermal.absolute_tolerance_K = v.parameter;
  }
  RunOptions o;
  o.output_path = dir + "/" + v.strategy + ".h5";
  o.quiet = true;
  return run_scene(s, o, log);
}

}  // namespace

int run_coupling_study(const Scene& scene, const std::string& csv_path, std::ostream& out,
                       std::ostream& log) {
  if (scene.effects.mechanics != MechanicsMode::Dynamic) {
    log << "error: tmdem study coupling needs a scene with effects.mechanics = \"dynamic\"\n";
    return 2;
  }
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tmdem_coupling_study_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const double h = scene.mechanics.time_step_s;
  out << "coupling study: " << scene.source << ", " << scene.particles.size()
      << " particles, " << scene.duration_s << " s at mechanical step " << h << " s\n";

  Scene ref_scene = scene;
  ref_scene.thermal.coupling = "restart";
  auto ref = run_variant(ref_scene, {"restart", "cvode", 1e-12}, dir.string(), log);
  if (ref.exit_code != 0) {
    log << "error: the reference run failed: " << ref.summary.message << "\n";
    return 3;
  }
  out << "reference: cvode/klu restarted every mechanical step, rtol = atol = 1e-12 ("
      << ref.summary.thermal.steps << " thermal steps, " << ref.summary.thermal.wall_time_s
      << " s thermal wall time)\n";

  const std::vector<Variant> variants{{"continue", "cvode", 1e-4}, {"continue", "cvode", 1e-6},
                                      {"continue", "cvode", 1e-8}, {"restart", "cvode", 1e-4},
                                      {"restart", "cvode", 1e-6},  {"restart", "cvode", 1e-8},
                                      {"explicit", "explicit", h}};
  std::vector<Row> rows;
  for (const auto& v : variants) {
    Row row{v, run_variant(scene, v, dir.string(), log)};
    if (row.outcome.exit_code != 0) {
      log << "warning: " << v.strategy << " (" << v.parameter << ") failed: "
          << row.outcome.summary.message << "\n";
      continue;
    }
    for (std::size_t i = 0; i < ref.final_temperature_K.size(); ++i)
      row.max_error_K = std::max(row.max_error_K,
                                 std::abs(row.outcome.final_temperature_K[i] - ref.final_temperature_K[i]));
    rows.push_back(std::move(row));
  }
  std::filesystem::remove_all(dir);

  std::ostringstream csv;
  csv << "strategy,integrator,parameter,max_error_K,wall_time_s,thermal_wall_time_s,thermal_steps,"
         "reinitializations\n";
  out << std::left << std::setw(10) << "strategy" << std::setw(10) << "integ" << std::setw(11)
      << "parameter" << std::setw(13) << "max_error_K" << std::setw(12) << "thermal_s"
      << std::setw(10) << "steps" << "reinits\n";
  for (const auto& r : rows) {
    const auto& t = r.outcome.summary.thermal;
    csv << r.v.strategy << "," << r.v.integrator << "," << r.v.parameter << "," << r.max_error_K
        << "," << r.outcome.summary.wall_time_s << "," << t.wall_time_s << "," << t.steps << ","
        << t.reinitializations << "\n";
    out << std::left << std::setw(10) << r.v.strategy << std::setw(10) << r.v.integrator
        << std::setw(11) << r.v.parameter << std::setw(13) << r.max_error_K << std::setw(12)
        << t.wall_time_s << std::setw(10) << t.steps << t.reinitializations << "\n";
  }
  if (!csv_path.empty()) {
    std::ofstream f(csv_path);
    f << csv.str();
    if (!f) {
      log << "error: cannot write " << csv_path << "\n";
      return 4;
    }
  }
  return 0;
}

}  // namespace tmdem::coupling

#include "coupling/studies/ConductivityStudy.h"

#include "coupling/common/ShortestNumber.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneError.h"
#include "coupling/studies/ZehnerSchlunderBauer.h"
#include "mechanics/model/PairIndex.h"
#include "thermal/modes/GasGapConductance.h"
#include "thermal/modes/ModeRegistry.h"
#include "thermal/steady/SteadyStateSolver.h"
#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::coupling {
namespace {

Eigen::Vector3d vec(const Vec3& v) { return {v[0], v[1], v[2]}; }

// Which wall each of the network's wall edges belongs to. The study's only isothermal walls are
// the hot and the cold one, at different constant temperatures, so an edge's wall temperature
// names its wall; near pairs (gas across a gap) add wall edges that are not contacts.
std::vector<std::size_t> wall_of_wall_edge(const thermal::ThermalNetwork& net, double T_hot_K,
                                           std::size_t hot, std::size_t cold) {
  std::vector<std::size_t> wall;
  for (std::size_t e = 0; e < net.wall_edge_count(); ++e)
    wall.push_back(net.wall_temperature_K[e] == T_hot_K ? hot : cold);
  return wall;
}

// The network with only the wall edges of `keep` (npos: none).
thermal::ThermalNetwork with_wall_edges_of(const thermal::ThermalNetwork& net,
                                           const std::vector<std::size_t>& edge_wall,
                                           std::size_t keep) {
  thermal::ThermalNetwork out = net;
  out.clear_wall_edges();
  for (std::size_t w = 0; w < net.wall_edge_count(); ++w)
    if (edge_wall[w] == keep) {
      out.add_wall_edge(net.wall_node[w], net.wall_temperature_K[w], net.wall_conductance_W_per_K[w],
                        net.wall_schedule[w], net.wall_gap_m[w], net.wall_contact_radius_m[w],
                        net.wall_in_contact[w] != 0);
      // The kept edge keeps the full network's series factor (the particle's own resistance),
      // so the filtered flows add up to the system's.
      if (!net.wall_series_factor.empty()) out.wall_series_factor.push_back(net.wall_series_factor[w]);
      if (!net.wall_emissivity.empty()) out.wall_emissivity.push_back(net.wall_emissivity[w]);
    }
  return out;
}

double mode_heat_sum(const thermal::HeatTransferMode& mode, const thermal::ThermalNetwork& net,
                     const std::vector<double>& T, std::vector<double>& q) {
  std::fill(q.begin(), q.end(), 0.0);
  double boundary_W = 0.0;
  if (!mode.add_heat_flow(net, T, q, boundary_W))
    throw thermal::ThermalSolverError("conductivity study: mode " + std::string(mode.name()) +
                                      " refused the steady temperatures");
  double sum = 0.0;
  for (double v : q) sum += v;
  return sum;
}

// Cross-section normal to `axis`: a period along a periodic direction, side walls where the
// scene has them, else the particles' extent.
double cross_section_m2(const Scene& scene, const std::vector<Vec3>& positions,
                        const Eigen::Vector3d& axis, std::size_t hot, std::size_t cold) {
  // A column: a cylinder along the axis bounds the whole cross-section.
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    const auto& c = scene.walls[w];
    if (c.cylinder && std::abs(vec(c.normal).dot(axis)) > 1.0 - 1e-9)
      return std::numbers::pi * c.radius_m * c.radius_m;
  }
  Eigen::Vector3d e1 = Eigen::Vector3d::Zero();
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    if (w == hot || w == cold || scene.walls[w].cylinder) continue;
    const auto n = vec(scene.walls[w].normal);
    if (std::abs(n.dot(axis)) < 1e-9) {
      e1 = n.normalized();
      break;
    }
  }
  if (e1.isZero()) {
    Eigen::Index k = 0;
    axis.cwiseAbs().minCoeff(&k);
    e1 = Eigen::Vector3d::Unit(k);
    e1 = (e1 - e1.dot(axis) * axis).normalized();
  }
  const Eigen::Vector3d e2 = axis.cross(e1).normalized();
  double area = 1.0;
  for (const auto& e : {e1, e2}) {
    // A periodic direction has no sides: the bed repeats, and one period is its width.
    Eigen::Index along = 0;
    if (e.cwiseAbs().maxCoeff(&along) > 1.0 - 1e-9 && scene.periodic.axis[std::size_t(along)]) {
      area *= scene.periodic.length_m(int(along));
      continue;
    }
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const double x = vec(positions[i]).dot(e), r = scene.particles[i].radius_m;
      lo = std::min(lo, x - r);
      hi = std::max(hi, x + r);
    }
    double wall_lo = -INFINITY, wall_hi = INFINITY;
    for (std::size_t w = 0; w < scene.walls.size(); ++w) {
      if (w == hot || w == cold || scene.walls[w].cylinder) continue;
      const double c = vec(scene.walls[w].normal).dot(e), p = vec(scene.walls[w].point_m).dot(e);
      if (c > 1.0 - 1e-9) wall_lo = std::max(wall_lo, p);
      if (c < -1.0 + 1e-9) wall_hi = std::min(wall_hi, p);
    }
    if (std::isfinite(wall_lo)) lo = wall_lo;
    if (std::isfinite(wall_hi)) hi = wall_hi;
    area *= hi - lo;
  }
  return area;
}

}  // namespace

std::pair<std::size_t, std::size_t> conductivity_walls(const Scene& scene) {
  std::vector<std::size_t> iso;
  for (std::size_t w = 0; w < scene.walls.size(); ++w)
    if (scene.walls[w].temperature_K) iso.push_back(w);
  if (iso.size() != 2) {
    std::ostringstream msg;
    msg << "study conductivity needs exactly two walls with a temperature (the hot and the cold "
           "side; all other walls adiabatic), the scene has " << iso.size();
    if (!iso.empty()) {
      msg << ":";
      for (auto w : iso) msg << " wall[" << w << "]";
    }
    throw SceneError(msg.str());
  }
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    if (!scene.walls[w].temperature_table.empty())
      throw SceneError("study conductivity: wall[" + std::to_string(w) +
                       "].temperature is a table; the steady state needs constant temperatures");
    if (scene.walls[w].heat_flux_W_per_m2)
      throw SceneError("study conductivity: wall[" + std::to_string(w) +
                       "] has a heat_flux; every wall but the hot and the cold one must be "
                       "adiabatic");
  }
  for (auto w : iso)
    if (scene.walls[w].cylinder)
      throw SceneError("study conductivity: wall[" + std::to_string(w) +
                       "] is a cylinder; the hot and the cold wall must be planes");
  const auto& a = scene.walls[iso[0]];
  const auto& b = scene.walls[iso[1]];
  if (vec(a.normal).normalized().dot(vec(b.normal).normalized()) > -1.0 + 1e-9)
    throw SceneError("study conductivity: wall[" + std::to_string(iso[0]) + "] and wall[" +
                     std::to_string(iso[1]) + "] must face each other (opposite normals)");
  if (*a.temperature_K == *b.temperature_K)
    throw SceneError("study conductivity: wall[" + std::to_string(iso[0]) + "].temperature and wall[" +
                     std::to_string(iso[1]) + "].temperature are equal; no heat would flow");
  return *a.temperature_K > *b.temperature_K ? std::pair(iso[0], iso[1]) : std::pair(iso[1], iso[0]);
}

namespace {

// k_eff and the rest from a frozen problem; `scene` has the walls where the problem has them.
// ZSB beside k_eff (docs/validation.md) for a bed in a gas of one solid with a constant
// conductivity: at the study's porosity, the particles' mean diameter, the gas mode's
// conductivity and jump length, and the VDI's flattening coefficient for spheres.
// The particles' mean diameter, m (0 without particles).
double mean_diameter_m(const Scene& scene) {
  if (scene.particles.empty()) return 0.0;
  double sum_m = 0.0;
  for (const auto& p : scene.particles) sum_m += 2.0 * p.radius_m;
  return sum_m / double(scene.particles.size());
}

std::optional<double> zehner_schlunder_bauer_of(const Scene& scene, const ConductivityResult& r,
                                                double porosity) {
  const bool gas = std::any_of(r.modes.begin(), r.modes.end(),
                               [](const ModeShare& m) { return m.mode == "gas_conduction"; });
  if (!gas || scene.particles.empty() || !(porosity > 0.0 && porosity < 1.0)) return std::nullopt;
  const int material = scene.particles.front().material;
  for (const auto& p : scene.particles)
    if (p.material != material) return std::nullopt;
  const Material& solid = scene.materials[std::size_t(material)];
  if (solid.temperature_dependent()) return std::nullopt;
  const auto* mode = thermal::find_heat_transfer_mode("gas_conduction");
  if (mode == nullptr) return std::nullopt;
  const thermal::ModeParameters fluid = thermal::resolve_mode_parameters(*mode, scene.heat_modes);
  ZehnerSchlunderBauerInput in;
  in.porosity = porosity;
  in.k_solid_W_per_mK = solid.conductivity_W_per_mK;
  in.k_fluid_W_per_mK = fluid["conductivity"];
  in.diameter_m = mean_diameter_m(scene);
  in.flattening = 0.0077;
  in.jump_length_m =
      thermal::gas_jump_length_m(fluid["pressure"], fluid["mean_free_path"], fluid["accommodation"]);
  return zehner_schlunder_bauer(in).k_eff_W_per_mK;
}

// Volume of the sphere (centre c, radius rho) between the planes s = a and s = b, m^3:
// pi * integral of (rho^2 - (s - c)^2) ds over the part of [a, b] the sphere spans.
double sphere_volume_in_slab_m3(double c, double rho, double a, double b) {
  const double lo = std::max(a, c - rho) - c, hi = std::min(b, c + rho) - c;
  if (!(hi > lo)) return 0.0;
  const auto primitive = [rho](double u) { return rho * rho * u - u * u * u / 3.0; };
  return std::numbers::pi * (primitive(hi) - primitive(lo));
}

// ConductivityResult's bulk figures from the steady temperatures; x: each particle's distance
// from the hot wall along the axis, m.
void measure_bulk(const Scene& scene, const std::vector<double>& x,
                  const std::vector<std::uint8_t>& floating, ConductivityResult& r) {
  const std::size_t n = scene.particles.size();
  if (n == 0) return;
  r.bulk_margin_m = 2.0 * mean_diameter_m(scene);
  const double a = r.bulk_margin_m, b = r.length_m - r.bulk_margin_m;
  if (!(b > a)) return;
  double solid_m3 = 0.0, sx = 0.0, sT = 0.0, sxx = 0.0, sxT = 0.0;
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i) {
    solid_m3 += sphere_volume_in_slab_m3(x[i], scene.particles[i].radius_m, a, b);
    if (!(x[i] > a && x[i] < b) || (i < floating.size() && floating[i])) continue;
    ++m;
    sx += x[i];
    sT += r.T_K[i];
  }
  r.bulk_particles = m;
  if (m < 20) return;
  const double x_mean = sx / double(m), T_mean = sT / double(m);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(x[i] > a && x[i] < b) || (i < floating.size() && floating[i])) continue;
    sxx += (x[i] - x_mean) * (x[i] - x_mean);
    sxT += (x[i] - x_mean) * (r.T_K[i] - T_mean);
  }
  const double slope_K_per_m = sxT / sxx;
  if (!(slope_K_per_m < 0.0)) return;  // no gradient from hot to cold: nothing to measure
  r.porosity_bulk = 1.0 - solid_m3 / (r.area_m2 * (b - a));
  r.k_bulk_W_per_mK = r.heat_hot_W / r.area_m2 / -slope_K_per_m;
  r.zsb_bulk_W_per_mK = zehner_schlunder_bauer_of(scene, r, *r.porosity_bulk);
}

ConductivityResult measure_conductivity(const Scene& scene, const FrozenThermalProblem& problem,
                                        std::size_t hot_wall, std::size_t cold_wall) {
  ConductivityResult r;
  r.hot_wall = hot_wall;
  r.cold_wall = cold_wall;
  const auto& hot = scene.walls[r.hot_wall];
  const auto& cold = scene.walls[r.cold_wall];
  r.T_hot_K = *hot.temperature_K;
  r.T_cold_K = *cold.temperature_K;
  const Eigen::Vector3d axis = vec(hot.normal).normalized();
  r.length_m = (vec(cold.point_m) - vec(hot.point_m)).dot(axis);
  if (!(r.length_m > 0.0))
    throw SceneError("study conductivity: the cold wall[" + std::to_string(r.cold_wall) +
                     "] is not on the inner side of the hot wall[" + std::to_string(r.hot_wall) +
                     "] (distance " + std::to_string(r.length_m) + " m)");
  if (problem.settle) r.at_rest = problem.settle->at_rest;

  const auto& system = *problem.system;
  // thermal.linear_solver = "amg" solves the steady state with multigrid CG; klu and pcg with KLU.
  // "auto" that resolves to conjugate gradients (a large symmetric bed) takes amg's: the steady
  // solver has no IC(0) variant, and KLU's fill on a large 3D bed is what "auto" avoids.
  thermal::SteadyStateOptions steady_options;
  const auto choice = choose_linear_solver(scene, system, 1);
  if (choice.kind == thermal::LinearSolverKind::Amg ||
      (choice.automatic && thermal::is_conjugate_gradients(choice.kind)))
    steady_options.linear_solver = thermal::LinearSolverKind::Amg;
  const auto steady = thermal::solve_steady_state(system, problem.T0_K, steady_options);
  r.T_K = steady.T_K;
  r.newton_iterations = steady.newton_iterations;
  r.factorizations = steady.factorizations;
  r.linear_solver = steady_options.linear_solver;
  r.cg_iterations = steady.cg_iterations;
  r.max_residual_W = steady.max_residual_W;
  r.floating_particles = steady.floating_particles;

  // Geometry of the frozen packing.
  const std::size_t n = scene.particles.size();
  r.particles = n;
  r.area_m2 = cross_section_m2(scene, problem.positions_m, axis, r.hot_wall, r.cold_wall);
  for (int a = 0; a < 3; ++a)
    if (scene.periodic.axis[std::size_t(a)])
      r.periodic_axes += std::string(r.periodic_axes.empty() ? "" : ", ") + "xyz"[a];
  double solid_m3 = 0.0;
  for (const auto& p : scene.particles) solid_m3 += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius_m, 3);
  r.porosity = 1.0 - solid_m3 / (r.area_m2 * r.length_m);
  const bool geometric = scene.effects.mechanics == MechanicsMode::Off;
  for (std::size_t c = 0; c < problem.contacts.size(); ++c) {
    if (!geometric && !(problem.contacts.normal_force_N[c] > 0.0)) continue;
    const auto j = problem.contacts.pair[2 * c + 1];
    if (mechanics::is_wall(j)) {
      ++r.wall_contacts;
      r.hot_wall_contacts += mechanics::wall_index(j) == r.hot_wall;
      r.cold_wall_contacts += mechanics::wall_index(j) == r.cold_wall;
    }
    else ++r.contacts;
  }
  r.coordination = n > 0 ? 2.0 * double(r.contacts) / double(n) : 0.0;

  // Heat per mode through each wall and across the bed.
  const auto& net = system.network();
  const auto edge_wall = wall_of_wall_edge(net, r.T_hot_K, r.hot_wall, r.cold_wall);
  const auto no_walls = with_wall_edges_of(net, edge_wall, SIZE_MAX);
  const auto hot_only = with_wall_edges_of(net, edge_wall, r.hot_wall);
  const auto cold_only = with_wall_edges_of(net, edge_wall, r.cold_wall);
  std::vector<double> x(n), q(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = (vec(problem.positions_m[i]) - vec(hot.point_m)).dot(axis);
  std::vector<double> transport_Wm;
  for (const auto& mode : system.modes()) {
    ModeShare s;
    s.mode = std::string(mode->name());
    const double interior = mode_heat_sum(*mode, no_walls, r.T_K, q);
    s.hot_wall_W = mode_heat_sum(*mode, hot_only, r.T_K, q) - interior;
    s.cold_wall_W = -(mode_heat_sum(*mode, cold_only, r.T_K, q) - interior);
    mode_heat_sum(*mode, net, r.T_K, q);
    double t = r.length_m * s.cold_wall_W;
    for (std::size_t i = 0; i < n; ++i) t += q[i] * x[i];
    transport_Wm.push_back(t);
    r.heat_hot_W += s.hot_wall_W;
    r.heat_cold_W += s.cold_wall_W;
    r.modes.push_back(s);
  }
  for (std::size_t m = 0; m < r.modes.size(); ++m)
    r.modes[m].share = r.heat_cold_W != 0.0 ? transport_Wm[m] / (r.length_m * r.heat_cold_W) : 0.0;
  r.balance_rel = r.heat_hot_W != 0.0 ? std::abs(r.heat_hot_W - r.heat_cold_W) / std::abs(r.heat_hot_W) : 0.0;
  r.k_eff_W_per_mK = r.heat_hot_W * r.length_m / (r.area_m2 * (r.T_hot_K - r.T_cold_K));
  r.zsb_W_per_mK = zehner_schlunder_bauer_of(scene, r, r.porosity);
  measure_bulk(scene, x, steady.floating, r);
  return r;
}

// The scene's walls moved to where the problem has them.
Scene with_walls_of(const Scene& scene, const FrozenThermalProblem& problem) {
  Scene moved = scene;
  for (std::size_t w = 0; w < moved.walls.size() && w < problem.wall_points_m.size(); ++w)
    moved.walls[w].point_m = problem.wall_points_m[w];
  return moved;
}

// The one piston of a --pressures study (SceneError otherwise).
std::size_t study_piston(const Scene& scene) {
  std::vector<std::size_t> pistons;
  for (std::size_t w = 0; w < scene.walls.size(); ++w)
    if (scene.walls[w].piston) pistons.push_back(w);
  if (pistons.size() != 1)
    throw SceneError("study conductivity --pressures needs exactly one wall with piston = true "
                     "(it loads the bed), the scene has " + std::to_string(pistons.size()));
  if (scene.effects.mechanics == MechanicsMode::Off)
    throw SceneError("study conductivity --pressures needs effects.mechanics = \"settle\" (the "
                     "piston loads the bed through the contact mechanics), the scene has \"off\"");
  return pistons[0];
}

}  // namespace

ConductivityResult run_conductivity_study(const Scene& input, ProgressReporter& progress,
                                          MechanicsStepLog* step_log) {
  const auto [hot, cold] = conductivity_walls(input);
  Scene scene = input;
  if (scene.effects.mechanics == MechanicsMode::Dynamic || scene.effects.mechanics == MechanicsMode::Coupled)
    scene.effects.mechanics = MechanicsMode::Settle;
  const auto problem = build_frozen_thermal_problem(scene, progress, step_log);
  auto r = measure_conductivity(with_walls_of(scene, problem), problem, hot, cold);
  const auto& piston = std::find_if(scene.walls.begin(), scene.walls.end(), [](const Wall& w) { return w.piston; });
  if (piston != scene.walls.end() && piston->piston_pressure_Pa && scene.effects.mechanics != MechanicsMode::Off)
    r.pressure_Pa = piston->piston_pressure_Pa;
  return r;
}

double piston_area_m2(const Scene& scene) {
  const std::size_t w = study_piston(scene);
  if (scene.walls[w].piston_area_m2 > 0.0) return scene.walls[w].piston_area_m2;
  const auto [hot, cold] = conductivity_walls(scene);
  std::vector<Vec3> positions;
  for (const auto& p : scene.particles) positions.push_back(p.position_m);
  return cross_section_m2(scene, positions, vec(scene.walls[hot].normal).normalized(), hot, cold);
}

std::vector<ConductivityResult> run_conductivity_pressure_study(
    const Scene& input, const std::vector<double>& pressures_Pa, ProgressReporter& progress,
    const std::function<bool()>& stop, MechanicsStepLog* step_log) {
  const auto [hot, cold] = conductivity_walls(input);
  Scene scene = input;
  if (scene.effects.mechanics == MechanicsMode::Dynamic || scene.effects.mechanics == MechanicsMode::Coupled)
    scene.effects.mechanics = MechanicsMode::Settle;
  const std::size_t piston = study_piston(scene);
  const double area = piston_area_m2(scene);
  for (double p : pressures_Pa)
    if (!(p >= 0.0) || !std::isfinite(p))
      throw SceneError("study conductivity --pressures: every pressure must be a finite number "
                       ">= 0 Pa (got " + std::to_string(p) + ")");
  auto nscd = make_nscd_integrator(scene, make_particle_set(scene));
  if (step_log) step_log->attach(*nscd);
  std::vector<ConductivityResult> results;
  for (double p : pressures_Pa) {
    // Each load re-settles the bed left by the previous one (the piston keeps its place and
    // the contacts their forces as the warm start).
    nscd->set_piston_load(piston, p * area);
    FrozenThermalProblem problem;
    if (step_log) step_log->begin_phase("settle at " + shortest_number(p) + " Pa", 0.0);
    problem.settle = settle_packing(*nscd, scene, progress, stop);
    if (problem.settle->ended_by == "interrupted") break;  // this load's packing is not settled
    freeze_packing(scene, *nscd, problem);
    auto r = measure_conductivity(with_walls_of(scene, problem), problem, hot, cold);
    r.pressure_Pa = p;
    results.push_back(std::move(r));
    if (stop && stop()) break;
  }
  return results;
}

}  // namespace tmdem::coupling

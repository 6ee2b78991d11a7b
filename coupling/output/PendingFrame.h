#pragma once
// A frame the result writer has accepted but not yet put into the .h5: an owning copy of a
// FrameView. Frames reach the .h5 in batches, each followed by the XDMF rewrite, so that the
// two files always describe the same frames (ResultWriter.h).
#include <cstdint>
#include <vector>

#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling {

struct PendingFrame {
  double time_s = 0.0;
  double thermal_energy_J = 0.0;
  double boundary_heat_J = 0.0;
  std::vector<double> position_m, velocity_m_per_s, temperature_K;
  std::vector<std::int64_t> contact_pair;
  std::vector<double> normal_force_N, conductance_W_per_K, tangential_force_N, heat_flow_W;
  std::vector<double> wall_point_m;

  static PendingFrame copy_of(const FrameView& f) {
    PendingFrame p;
    p.time_s = f.time_s;
    p.thermal_energy_J = f.thermal_energy_J;
    p.boundary_heat_J = f.boundary_heat_J;
    p.position_m.assign(f.position_m.begin(), f.position_m.end());
    p.velocity_m_per_s.assign(f.velocity_m_per_s.begin(), f.velocity_m_per_s.end());
    p.temperature_K.assign(f.temperature_K.begin(), f.temperature_K.end());
    p.contact_pair.assign(f.contact_pair.begin(), f.contact_pair.end());
    p.normal_force_N.assign(f.normal_force_N.begin(), f.normal_force_N.end());
    p.conductance_W_per_K.assign(f.conductance_W_per_K.begin(), f.conductance_W_per_K.end());
    p.tangential_force_N.assign(f.tangential_force_N.begin(), f.tangential_force_N.end());
    p.heat_flow_W.assign(f.heat_flow_W.begin(), f.heat_flow_W.end());
    p.wall_point_m.assign(f.wall_point_m.begin(), f.wall_point_m.end());
    return p;
  }

  FrameView view() const {
    FrameView f;
    f.time_s = time_s;
    f.thermal_energy_J = thermal_energy_J;
    f.boundary_heat_J = boundary_heat_J;
    f.position_m = position_m;
    f.velocity_m_per_s = velocity_m_per_s;
    f.temperature_K = temperature_K;
    f.contact_pair = contact_pair;
    f.normal_force_N = normal_force_N;
    f.conductance_W_per_K = conductance_W_per_K;
    f.tangential_force_N = tangential_force_N;
    f.heat_flow_W = heat_flow_W;
    f.wall_point_m = wall_point_m;
    return f;
  }

  std::size_t bytes() const {
    return 8 * (position_m.size() + velocity_m_per_s.size() + temperature_K.size() +
                contact_pair.size() + normal_force_N.size() + conductance_W_per_K.size() +
                tangential_force_N.size() + heat_flow_W.size() + wall_point_m.size());
  }
};

}  // namespace tmdem::coupling

#pragma once
// Small networks and settings shared by both exact references' tests
// (test_accuracy_reference.cpp: dense; test_sparse_exact_reference.cpp: sparse).
#include <string>
#include <vector>

#include "thermal/modes/ModeSettings.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::coupling::testing {

// Two particles joined by one contact: the closed-form case.
inline thermal::ThermalNetwork two_node_network(double C1_J_per_K, double C2_J_per_K,
                                                double H_W_per_K) {
  thermal::ThermalNetwork net;
  net.resize_nodes(2);
  net.heat_capacity_J_per_K = {C1_J_per_K, C2_J_per_K};
  net.surface_area_m2 = {1e-5, 2e-5};
  net.add_edge(0, 1, H_W_per_K);
  return net;
}

// Every affine mode: conduction, walls, convection, sources.
inline const std::vector<std::string> kAffineModes{"contact_conduction", "wall_conduction",
                                                   "convection", "heat_source"};

inline thermal::ModeSettings convection_settings(double h_W_per_m2K, double fluid_K) {
  thermal::ModeSettings s;
  s.set("convection", "coefficient", h_W_per_m2K);
  s.set("convection", "fluid_temperature", fluid_K);
  return s;
}

}  // namespace tmdem::coupling::testing

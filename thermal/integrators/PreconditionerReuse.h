#pragma once
// When CVODES' preconditioner set-up may keep the BoomerAMG V-cycle of the last one. CVODES
// asks for a set-up at every change of gamma = h l_1 beyond 30% and every 20 steps; with "amg"
// each set-up rebuilds hypre's whole hierarchy, a quarter of the time of an hour's heating of
// 10^6 particles (docs/scale-out.md), while the V-cycle of I - gamma' J preconditions
// I - gamma J nearly as well for gamma' within a factor 2 of gamma: the conjugate gradients
// still solve the true Newton system (the matrix-free product uses the current gamma) to their
// tolerance, in a few more iterations. Measured on bench/lattice_1e6.toml: 8 of 18 set-ups kept,
// the same 106 steps and right-hand sides, 12% less CPU, final temperatures within 6e-8 K.
// The V-cycle is rebuilt whenever CVODES wants new Jacobian data (jok false: the first step,
// every 51 steps, after a convergence failure) and after any change of the network.
#include <cstdint>

namespace tmdem::thermal {

class PreconditionerReuse {
 public:
  static constexpr double kGammaRatio = 2.0;

  // enabled: "amg" (IC(0)'s set-up is cheap, and pcg's runs keep their bits).
  explicit PreconditionerReuse(bool enabled) : enabled_(enabled) {}

  bool may_keep(bool jacobian_ok, double gamma, std::uint64_t network_version) const {
    return enabled_ && jacobian_ok && gamma_ > 0.0 && network_version == network_version_ &&
           gamma < gamma_ * kGammaRatio && gamma * kGammaRatio > gamma_;
  }
  // After a set-up for gamma of the network at network_version (ThermalSystem::values_version,
  // which every change of the edges advances); ok false: it broke down, nothing to keep.
  void factored(bool ok, double gamma, std::uint64_t network_version) {
    gamma_ = ok ? gamma : 0.0;
    network_version_ = network_version;
  }

 private:
  bool enabled_;
  double gamma_ = 0.0;  // 0: nothing kept
  std::uint64_t network_version_ = 0;
};

}  // namespace tmdem::thermal

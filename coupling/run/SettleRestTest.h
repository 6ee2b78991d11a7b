#pragma once
// When a settling packing is at rest for heating (mechanics.rest_test = "network"): the heat
// sees the contact network and its normal forces, so settling ends when they have stopped
// changing, not when the last rattler or free roller has. Over the last `window` steps the
// normal forces changed by less than `force_change` relative to their sum (a contact that
// opened or closed counts with its whole force), and the load-carrying particles move slower
// than `speed` in the mass-weighted mean sense: sqrt(2 KE / M) < speed.
//
// A particle carries load when something presses it along gravity: the contact forces on it
// (normal and tangential) have components along g adding up to at least half its weight, so it
// passes on the weight of what rests on it. The particles of the free surface carry only their
// own weight: one of them rolling down the surface changes nobody's load, and it neither holds
// the test up nor has to stop (a single steel sphere rolling at 0.1 m/s on a 10^4 bed made
// sqrt(2 KE / M) 1.6e-3 m/s, and held a deposited 10^4 bed up for 250 steps). Where nothing is
// pressed (a single layer, no gravity) a particle carries load when its contacts' normal forces
// add up to at least half its weight. Particles without such contacts are rattlers, or on their
// way down a pore grazing a neighbour: counted as rattlers, never waited for. A packing in which
// no contact carries force (no gravity, no load) is at rest when every particle is slower than
// `speed`.
//
// Its only state from step to step is the window of snapshots: a settle checkpoint carries it
// (SettleProgress.h), so that a resumed settle ends at the step the uninterrupted one would.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mechanics/contact/ContactForce.h"
#include "mechanics/model/ParticleSet.h"

namespace tmdem::coupling {

struct SettleRestTestSettings {
  int window_steps = 5;        // forces compared with those this many steps before
  Eigen::Vector3d gravity_m_s2{0.0, -9.81, 0.0};  // for a particle's weight and what presses it
  double force_change = 1e-2;  // largest sum |F_now - F_before| / sum F_now
  double speed_m_s = 1e-4;     // largest sqrt(2 KE / M) of the load-carrying particles
};

class SettleRestTest {
 public:
  using Pair = std::pair<std::int64_t, std::int64_t>;
  // One step's contacts (strictly increasing pairs) and their normal forces, N.
  struct Snapshot {
    std::vector<Pair> pair;
    std::vector<double> normal_force_N;
  };

  explicit SettleRestTest(SettleRestTestSettings settings);

  // After each settle step, with the step's contacts (NscdIntegrator::contacts(): strictly
  // increasing (i, j)) and the particles: true when the packing is at rest.
  bool after_step(const std::vector<mechanics::ContactForce>& contacts,
                  const mechanics::ParticleSet& particles);

  // Of the last step: the relative force change over the window (infinity until the window is
  // full), the load carriers' mean speed (m/s), the load carriers, and the moving particles with
  // no contact that carries force.
  double force_change() const { return force_change_; }
  double load_speed_m_s() const { return load_speed_m_s_; }
  std::int64_t load_carriers() const { return load_carriers_; }
  std::int64_t rattlers() const { return rattlers_; }

  // The last window + 1 steps' snapshots (fewer at first), oldest first, and back: a test given
  // the history of another judges the next steps as that one would. restore_history throws
  // std::invalid_argument for more snapshots than the window holds or a snapshot whose lists
  // differ in length.
  const std::deque<Snapshot>& history() const { return history_; }
  void restore_history(std::deque<Snapshot> history);

 private:
  // sum |F_a - F_b| over the union of both contact lists (sorted by pair), N.
  static double force_difference_N(const Snapshot& a, const Snapshot& b);

  SettleRestTestSettings settings_;
  std::deque<Snapshot> history_;  // the last window + 1 steps, oldest first
  std::vector<double> contact_force_N_;  // per particle: sum of its contacts' normal forces
  std::vector<double> pressed_N_;        // per particle: sum of the positive parts of F . g/|g|
  double force_change_;
  double load_speed_m_s_ = 0.0;
  std::int64_t load_carriers_ = 0;
  std::int64_t rattlers_ = 0;
};

}  // namespace tmdem::coupling

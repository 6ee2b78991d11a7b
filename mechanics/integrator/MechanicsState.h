#pragma once
// Everything NscdIntegrator::step() reads from earlier steps, so that an integrator built anew
// from the same scene and given this state continues bit for bit (restart from a checkpoint).
//
// Beyond the particles' positions and velocities (and the pistons': Wall.h) that is the candidate table (ContactDetector:
// its pairs, the positions at its last rebuild, which decide the next rebuild, and the margin
// and rebuild count) and each candidate's last reaction force, the warm start of the next solve
// (normal and tangential parts). The step's own scratch (velocities at the start of the step,
// the contact problem) is rebuilt by every step and is not part of it. contacts() stays empty
// after a restore until the next step.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "mechanics/detection/ContactDetector.h"
#include "mechanics/integrator/StepReport.h"
#include "mechanics/integrator/ToleranceSchedule.h"

namespace tmdem::mechanics {

struct MechanicsState {
  std::vector<Eigen::Vector3d> position_m;
  std::vector<Eigen::Vector3d> velocity_m_per_s;
  std::vector<Eigen::Vector3d> angular_velocity_rad_per_s;

  // Candidate table; empty reference positions: no table yet (the next step rebuilds).
  double margin_m = 0.0;
  double wall_margin_m = 0.0;  // particle-wall pairs (ContactDetector::wall_margin); 0: margin_m
  bool margin_widened_by_wall = false;  // ContactDetector::widened_by_wall
  std::int64_t rebuilds = 0;
  std::vector<Eigen::Vector3d> reference_position_m;  // per particle, at the last rebuild
  std::vector<CandidatePair> candidates;               // sorted as ContactDetector::pairs()
  std::vector<Eigen::Vector3d> candidate_force_N;      // per candidate, global frame, on i
  // Per candidate, global, on i: the rolling resistance torque (warm start); empty when no
  // material has rolling_friction (and in states saved before it existed: zeros).
  std::vector<Eigen::Vector3d> candidate_rolling_torque_Nm;
  // Per candidate: the overlap held (NscdIntegrator::hold_initial_overlaps), m; empty when none.
  std::vector<double> candidate_held_overlap_m;
  std::vector<double> solver_state;                    // ContactSolver::carried_state()

  // Walls, one entry each (pistons move; fixed walls keep the scene's values). Empty: the
  // walls as the integrator was built with (a state saved before pistons existed).
  std::vector<Eigen::Vector3d> wall_point_m;
  std::vector<double> wall_velocity_m_per_s;           // along the wall normal
  std::vector<Eigen::Vector3d> reference_wall_point_m; // at the last rebuild (ContactDetector)

  // The tolerance schedule's phase (ToleranceSchedule.h; Before when the scene has none).
  ToleranceSchedule::State tolerance_schedule;

  // The retry's budget (NscdIntegrator::step(double)): the parts a retry may go up to now (0:
  // NscdParameters::retry_parts, also in checkpoints older than it), and the steps converged in
  // a row since it was last changed.
  int retry_limit = 0;
  int retry_converged_in_a_row = 0;
  // The parts the next step starts in (NscdParameters::retry_keep_steps; 0 or 1: whole), and the
  // steps converged in a row at those parts.
  int start_parts = 0;
  int start_parts_converged_in_a_row = 0;

  MechanicsStats stats;
};

}  // namespace tmdem::mechanics

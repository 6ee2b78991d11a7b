#pragma once
// What a checkpoint carries beyond positions and temperatures so that a restart continues bit
// for bit (docs/restart-and-files.md "Restart, interruption and files"): the mechanics' own state
// (mechanics/integrator/MechanicsState.h), its counters, the thermal integrator's counters and the contact
// list with its exact forces. Converts between the run's objects and the flat CheckpointState
// of the output room, which knows neither mechanics nor thermal.
#include "coupling/bridge/ContactList.h"
#include "coupling/output/Checkpoint.h"
#include "coupling/run/SettleProgress.h"
#include "mechanics/integrator/MechanicsState.h"
#include "mechanics/integrator/StepReport.h"
#include "thermal/integrators/ThermalIntegrator.h"

namespace tmdem::coupling {

// The contact list as the result file has it (pairs, normal and tangential forces).
void store_contacts(const ContactList& contacts, double time_step_s, CheckpointState& cs);
// Back: normal forces exact when the checkpoint has them, else impulse / time step.
ContactList contacts_of(const CheckpointState& cs, double time_step_s);

// Counters as /extra scalars ("thermal_steps", "mechanics_steps", ...); absent ones read as 0.
void store_thermal_stats(const thermal::IntegratorStats& stats, CheckpointState& cs);
thermal::IntegratorStats thermal_stats_of(const CheckpointState& cs);
void store_mechanics_stats(const mechanics::MechanicsStats& stats, CheckpointState& cs);
mechanics::MechanicsStats mechanics_stats_of(const CheckpointState& cs);

// The whole mechanics state (has_mechanics = true); its particle arrays go to the checkpoint's
// position, velocity and angular_velocity. mechanics_state_of needs has_mechanics.
void store_mechanics_state(const mechanics::MechanicsState& state, CheckpointState& cs);
mechanics::MechanicsState mechanics_state_of(const CheckpointState& cs);

// A settle checkpoint's own part (SettleProgress.h): settling = true, the rest test's window
// and the settle's counters (/extra scalars "settle_progress_*"). settle_progress_of needs
// settling; the window's pairs come back as written (strictly increasing, as saved).
void store_settle_progress(const SettleProgress& progress, CheckpointState& cs);
SettleProgress settle_progress_of(const CheckpointState& cs);

// The next checkpoint time after t: the first multiple of the interval strictly above t, the
// same in an uninterrupted run and in one restarted at t (so both have the same boundaries).
double next_checkpoint_time_s(double t_s, double interval_s);

}  // namespace tmdem::coupling

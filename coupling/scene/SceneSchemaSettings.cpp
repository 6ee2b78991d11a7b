// The scene schema's settings sections, [mechanics], [thermal] and [output] (SceneSchema.h). Their
// defaults are Scene.h's (MechanicsSettings, ThermalSettings, OutputSettings), written there once.
#include "coupling/scene/SceneSchemaKeys.h"

#include "mechanics/solvers/ContactSolverRegistry.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ModeRegistry.h"
#include "mechanics/contact/NormalLaw.h"

namespace tmdem::coupling::schema_keys {

std::vector<Section> settings_sections() {
  const auto& kM = kMechanicsDefaults;
  const auto& kT = kThermalDefaults;
  const auto& kO = kOutputDefaults;
  std::vector<Section> sections;
  sections.push_back(
      {"mechanics", "NSCD (Moreau-Jean, Gauss-Seidel); range checks apply when mechanics is on",
       {number("time_step", "s", kM.time_step_s, Range::greater(0.0), "mechanical time step"),
        number("theta", "", kM.theta, Range::open_closed(0.0, 1.0), "Moreau-Jean theta"),
        choice("solver", kM.solver, mechanics::contact_solver_names(),
               "contact solver by name (mechanics::ContactSolverRegistry)"),
        choice("stop_test", kM.stop_test, {"sweep", "siconos"},
               "when a step's solve counts as converged: \"siconos\", when Siconos' residual "
               "(relative to |q|) is below tolerance (nncg sweeping on as needed; a solve out of "
               "sweeps or stalled on its sweep change with the residual below tolerance counts "
               "as converged); \"sweep\", when the change of one sweep is (the other solvers "
               "always stop and count on their own test; docs/mechanics.md \"Honest convergence\")"),
        choice("normal_law", mechanics::normal_law_name(kM.normal_law), mechanics::normal_law_names(),
               "normal contact law: \"rigid\", unilateral contacts without overlap (NSCD); "
               "\"hertz\", elastic contacts at the materials' young_modulus and poisson_ratio, "
               "F = (4/3) E* sqrt(R*) delta^(3/2) for an overlap delta, solved in the same "
               "Moreau-Jean step as a normal compliance: forces unique in a hyperstatic packing, "
               "elastic overlaps kept (the position step removes only what lies beyond them); "
               "not with solver apgd or nlgs_block (docs/mechanics.md \"The normal law\")"),
        number("tolerance", "", kM.tolerance, Range::greater(0.0),
               "relative residual at which a step's solve counts as converged (scale-free): "
               "with stop_test \"siconos\" (the default), Siconos' natural-map residual of the "
               "contact law relative to |q|; with \"sweep\", and for the solvers other than nncg "
               "and nncg_ipm, the change of the reactions over one sweep relative to the "
               "reactions (docs/mechanics.md \"The defaults\", \"Honest convergence\")"),
        number("fall_tolerance", "", kM.fall_tolerance, Range::at_least(0.0),
               "tolerance schedule: the solves stop at this tolerance instead of `tolerance` "
               "from the first step at which fall_share of the particles move at or above "
               "fall_speed (never tighter than `tolerance`), or a piston moves at or above "
               "compaction_speed; once the fastest particle is below fall_speed again and every "
               "piston below compaction_speed, the tolerance ramps back to `tolerance` over "
               "tighten_steps (settle and dynamic runs alike). A step that ends unconverged at "
               "`tolerance` while fall_share of the particles move at a tenth of fall_speed or "
               "faster (a laid bed giving way, a pile creeping) is taken again at this "
               "tolerance, the bed then collapsing until its fastest particle is below that "
               "tenth (needs retry_parts >= 2 and this tolerance looser than `tolerance`). 0: no "
               "schedule, `tolerance` for every step. A step counts as converged when it met "
               "the tolerance in force"),
        number("fall_speed", "m/s", std::nullopt, Range::greater(0.0),
               "tolerance schedule: the particle speed at or above which a particle "
               "counts as falling (fall_tolerance applies); absent: a tenth of the smallest "
               "radius per time_step (0.05 m/s for 0.5 mm spheres at 1 ms)"),
        number("fall_share", "", kM.fall_share, Range::closed(0.0, 1.0),
               "tolerance schedule: the share of the moving particles (at least one) that "
               "must move at or above fall_speed for a fall to begin; 0: the fastest alone. "
               "A few spheres rolling down a laid bed's surface do not put the whole bed at "
               "fall_tolerance (docs/mechanics.md \"A tolerance schedule\")"),
        number("compaction_speed", "m/s", std::nullopt, Range::at_least(0.0),
               "tolerance schedule: while a piston moves at or above this speed its load is "
               "compacting the bed and the solves stop at fall_tolerance, as in a fall, from any "
               "phase; once every piston is slower (and no particle falls) the tolerance ramps "
               "back to `tolerance` over tighten_steps. A loaded bed that flows creeps at the "
               "edge of jamming, where solves at `tolerance` stall just above it "
               "(docs/mechanics.md \"A tolerance schedule\"); absent: a hundredth of the speed "
               "the piston's load and weight give it in one time_step, time_step |F / m + g.n| "
               "(a pressed bed solved at fall_tolerance creeps by itself at about a tenth of "
               "that); 0: off. Only with the solvers that stop on Siconos' residual (nncg, "
               "nncg_ipm): at the others' sweep test a bed creeps by itself faster"),
        number("stop_travel", "", kM.stop_travel, Range::at_least(0.0),
               "the stop test counts a contact's impulse at most as the one that would move "
               "its bodies by this fraction of the smallest radius per time_step, so that "
               "contacts under a load far above their weight are solved to the same speed "
               "error as the rest (docs/mechanics.md \"The defaults\"); 0: off"),
        boolean("estimate_piston_reach", bool_text(kM.estimate_piston_reach),
                "where a piston's bound reach (its load and weight as if nothing held it) is "
                "beyond 4 largest radii (a light piston under a large load), list its candidate "
                "pairs within its likely reach instead (its speed and twice the acceleration the "
                "bed's last push leaves it), each step's travel checked against that table after the solve and "
                "the step listed again with the bound where it does not fit "
                "(summary mechanics.relisted_steps; docs/mechanics.md \"A loaded piston's reach\")"),
        boolean("skip_out_of_reach", bool_text(kM.skip_out_of_reach),
                "leave out of each step's contact problem the candidates farther apart than "
                "their two look-aheads (the bound on the step's motion the detector trusts): "
                "about 2x faster while a large pour lands, but not exact (a struck particle can "
                "outrun its own look-ahead), so off by default "
                "(docs/mechanics.md \"The defaults\")"),
        boolean("static_warm_start", bool_text(kM.static_warm_start),
                "the first step's solve starts from the statics of the contact geometry (each "
                "particle's weight and what rests on it passed down to its supports) instead of "
                "from no forces: a deposited or imported bed's first steps take fewer sweeps "
                "(docs/mechanics.md \"The first step\")"),
        value("static_balance_rounds", "", std::to_string(kM.static_balance_rounds),
              "integer in [0, " + std::to_string(mechanics::NscdParameters::kMaxBalanceRounds) + "]",
              "with static_warm_start, rounds that also balance each particle horizontally and in "
              "rotation (one sparse factorisation with 6 unknowns per particle each): a deep "
              "shaft's first step finds the side walls' friction (Janssen) in far fewer sweeps, "
              "but a bed that still has to move may take more in its later steps; 0: the "
              "vertical start alone (docs/mechanics.md \"The first step\")"),
        value("residual_check_every", "", std::to_string(kM.residual_check_every), "integer >= 0",
              "solvers nncg and nncg_ipm with stop_test \"siconos\": until a solve's sweep test "
              "is met, Siconos' residual is checked every this many sweeps and the solve ends "
              "once it is within the tolerance (a check costs about one full sweep; 0: never). "
              "Fewer sweeps between checks end a pour's steps sooner, with deeper overlaps left "
              "in its impact steps (docs/mechanics.md \"Checked before the sweep test is met\")"),
        value("tighten_steps", "", std::to_string(kM.tighten_steps), "integer >= 1",
              "tolerance schedule: once the fall has ended, the tolerance goes from "
              "fall_tolerance to tolerance geometrically over this many steps (1: at once)"),
        value("max_iterations", "", std::to_string(kM.max_iterations), "integer >= 1", "Gauss-Seidel sweeps per step, at most"),
        value("retry_parts", "", std::to_string(kM.retry_parts),
              "integer in [1, " + std::to_string(mechanics::NscdParameters::kMaxRetryParts) + "]",
              "a step that ends unconverged is taken again from its start in 2 equal parts, "
              "then 4, and so on up to this many, until every part converges (parts of the "
              "first try's own: a piston's landing first taken in 8 parts is retaken in 16, "
              "32, 64); the last try stands, converged or not (1: never retaken). A step still "
              "unconverged after its retries halves the parts the next retries may go up to, "
              "and ten converged steps in a row double them back. The steps that stall are rare and tied to one "
              "configuration of the bed (a piston at the onset of a compaction), and a shorter "
              "step starts nearer its answer (docs/mechanics.md \"Retaking an unconverged "
              "step\"; summary: mechanics.retried_steps, mechanics.discarded_sweeps)"),
        value("retry_keep_steps", "", std::to_string(kM.retry_keep_steps), "integer >= 0",
              "a step retaken in P parts that converged makes the steps after it start in P "
              "parts, and this many converged steps in a row halve P again, down to whole "
              "steps (0: every step starts whole). A bed's hard spell outlasts one step (a "
              "re-settle after heating, a piston compacting), and a whole try that stalls "
              "before its parts converge is thrown away. Off by default: where a bed's whole "
              "steps converge again right after a retry, the kept parts cost nearly a whole "
              "step's sweeps each (a plate landing on a deposit: 2.4 times the run at 4); try "
              "it where the summary's retried_steps come near its steps (docs/mechanics.md "
              "\"Steps that start in the parts the last retry needed\"; summary: "
              "mechanics.kept_parts_steps)"),
        boolean("fallback_on_last_try", bool_text(kM.fallback_on_last_try),
                "a solver with later stages (nncg_ipm, the default: the interior point, nncg "
                "once more, plain sweeps) runs them only on a step's last try, where no retry "
                "in shorter parts (retry_parts) would follow; a try that turned out to be the "
                "last without them is taken once more with them. A retry in parts converged "
                "the steps the stages left unconverged on a plate landing on a deposit, in a "
                "quarter of the time; off by default: on beds whose hard steps follow one "
                "another (2D deposits loaded, a periodic piston) the stages are cheaper than "
                "the retries, and one such bed kept an unconverged step with it "
                "(docs/mechanics.md \"The fallback on the last try\")"),
        value("full_sweep_every", "", std::to_string(kM.full_sweep_every), "integer >= 1",
              "\"nlgs\", \"nlgs_coloured\": a sweep over every candidate at least every this "
              "many sweeps, the others visit the contacts the last full sweep left closed; "
              "convergence is judged on full sweeps (1: every sweep is full)"),
        number("settle_time", "s", kM.settle_time_s, Range::greater(0.0), "longest \"settle\" phase"),
        number("coupling_interval", "s", kM.coupling_interval_s, Range::greater(0.0),
               "effects.mechanics = \"coupled\": heating time between two quasi-static "
               "re-solves of the packing (each settles as the first, at most settle_time of "
               "mechanics, the heating paused)"),
        number("settle_velocity", "m/s", kM.settle_velocity_m_per_s, Range::greater(0.0),
               "rest_test \"velocity\": every particle slower than this; \"network\": the "
               "mass-weighted mean speed sqrt(2 KE / M) of the load-carrying particles (pressed "
               "along gravity by at least half their weight) below this"),
        choice("rest_test", kM.rest_test, {"network", "velocity"},
               "when \"settle\" ends: \"network\" once the contact normal forces changed by less "
               "than rest_force_change over rest_window steps and the load-carrying particles "
               "are slower than settle_velocity (rattlers and the free surface are not waited for); "
               "\"velocity\" once "
               "every particle is slower than settle_velocity"),
        value("rest_window", "", std::to_string(kM.rest_window), "integer >= 1",
              "rest_test \"network\": steps over which the normal forces are compared"),
        number("rest_force_change", "", kM.rest_force_change, Range::greater(0.0),
               "rest_test \"network\": largest sum |F_now - F_window_before| / sum F_now"),
        number("penetration_slop", "", kM.penetration_slop, Range::closed(0.0, 0.5),
               "slop s, as a fraction of the smallest radius: overlaps up to 2 s are held, a "
               "deeper one is moved back to s by positions only (no speed is made of it)"),
        number("recovery_speed", "m/s", kM.recovery_speed_m_per_s, Range::at_least(0.0),
               "largest rate at which the position step moves an overlap out (at most h x this "
               "per step); 0 = no cap")}});
  sections.push_back(
      {"thermal", "the thermal integrator and the contact conductance",
       {choice("integrator", kT.integrator,
               names_of(thermal::thermal_integrator_names()),
               "CVODE (BDF), IDA (DAE; held temperatures algebraic) or forward Euler"),
        choice("linear_solver", std::string(thermal::kDefaultLinearSolverName),
               linear_solver_choices(),
               "\"auto\": one of the others, chosen once per run from the particles, the "
               "dimension, the MPI processes and the Jacobian's symmetry (klu for small beds and "
               "one-sided Jacobians, pcg for large ones, amg for the largest and under MPI; the "
               "rule and its measurements: docs/integrators.md); sparse direct (KLU), conjugate "
               "gradients preconditioned by incomplete Cholesky (pcg) "
               "or by an algebraic-multigrid V-cycle (amg, hypre BoomerAMG; also the steady "
               "state of study conductivity)"),
        number("relative_tolerance", "", kT.relative_tolerance, Range::greater(0.0), "integrator tolerance"),
        number("absolute_tolerance", "K", kT.absolute_tolerance_K, Range::greater(0.0), "integrator tolerance"),
        number("explicit_step", "s", kT.explicit_step_s, Range::at_least(0.0),
               "explicit step; 0 = 0.9 x the stability bound 2 / lambda_max (Gershgorin), a "
               "step above the bound is refused with the bound in the message"),
        choice("conductance", std::string(thermal::name_of(kT.conductance)),
               names_of(thermal::kConductanceLawNames),
               "contact conductance: \"hertz\": H = 2 k a (Hertz radius a from the normal "
               "force); \"constant\": constant_conductance; \"bahrami\": rough surfaces "
               "(material roughness, asperity_slope, microhardness), the Hertz spot in series "
               "with its micro-contacts and, with effects.gas_conduction, its micro-gap "
               "(docs/heat-modes.md \"Rough contacts\")"),
        number("constant_conductance", "W/K", kT.constant_conductance_W_per_K, Range::greater(0.0),
               "H of every contact when conductance = \"constant\""),
        number("contact_flattening", "", kT.contact_flattening, Range::closed(0.0, 1.0),
               "conductance = \"hertz\": a loaded contact conducts through a spot of radius at "
               "least contact_flattening x R* (R* = r1 r2 / (r1 + r2); a wall: r), the flattened "
               "contact of rough or deformed beads (ZSB's flattening term); 0 = the Hertz radius "
               "(docs/heat-modes.md \"Flattened contacts\")"),
        choice("particle_resistance", std::string(thermal::name_of(kT.particle_resistance)),
               names_of(thermal::kParticleResistanceNames),
               "the particle's own resistance: \"isothermal_core\" puts the solid shell between "
               "an isothermal core (radius core_fraction x r) and the surface in series with the "
               "summed contact and gas conductance of every pair, H' = 1 / (1/H + R_a + R_b), "
               "R = (1/(c r) - 1/r) / (k Omega) over the cone Omega that the partner (a wall: "
               "the mirror image) subtends; \"isothermal_core_rays\" keeps that for the contacts "
               "and lets the surrounding layer's gas cross the shells ray by ray, each ray's "
               "shell in series with its own gas; needs constant conductivities "
               "(docs/heat-modes.md \"The particle's own resistance\")"),
        number("core_fraction", "", kT.core_fraction, Range::open(0.0, 1.0),
               "particle_resistance = \"isothermal_core\": radius of the isothermal core as a "
               "fraction c of the particle radius"),
        choice("coupling", kT.coupling, {"continue", "restart"},
               "dynamic runs: keep the integrator history while only forces change, or "
               "re-initialise every mechanical step")}});
  sections.push_back(
      {"output", "the result file",
       {value("file", "", "\"" + kO.file + "\"", "non-empty path", "result file (HDF5; RESULT.xdmf beside it)"),
        number("interval", "s", kO.interval_s, Range::greater(0.0), "simulated time between frames"),
        boolean("contacts", bool_text(kO.contacts), "store the contact list of every frame"),
        number("checkpoint_interval", "s", kO.checkpoint_interval_s, Range::at_least(0.0),
               "simulated time between checkpoints; 0 = none"),
        number("settle_checkpoint_interval", "s", kO.settle_checkpoint_interval_s, Range::at_least(0.0),
               "wall-clock time between settle checkpoints while a packing settles (RESULT.checkpoint.h5; "
               "--restart resumes the settle); 0 = none")}});
  return sections;
}

}  // namespace tmdem::coupling::schema_keys

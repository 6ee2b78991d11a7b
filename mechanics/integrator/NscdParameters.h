#pragma once
// Settings of the Moreau-Jean / bipotential contact dynamics ([mechanics] in the scene).

#include "mechanics/model/ParallelFrom.h"
#include <cstddef>
#include <optional>
#include <string>

#include "mechanics/contact/NormalLaw.h"
#include "mechanics/solvers/ContactSolverRegistry.h"

namespace tmdem::mechanics {

struct NscdParameters {
  double time_step = 1.0e-3;  // s
  double theta = 0.5;         // Moreau-Jean theta, in (0, 1]; 0.5 conserves energy in flight
  std::string solver = default_contact_solver();  // contact solver by name (ContactSolverRegistry.h)
  // Rigid unilateral contacts, or Hertz's elastic ones at the materials' moduli (NormalLaw.h;
  // the position step then leaves overlaps alone: they are the law's).
  NormalLaw normal_law = NormalLaw::rigid;
  // Gauss-Seidel stop: sum_c |dr_c| / sum_c |r_c| < tolerance over one sweep (Euclidean norms
  // of the local impulses, N s). With the natural step of the closed-form local solve
  // (CoulombCone.h), dr_c is the bipotential fixed-point residual r - proj_K(r - rho u~) of
  // contact c at its visit, so this is the relative residual of the contact law itself; the
  // same residual re-evaluated for every contact after the sweep is within 0.85-1.2x of it
  // (measured on stalled steps of the default scene and a 3D pile).
  // 1e-5: at 1e-6 a poured 3D bed of thousands of spheres spends thousands of sweeps per step
  // and does not settle in hours; at 1e-4 a landed bed creeps and never rests
  // (docs/mechanics.md "The defaults").
  double tolerance = 1.0e-5;
  // Tolerance schedule (ToleranceSchedule.h): while the largest particle speed is at or above
  // fall_speed (m/s), the solves stop at fall_tolerance instead (never tighter than
  // `tolerance`); after the speed first drops back below fall_speed, `tolerance` holds for the
  // rest of the run. fall_tolerance 0: off. On by default: when a pour lands every step brings
  // new impacts, and at the tight tolerance those steps run out of sweeps.
  double fall_tolerance = 1.0e-4;
  // m/s; 0: automatic, fall_travel_fraction of the smallest radius per time step (a particle
  // that moves a tenth of the smallest radius per step is still falling, at any scale: 0.05 m/s
  // for examples/pour_3d.toml's 0.5 mm spheres at 1 ms).
  double fall_speed = 0.0;
  double fall_travel_fraction = 0.1;
  // A fall begins when this share of the moving particles (at least one; 0: the fastest
  // alone) reach fall_speed, and ends, as before, when the fastest is below it: in a bed laid
  // by deposition a few surface spheres always roll (20-40 of 100,000 above 0.1 m/s), and
  // judged on the fastest the whole bed sat at fall_tolerance, crept, and a 100,000 bed did
  // not come to rest in 1,100 s (429 s with the share; docs/mechanics.md "A tolerance
  // schedule"). A pour's fill falls as a whole and starts its fall as before.
  double fall_share = 0.01;
  // The stop test counts a contact's impulse at most as the one that moves its bodies by this
  // fraction of the smallest radius per time step (ContactProblem::stop_speed; 0: off, every
  // impulse counts whole). 1: the 48-sphere glass bed of test_e2e_conductivity under a 1e4 Pa
  // piston creeps from 10.18 to 9.54 mm over 1,100 converged steps at tolerance 1e-5 without
  // it (its contacts carry ~10x the impulse that gives r_min per step), and holds with it.
  double stop_travel_fraction = 1.0;
  // Steps over which the tolerance goes geometrically from fall_tolerance to tolerance once
  // the fall has ended (ToleranceSchedule.h); 1: at once. Why 20: right after a pour lands the
  // pile still creeps, and solved at once at tolerance those steps stalled a little above it
  // (bed_2d laid with seeds 21 and 22: past 600 s, and 2 unconverged steps; at 20: at rest in
  // 213 and 226 steps, none unconverged; docs/mechanics.md "A tolerance schedule").
  int tighten_steps = 20;
  // While a piston moves at or above its compaction speed its load is compacting the bed, and
  // the solves stop at fall_tolerance as in a fall; once no piston does the tolerance ramps
  // back over tighten_steps (ToleranceSchedule.h). A loaded bed that flows creeps at the edge
  // of jamming, where the sweeps stall just above `tolerance` (docs/mechanics.md "A tolerance
  // schedule"). m/s; 0: off; absent: automatic, compaction_fraction of the speed the piston's
  // load and weight give it in one step, h |F / m + g.n|. Why relative to that speed: solved at
  // fall_tolerance a pressed bed creeps by itself, at a speed that grows with the load
  // (piston_cylinder at 1e4 Pa: 2-3e-4 m/s, 0.1% of h F / m); with a fixed 1e-4 m/s the creep
  // kept the schedule falling for 4 s of mechanics. Only with a solver whose steps stop on
  // Siconos' residual (nncg, nncg_ipm; siconos_stop): the sweep test of the others leaves a
  // larger residual at fall_tolerance, and the bed's own creep then stays above the compaction
  // speed (examples/thermal_cycling.toml's lid with nncg_subspace, for the whole 5 s settle).
  std::optional<double> compaction_speed;
  // Of h |F / m + g.n| (0: off). A hundredth: ten times the creep of piston_cylinder at 1e4 Pa
  // above; through its study over four seeds it left 18 unconverged steps, a fixed 1e-3 m/s 47.
  double compaction_fraction = 0.01;
  // A step that ends unconverged is taken again from its start in 2 equal parts, then 4, and so
  // on up to this many, until every part converges (NscdIntegrator::step(double); parts of its
  // first try's own: a landing first taken in 8 parts is retaken in 16, 32, 64); the last
  // try stands, converged or not. 1: never retaken. A step still unconverged after its retries
  // halves the parts the next retries may go up to, ten converged steps double them back.
  // Why: the steps that stall are rare and tied to one configuration (a piston creeping at the
  // onset of a compaction, a loaded bed flowing under it), and a shorter step starts nearer its
  // answer and ends elsewhere.
  // piston_cylinder's study (1e3, 1e4, 1e5 Pa), four seeds: 18 unconverged steps with whole
  // steps, 0 with retries up to 8 parts (docs/mechanics.md "Retaking an unconverged step").
  int retry_parts = 8;
  // A step retaken in P parts that then converged makes the steps after it start in P parts
  // (the bed's hard spell outlasts one step: a re-settle after heating, a piston compacting),
  // and this many converged steps in a row halve P again (down to whole steps). 0: every
  // step starts whole. Why: thermal_cycling on nncg_ipm at 1e-5 threw away 12.9 M sweeps on 958
  // retakes, each whole try stalling before the parts converged; 4 cut its sweeps to half. Off by
  // default: on bench/beds/plate_on_deposit, whose whole steps converge again after a retry, 4
  // cost 2.4 times the run (docs/mechanics.md "Steps that start in the parts the last retry
  // needed").
  int retry_keep_steps = 0;
  static constexpr int kMaxRetryParts = 64;
  // A solver with later stages (nncg_ipm: the interior point, nncg once more, plain sweeps) runs
  // them only on a try of a step that no retry in shorter parts would follow; a try that
  // turned out to be the last without them is taken once more with them. Why: a retry in parts
  // converged the steps the stages did not (docs/mechanics.md "The fallback on the last try").
  // Opt-in: measured on 40 beds, it quarters two runs and doubles or triples two others, where
  // the stages converge cheaply what the retries in parts do not.
  bool fallback_on_last_try = false;
  int max_iterations = 10000; // Gauss-Seidel sweeps per step
  // "nncg" only (the other solvers stop on their own test whatever this says): a step converges
  // when Siconos' residual is within the tolerance too, not only the change per sweep
  // (SolverSettings::siconos_stop; docs/mechanics.md "Honest convergence"). On by default: the
  // examples keep their bits (every one of their steps already met it), the beds laid at rest
  // pay 3-4x the sweeps for an answer within the tolerance.
  bool siconos_stop = true;
  // With siconos_stop, "nncg" (and nncg_ipm's nncg) checks Siconos' residual every this many
  // sweeps before its own sweep test is met, and ends the solve as soon as it is within the
  // tolerance (SolverSettings::residual_check_every, NncgSolver::Options::
  // siconos_check_unmet_every; scene key mechanics.residual_check_every; 0: never). A check
  // costs about one full sweep. Denser checks end the steps of a pour sooner (the residual is
  // relative to |q|, which the open candidates' gaps inflate) at the price of deeper transient
  // overlaps in the impact steps: at 100 instead of 250, wide_pour 240.7 s instead of 327.2 s
  // (2 threads), its deepest overlap after a step 1.1e-5 m instead of 4.6e-6; the beds at rest
  // alike (docs/mechanics.md "How often to check"). The same as NncgSolver's own default.
  int residual_check_every = 100;
  // Over-relaxation of the Gauss-Seidel update, r <- proj_K(r + w (r_local - r)); 1 = plain
  // Gauss-Seidel. On frictional piles over-relaxation does not pay (default 256-particle 2D
  // scene: w = 1.3, 1.6, 1.8 gave more unconverged steps and more sweeps than w = 1).
  double relaxation = 1.0;
  // Gauss-Seidel stops early (stalled, counted as unconverged) when its residual has not
  // fallen below 0.9x its best value over this many sweeps.
  int stall_sweeps = 500;
  // Gauss-Seidel sweeps visit the active contacts only, with a sweep over every candidate at
  // least every this many sweeps and before convergence is declared (ActiveContactSet.h;
  // SolverSettings::full_sweep_every; scene key mechanics.full_sweep_every). 1: every sweep
  // visits every candidate. With 8 the first 110 steps of bench_pour 2000/1 cost 18.9 s of
  // CPU instead of 36.8 s, and a step's solve is as accurate as with 1; but a settling bed
  // ends up elsewhere, as it does for any change to the solve (K = 1 at a 1% tighter
  // tolerance: the 2,000 pour not at rest in 5 s either, test_e2e_conductivity's seed-5 bed
  // exponent 0.394 instead of 0.320, as with 8), so the tests' measured trajectories hold
  // for 1 only (measured in development). Default 1.
  int full_sweep_every = 1;
  // The same period for the penetration correction's position solve (PenetrationCorrection.h),
  // which pushes a few contacts of many: 8 by default; 1 reproduces the trajectories of
  // before (test fixtures settled on them).
  int correction_full_sweep_every = 8;
  // Penetration slop s, as a fraction of the smallest radius. The velocity solve never pushes
  // an overlap out (NscdIntegrator.h); the position step (PenetrationCorrection.h) holds
  // overlaps up to 2 s and brings a deeper one back to s by moving centres only, so at the end
  // of every step no overlap is deeper than 2 s (to the position solve's 1% tolerance).
  // 0: every overlap is removed within its step (still without speed).
  double penetration_slop_fraction = 1.0e-4;
  // Largest distance per unit time, m/s, by which the position step moves an overlap out
  // (correction at most h * recovery_speed per step; 0 = no cap). No speed is made of it.
  double recovery_speed = 0.0;
  // Candidates farther apart than their two look-aheads leave the step's problem. The
  // 10,000-sphere pour's collapse: 95 steps in 199 s of CPU instead of 385 s, the same mean
  // sweeps. Not exact: a look-ahead bounds a particle's motion from its own velocity, but a
  // resting particle struck within the step moves at its striker's speed (impulses cross a
  // rigid packing at once), and can then close a gap its own look-ahead did not foresee; the
  // detector is safe because its margin follows the largest look-ahead of all. So a left-out
  // pair may overlap after the step (the position step then removes it) and trajectories move:
  // pour_3d with nncg at rest after 297 steps instead of 251, a resting nlgs_block pile drifts
  // 2e-7 m in 10,000 steps instead of < 1e-9 m, an imported bed re-settles in 15 steps instead
  // of <= 10. On a pile where nothing is struck it keeps the bits (test_out_of_reach). Off.
  bool skip_out_of_reach = false;
  // A moving wall's candidates listed with its likely reach instead of its bound. The bound
  // (2 h (|v| + h |a|), a its load and weight over its mass) is what a piston would travel if
  // nothing held it; once the piston can touch a particle, every particle pair within it is
  // listed. A light piston under a large load makes that reach many diameters: 1 g pressed
  // with 6.4 N (1e5 Pa on an 8 x 8 mm shaft of 1 mm spheres) reaches 12.8 mm, and its 2,920
  // spheres' table held 3.6 million candidates (7,600 contacts), 13 s a step at 250 sweeps.
  // With the key, a piston whose load alone reaches beyond NscdIntegrator::kEstimatedReachFrom
  // widest margins (2 h^2 |a|) is listed with its speed and twice the acceleration the bed's last push leaves it,
  // and after the solve the step's travel is checked against the table: where it does not fit
  // (the bed gave way), the step is listed with the bound and solved again (summary
  // mechanics.relisted_steps). That bed came to rest in 110 steps, 396 s. Never on a run's first
  // step; a step after a load change comes out at the bound by the same rule (the last push
  // does not hold the new load). Off: the bound on every step (docs/mechanics.md "A loaded
  // piston's reach").
  bool estimate_wall_reach = true;
  // Candidate margin, as fractions of the largest radius (see ContactDetector).
  double min_margin_fraction = 0.1;
  double max_margin_fraction = 2.0;
  // Particles (detection) or candidates (contact set-up) from which those loops use OpenMP
  // threads; below it waking the threads costs more than the loop. 0: always (tests). The
  // results are the same bits for any thread count.
  std::ptrdiff_t parallel_from = kDefaultParallelFrom;  // mechanics/model/ParallelFrom.h
  // Particles from which the contact solver is handed the problem in a spatial order
  // (SpatialContactOrder.h: bodies along a Morton curve, contacts sorted by them; ids and
  // results keep the scene's order). Measured on the settled 2,000 pour bed tiled with ids at
  // random (1 thread, 40 cold nlgs sweeps): 2,000 spheres 95 ns per candidate per sweep in
  // their ids' order, 100 ns in spatial order (the copy); 18,000: 101-103 and 103; 98,000:
  // 124-126 and 108-110. Where between 18,000 and 98,000 it starts to pay was not measured.
  // 0: always (tests).
  std::size_t spatial_order_from = 50000;
  // The first step of an integrator that knows no forces starts its solve from the statics of
  // the contact geometry (StaticWarmStart.h) instead of from zero impulses. A restored state
  // keeps its own warm start.
  bool static_warm_start = true;
  // With the static warm start, this many rounds that balance each particle horizontally and in
  // rotation as well (StaticWarmStart.h; 0: the vertical start alone). Off by default until
  // measured on every bed (docs/mechanics.md "The first step").
  int static_balance_rounds = 0;
  static constexpr int kMaxBalanceRounds = 100;  // the scene key's upper bound
};

}  // namespace tmdem::mechanics

#!/usr/bin/env python3
"""Sweeps per step against a bed's depth and load, as a run settles it (the target "iterations per
step at most 2x from 10 to 160 layers and from 1e3 to 1e5 Pa with the default solver").

Usage, from the project's root after a build:
    python3 bench/depth_and_load.py [--threads N] [--limit SECONDS] [--layers 10,40,160]
                                    [--pressures 0,1e3,1e4,1e5] [--seeds 5,21,22] [--set KEY=VALUE ...]
For every depth and load it writes a scene (steel spheres of 1 mm diameter, friction 0.5,
rolling resistance 0.02, laid by deposition in an 8 x 8 mm shaft to about LAYERS diameters; for a
pressure > 0 a 1 g piston started resting on the bed's top, pressing with PRESSURE over the
shaft's 64 mm2), settles it at the scene defaults
    OMP_NUM_THREADS=N build/tmdem run SCENE.toml --summary S.json --quiet --set simulation.duration=1e-3
(bench/settle_beds.py's run) once per seed (default 5) and prints a line each: layers, particles,
pressure, seed, steps, mean and largest sweeps per step, unconverged steps, at rest, mechanics
wall seconds; with several seeds a line per shaft with the mean over seeds; then the depth ratio
(deepest against shallowest, unloaded) and the load ratios (heaviest against lightest load) of
those means. The bench_solvers BM_PileHeight benchmark
solves one step of a lattice pile cold instead (no warm start): both are reported in
docs/benchmarks.md. Needs only the standard library.
"""
import argparse
import os
import sys
import tempfile

from settle_beds import parse_seeds, run_bed  # the same run as every bed of bench/beds

SPHERES_PER_MM = 73  # about 0.6 x 64 mm3 / (pi / 6 mm3): spheres per mm of the shaft's height


def scene(layers, pressure):
    count = SPHERES_PER_MM * layers
    lines = [
        f"# {count} steel spheres laid in an 8 x 8 mm shaft, about {layers} layers"
        + (f", pressed at {pressure:g} Pa" if pressure > 0 else ""),
        'format = "tmdem-scene-1"',
        "[simulation]", "duration = 1.0", "gravity = [0.0, 0.0, -9.81]", "seed = 5",
        "[effects]", 'mechanics = "settle"',
        "[[material]]", 'name = "steel"', "density = 7800.0", "young_modulus = 2.1e11",
        "poisson_ratio = 0.3", "friction = 0.5", "rolling_friction = 0.02", "conductivity = 50.0",
        "heat_capacity = 460.0",
        "[[generate]]", 'kind = "deposit"', f"count = {count}",
        f"box = {{ min = [0.0, 0.0, 0.0], max = [0.008, 0.008, {0.004 * layers:g}] }}",
        "radius = 0.0005", 'material = "steel"',
        "[[wall]]", "point = [0.0, 0.0, 0.0]", "normal = [0.0, 0.0, 1.0]", 'material = "steel"',
        "temperature = 373.15",
    ]
    for point, normal in (("[0.0, 0.0, 0.0]", "[1.0, 0.0, 0.0]"), ("[0.008, 0.0, 0.0]", "[-1.0, 0.0, 0.0]"),
                          ("[0.0, 0.0, 0.0]", "[0.0, 1.0, 0.0]"), ("[0.0, 0.008, 0.0]", "[0.0, -1.0, 0.0]")):
        lines += ["[[wall]]", f"point = {point}", f"normal = {normal}", 'material = "steel"']
    if pressure > 0:
        lines += ["[[wall]]", f"point = [0.0, 0.0, {0.004 * layers:g}]", "normal = [0.0, 0.0, -1.0]",
                  'material = "steel"', "piston = true", "mass = 0.001", f"pressure = {pressure:g}",
                  "pressure_area = 6.4e-5", 'start = "on_bed"']
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--limit", type=float, default=300.0)
    parser.add_argument("--layers", default="10,40,160")
    parser.add_argument("--pressures", default="0,1e3,1e4,1e5")
    parser.add_argument("--tmdem", default=os.path.join("build", "tmdem"))
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a scene setting for every run (tmdem run --set), e.g. mechanics.static_balance_rounds=4")
    parser.add_argument("--seeds", default="5",
                        help="comma-separated seeds: every shaft is laid and settled once per seed (the sweeps "
                             "a bed takes to rest are chaotic in its seed), and a line per shaft gives the mean "
                             "over seeds of the mean sweeps per step")
    args = parser.parse_args()
    seeds = parse_seeds(args.seeds)
    tmdem = os.path.abspath(args.tmdem)
    if not os.access(tmdem, os.X_OK):
        sys.exit(f"no {args.tmdem}: run from the project's root after a build, or give --tmdem")
    print(f"{'layers':>6} {'particles':>9} {'pressure Pa':>11} {'seed':>5} {'steps':>6} {'mean sweeps':>11} "
          f"{'max sweeps':>10} {'unconv':>6} {'at rest':>7} {'mech s':>8}", flush=True)
    bad = 0
    over_seeds = {}  # (layers, pressure) -> the mean sweeps per step of each seed's run
    with tempfile.TemporaryDirectory() as work:
        for layers in (int(x) for x in args.layers.split(",")):
            for pressure in (float(x) for x in args.pressures.split(",")):
                name = os.path.join(work, f"bed_{layers}_{pressure:g}")
                with open(name + ".toml", "w") as out:
                    out.write(scene(layers, pressure))
                means = over_seeds.setdefault((layers, pressure), [])
                for seed in seeds:
                    code, summary, _, _, _ = run_bed(tmdem, name + ".toml", args.threads, args.limit, work,
                                                     args.set + [f"simulation.seed={seed}"])
                    if summary is None:
                        bad = 1
                        print(f"{layers:>6} {SPHERES_PER_MM * layers:>9} {pressure:>11g} {seed:>5}  failed ({code})",
                              flush=True)
                        continue
                    m = summary["mechanics"]
                    rest = summary.get("settle", {}).get("at_rest")
                    if m["unconverged_steps"] or rest is not True:
                        bad = 1
                    means.append(m["mean_iterations"])
                    print(f"{layers:>6} {summary['particles']:>9} {pressure:>11g} {seed:>5} {m['steps']:>6} "
                          f"{m['mean_iterations']:>11.0f} {m['max_iterations']:>10} {m['unconverged_steps']:>6} "
                          f"{str(rest):>7} {summary['wall_time_parts']['mechanics_s']:>8.1f}", flush=True)
                if len(seeds) > 1 and means:
                    print(f"{layers:>6} {'':>9} {pressure:>11g} {'mean':>5} {'':>6} {sum(means) / len(means):>11.0f}"
                          f"   (over {len(means)} of {len(seeds)} seeds)", flush=True)
    # The ratios the target is about: the deepest shaft's sweeps per step against the shallowest's
    # (unloaded), and the heaviest load's against the lightest's (each depth), means over seeds.
    mean = {key: sum(v) / len(v) for key, v in over_seeds.items() if v}
    depths = sorted({k[0] for k in mean})
    loads = sorted({k[1] for k in mean})
    if len(depths) > 1 and (depths[0], loads[0]) in mean and (depths[-1], loads[0]) in mean:
        print(f"depth ratio {depths[0]} -> {depths[-1]} layers at {loads[0]:g} Pa: "
              f"{mean[(depths[-1], loads[0])] / mean[(depths[0], loads[0])]:.1f}x", flush=True)
    positive = [p for p in loads if p > 0]
    for layers in depths:
        if len(positive) > 1 and (layers, positive[0]) in mean and (layers, positive[-1]) in mean:
            print(f"load ratio {positive[0]:g} -> {positive[-1]:g} Pa at {layers} layers: "
                  f"{mean[(layers, positive[-1])] / mean[(layers, positive[0])]:.1f}x", flush=True)
    return bad


if __name__ == "__main__":
    sys.exit(main())

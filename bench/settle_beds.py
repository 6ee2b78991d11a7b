#!/usr/bin/env python3
"""Settle beds at the scene defaults and print one line a bed (the beds users bring, and ours).

Usage, from the project's root after a build:
    python3 bench/settle_beds.py [--threads N] [--limit SECONDS] [--seeds 5,21,22] [--set KEY=VALUE ...]
                                 [BED.toml ...]
Default beds: bench/beds/*.toml (ours: other containers, frictions, size and mass ratios, 2D,
plates and pistons than the sample users gave us). Each bed runs
    OMP_NUM_THREADS=N build/tmdem run BED.toml --summary S.json --quiet --set simulation.duration=1e-3
in a temporary folder (the heating after the settle is cut to 1 ms: only the mechanics is judged)
and its line says: particles, mechanical steps, mean sweeps, unconverged steps, the largest
Siconos residual, the largest speed when frozen, mechanics wall seconds, CPU seconds of the
process, and "ok" when the bed came to rest with no step unconverged within the limit.
--set KEY=VALUE passes a scene setting to every run (tmdem run --set). --seeds runs every bed once
per seed (--set simulation.seed=N: a bed laid by deposition is laid anew, a pour poured anew) and
adds a line per bed over its seeds: steps and mechanics seconds summed, the mean of the mean sweeps,
the unconverged steps summed. How a bed comes to rest is chaotic (one seed can take 10x the sweeps
of the next at the same settings), so a change is judged over seeds, not on one.
Exit 1 when a bed falls short. Needs only the standard library.
"""
import argparse
import glob
import json
import os
import resource
import subprocess
import sys
import tempfile
import time


def run_bed(tmdem, bed, threads, limit, work, settings=()):
    """Settles one bed at the defaults (the command above, in the bed's folder). Returns its exit
    code ("time limit" past `limit` seconds), its summary (a dict; None when there is none), the
    wall and CPU seconds of the process, and its stderr."""
    name = os.path.splitext(os.path.basename(bed))[0]
    summary = os.path.join(work, name + ".json")
    command = [tmdem, "run", os.path.abspath(bed), "-o", os.path.join(work, name + ".h5"), "--summary", summary,
               "--overwrite", "--quiet", "--set", "simulation.duration=1e-3"]
    for setting in settings:  # extra KEY=VALUE settings (bench/depth_and_load.py --set)
        command += ["--set", setting]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    try:
        result = subprocess.run(command, cwd=os.path.dirname(os.path.abspath(bed)), env=env,
                                capture_output=True, text=True, timeout=limit)
        code = result.returncode
        stderr = result.stderr
    except subprocess.TimeoutExpired as expired:
        code = "time limit"
        stderr = expired.stderr.decode() if isinstance(expired.stderr, bytes) else (expired.stderr or "")
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    s = None
    if code == 0 and os.path.exists(summary):
        with open(summary) as f:
            s = json.load(f)
    return code, s, wall, cpu, stderr


def parse_seeds(text):
    """The seeds of --seeds ("5,21,22"; "" for none), or exit naming the bad value."""
    try:
        return [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        sys.exit(f"--seeds: integers separated by commas, not '{text}'")


def settle(tmdem, bed, threads, limit, work, settings=(), label=None):
    """Settles one bed; returns (ok, its line, its summary or None)."""
    name = label or os.path.splitext(os.path.basename(bed))[0]
    code, s, wall, cpu, stderr = run_bed(tmdem, bed, threads, limit, work, settings)
    if s is None:
        last = stderr.strip().splitlines()[-1] if stderr.strip() else ""
        return False, f"{name:<20} {'':>9} {'':>6} {'':>7} {'':>6} {'':>9} {'':>10} {wall:>8.1f} {cpu:>8.1f}  " \
                      f"FALLS SHORT ({code}{': ' + last[:80] if code != 'time limit' else ''})", None
    m = s["mechanics"]
    rest = s.get("settle", {})
    ok = rest.get("at_rest") is True and m["unconverged_steps"] == 0
    return ok, (f"{name:<20} {s.get('particles', '?')!s:>9} {m['steps']:>6} {m.get('mean_iterations', 0):>7.0f} "
                f"{m['unconverged_steps']:>6} {m.get('max_siconos_residual', float('nan')):>9.1e} "
                f"{rest.get('max_speed_m_s', float('nan')):>10.2e} {s['wall_time_parts']['mechanics_s']:>8.1f} "
                f"{cpu:>8.1f}  {'ok' if ok else 'FALLS SHORT'}{'' if rest.get('at_rest') else ' (not at rest)'}"), s


def over_seeds(name, seeds, summaries):
    """The line of a bed over its seeds (None for a run that gave no summary)."""
    done = [s for s in summaries if s is not None]
    if not done:
        return f"{name + ' (' + str(len(seeds)) + ' seeds)':<28} no run gave a summary"
    mech = [s["mechanics"] for s in done]
    return (f"{name + ' over ' + str(len(seeds)) + ' seeds':<28} steps {sum(m['steps'] for m in mech)}, "
            f"mean sweeps {sum(m.get('mean_iterations', 0) for m in mech) / len(mech):.0f}, "
            f"unconverged {sum(m['unconverged_steps'] for m in mech)}, "
            f"at rest {sum(1 for s in done if s.get('settle', {}).get('at_rest') is True)} of {len(seeds)}, "
            f"mechanics s {sum(s['wall_time_parts']['mechanics_s'] for s in done):.1f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--limit", type=float, default=300.0, help="seconds per bed (wall)")
    parser.add_argument("--tmdem", default=os.path.join(os.getcwd(), "build", "tmdem"))
    parser.add_argument("--seeds", default="", help="comma-separated seeds: each bed once per seed")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a scene setting for every run (tmdem run --set)")
    parser.add_argument("beds", nargs="*")
    args = parser.parse_args()
    seeds = parse_seeds(args.seeds)
    beds = args.beds or sorted(glob.glob(os.path.join(os.path.dirname(os.path.abspath(__file__)), "beds", "*.toml")))
    if not os.access(args.tmdem, os.X_OK):
        sys.exit(f"no {args.tmdem}: run from the project's root after a build, or give --tmdem")
    print(f"{'bed':<20} {'particles':>9} {'steps':>6} {'sweeps':>7} {'unconv':>6} {'siconos':>9} "
          f"{'speed m/s':>10} {'mech s':>8} {'cpu s':>8}  verdict", flush=True)
    all_ok = True
    with tempfile.TemporaryDirectory() as work:
        for bed in beds:
            name = os.path.splitext(os.path.basename(bed))[0]
            if not seeds:
                ok, line, _ = settle(args.tmdem, bed, args.threads, args.limit, work, args.set)
                all_ok = all_ok and ok
                print(line, flush=True)
                continue
            summaries = []
            for seed in seeds:
                ok, line, s = settle(args.tmdem, bed, args.threads, args.limit, work,
                                     args.set + [f"simulation.seed={seed}"], f"{name} seed {seed}")
                all_ok = all_ok and ok
                summaries.append(s)
                print(line, flush=True)
            print(over_seeds(name, seeds, summaries), flush=True)
    sys.exit(0 if all_ok else 1)


if __name__ == "__main__":
    main()

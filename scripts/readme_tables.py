#!/usr/bin/env python3
"""Regenerates the measured tables of docs/benchmarks.md from fresh runs of build/tmdem.

Each table sits between the markers
    <!-- readme_tables: NAME -->
    ...table...
    <!-- /readme_tables -->
and is rebuilt by running the commands its section names. Columns that depend on timing
(wall-clock seconds) are marked "[timing]" in their header: they change from run to run and
machine to machine; every other value (steps, errors, counts) is reproducible for a given build.
(The script and marker names keep "readme" from the days these tables lived in README.md.)

  scripts/readme_tables.py                  # rewrite checkpoints, coupling, settle in docs/benchmarks.md
  scripts/readme_tables.py --check          # compare only: exit 1 naming the values that drifted
  scripts/readme_tables.py --only coupling  # one table
  scripts/readme_tables.py --list           # every table of docs/benchmarks.md and how it is kept true
  scripts/readme_tables.py --file OTHER.md  # another Markdown file with the same markers

Tables: checkpoints (thermal steps added by checkpoint boundaries), coupling (`tmdem study
coupling examples/poured_bed.toml`), settle (how the default scene settles: `tmdem run`).
Together they run in about a minute on one core. piston (`tmdem study conductivity
examples/conductivity/piston_bed.toml --pressures ...`, half a minute of CPU) is rebuilt only
with `--only piston`, never by the default run or --check. examples (every scene of examples/
run for its whole duration: steps, converged %, sweeps, rest, penetration; minutes, pour_3d
most of them) likewise runs only with `--only examples`.
Needs python3 (standard library only). The ctest test readme_tables (label readme) runs --check.

The other measured tables are marked `<!-- readme_tables: hand-measured (why); command ... -->`
on the line above: the accuracy summary (its "cheapest run" is chosen by wall time), the
piston bed's gas-model comparison, the benchmark programs (bench_thermal, bench_mechanics,
bench_solvers, bench_pour: timings) and the solver and thread comparisons. Their timing columns
say `[timing]`; they are refreshed by rerunning the command docs/benchmarks.md shows above them.
"""
import argparse
import csv
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
# Every generated table states "1 thread": its runs get one, whatever the caller's environment.
os.environ["OMP_NUM_THREADS"] = "1"
TIMING = "[timing]"


def sci(value, digits):
    """value in e-notation without a leading zero in a negative exponent: 1.5e-3, not 1.5e-03."""
    return re.sub(r"e-0(\d)", r"e-\1", f"{value:.{digits}e}")


def tmdem(binary, args, cwd):
    subprocess.run([str(binary)] + args, cwd=cwd, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


def thermal_steps(binary, scene, sets, work):
    summary = pathlib.Path(work) / "s.json"
    tmdem(binary, ["run", str(ROOT / "examples" / scene), "-o", "r.h5", "--overwrite", "--quiet",
                   "--summary", str(summary)] + sum([["--set", s] for s in sets], []), work)
    return json.loads(summary.read_text())["thermal"]["steps"]


def checkpoints_table(binary, work):
    """Thermal steps without checkpoints, with 2 (or 1) and with 9 boundaries inside the run."""
    cases = [("lattice_constant.toml", "lattice_constant, 50 s", f"{i}/{s}" if i != "explicit" else i,
              ([f"thermal.integrator={i}"] + ([f"thermal.linear_solver={s}"] if s else [])), 20, 5)
             for i, s in [("cvode", "klu"), ("cvode", "pcg"), ("ida", "klu"), ("ida", "pcg"),
                          ("explicit", None)]]
    cases += [("paper_triangle.toml", "paper_triangle, 200 s", "cvode/klu", [], 100, 20),
              ("poured_bed.toml", "poured_bed, 0.5 s", "cvode/klu", ["simulation.duration=0.5"],
               0.2, 0.05)]
    rows = ["| scene | integrator | no checkpoint | 2 boundaries inside the run | 9 boundaries |",
            "|---|---|---|---|---|"]
    for k, (scene, label, integrator, sets, few, many) in enumerate(cases):
        counts = [thermal_steps(binary, scene, sets, work)]
        for x in (few, many):
            counts.append(thermal_steps(binary, scene, sets + [f"output.checkpoint_interval={x}"],
                                        work))
        first = k == 0 or scene != cases[k - 1][0]
        inside = " inside" if scene == "paper_triangle.toml" else ""
        few_text = f"{counts[1]} (X = {few:g}{', 1' + inside if inside else ''})" if first else str(counts[1])
        many_text = f"{counts[2]} (X = {many:g})" if first else str(counts[2])
        rows.append(f"| {label} | {integrator} | {counts[0]} | {few_text} | {many_text} |")
    return rows


def coupling_table(binary, work):
    out = pathlib.Path(work) / "coupling.csv"
    tmdem(binary, ["study", "coupling", str(ROOT / "examples" / "poured_bed.toml"), "--csv",
                   str(out)], work)
    rows = ["| strategy | rtol / step | max error (K) | thermal time (s) " + TIMING +
            " | thermal steps | re-initialisations |", "|---|---|---|---|---|---|"]
    with open(out) as f:
        for r in csv.DictReader(f):
            explicit = r["integrator"] == "explicit"
            strategy = "explicit at the mechanical step" if explicit else r["strategy"]
            parameter = sci(float(r["parameter"]), 0) + (" s" if explicit else "")
            error = sci(float(r["max_error_K"]), 1)
            rows.append(f"| {strategy} | {parameter} | {error} | "
                        f"{float(r['thermal_wall_time_s']):.3f} | {r['thermal_steps']} | "
                        f"{r['reinitializations']} |")
    return rows


def settle_table(binary, work):
    """The default scene's settle phase (its heating is skipped: duration 0.01 s)."""
    summary = pathlib.Path(work) / "settle.json"
    tmdem(binary, ["run", "--set", "simulation.duration=0.01", "-o", "settle.h5", "--overwrite",
                   "--quiet", "--summary", str(summary)], work)
    s = json.loads(summary.read_text())
    m, settle = s["mechanics"], s["settle"]
    r_min = 5e-4  # the default scene's smallest radius, m (examples/paper_bed.toml)
    return ["| settle steps | at rest | unconverged (stalled) | mean sweeps | max sweeps | "
            "largest penetration (m) | correction sweeps | largest travel per step / r_min | "
            "wall time (s) " + TIMING + " |", "|---|---|---|---|---|---|---|---|---|",
            f"| {settle['steps']:,} | {'yes' if settle['at_rest'] else 'no'} | "
            f"{m['unconverged_steps']} ({m['stalled_steps']}) | {m['mean_iterations']:.0f} | "
            f"{m['max_iterations']} | {sci(m['max_penetration_m'], 2)} | {m['correction_sweeps']:,} | "
            f"{m['max_step_travel_m'] / r_min:.2f} | {s['wall_time_s']:.1f} |"]


PISTON_PRESSURES = "1e3,3e3,1e4"


def piston_table(binary, work):
    """k_eff of examples/conductivity/piston_bed.toml against the piston's pressure (minutes: run
    by --only piston, not by the default run or --check)."""
    csv_path = pathlib.Path(work) / "piston_bed.csv"
    out = subprocess.run([str(binary), "study", "conductivity",
                          str(ROOT / "examples" / "conductivity" / "piston_bed.toml"),
                          "--pressures", PISTON_PRESSURES, "--csv", str(csv_path)],
                         cwd=work, check=True, capture_output=True, text=True)
    # One settle line per load, in order: "settle: at rest (TEST test) after T s (N steps, ..."
    # or the warning "not at rest after mechanics.settle_time = T s ...".
    settles = re.findall(r"settle: at rest (?:\(\w+ test\) )?after \S+ s \((\d+) steps|(not at rest after "
                         r"mechanics\.settle_time = \S+ s)", out.stdout + out.stderr)
    rows = ["| pressure (Pa) | k_eff (W/(m K)) | porosity | coordination | L (mm) | "
            "contacts (+ walls) | settle steps |", "|---|---|---|---|---|---|---|"]
    with open(csv_path) as f:
        for k, r in enumerate(csv.DictReader(f)):
            steps, late = settles[k] if k < len(settles) else ("?", "")
            rest = "not at rest" if late else steps
            pressure = re.sub(r"e\+0?(\d)", r"e\1", f"{float(r['pressure_Pa']):.0e}")
            k_eff = sci(float(r["k_eff_W_per_mK"]), 4)
            rows.append(f"| {pressure} | {k_eff} | {float(r['porosity']):.4f} | "
                        f"{float(r['coordination']):.3f} | {1e3 * float(r['length_m']):.3f} | "
                        f"{r['contacts']} (+ {r['wall_contacts']}) | {rest} |")
    return rows


def scene_default(section, key):
    """A scene key's default as docs/scene.md (generated from the schema) states it."""
    inside = False
    for line in (ROOT / "docs" / "scene.md").read_text().splitlines():
        if line.startswith("## "):
            inside = line == f"## `[{section}]`"
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if inside and len(cells) > 2 and cells[0] == f"`{key}`":
            return cells[2].strip('"')
    sys.exit(f"docs/scene.md: no row for [{section}] `{key}`")


def smallest_radius(binary, scene, work):
    """The scene's smallest radius, m, as `tmdem check` prints it."""
    out = subprocess.run([str(binary), "check", str(scene)], cwd=work, check=True,
                         capture_output=True, text=True).stdout
    found = re.search(r"radius ([0-9.eE+-]+) \.\.", out)
    if not found:
        sys.exit(f"tmdem check {scene}: no 'radius A .. B' line")
    return float(found.group(1))


def examples_table(binary, work):
    """Every scene of examples/ run as it is (its whole duration), one row each: how its
    mechanics converged and settled (issue 10: >= 99% of the steps converged)."""
    import tomllib
    rows = ["| example | mechanics | solver | particles | steps | converged % | mean sweeps | "
            "stalled | at rest | largest penetration / r_min | wall time (s) " + TIMING + " |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for scene in sorted((ROOT / "examples").rglob("*.toml")):
        name = scene.relative_to(ROOT / "examples").as_posix()
        config = tomllib.loads(scene.read_text())
        mode = config.get("effects", {}).get("mechanics", scene_default("effects", "mechanics"))
        solver = config.get("mechanics", {}).get("solver", scene_default("mechanics", "solver"))
        summary = pathlib.Path(work) / "example.json"
        tmdem(binary, ["run", str(scene), "-o", "example.h5", "--overwrite", "--quiet", "--summary",
                       str(summary)], work)
        s = json.loads(summary.read_text())
        m = s.get("mechanics")
        if mode == "off" or not m or not m.get("steps"):
            rows.append(f"| {name} | off | - | {s['particles']:,} | - | - | - | - | - | - | "
                        f"{s['wall_time_s']:.1f} |")
            continue
        steps = m["steps"]
        converged = 100.0 * (steps - m["unconverged_steps"]) / steps
        settle = s.get("settle")
        # A run without a settle phase has the block with at_rest null (not judged).
        at_rest = "-" if not settle or settle["at_rest"] is None else "yes" if settle["at_rest"] else "no"
        penetration = m["max_penetration_m"] / smallest_radius(binary, scene, work)
        rows.append(f"| {name} | {mode} | {solver} | {s['particles']:,} | {steps:,} | "
                    f"{converged:.1f} | {m['mean_iterations']:.1f} | {m['stalled_steps']} | "
                    f"{at_rest} | {sci(penetration, 1)} | {s['wall_time_s']:.1f} |")
    return rows


TABLES = {"checkpoints": checkpoints_table, "coupling": coupling_table, "settle": settle_table}
# Too long for the default run and --check (the ctest): only with --only NAME.
SLOW_TABLES = {"piston": piston_table, "examples": examples_table}


def timing_columns(header):
    return {k for k, cell in enumerate(header.strip("|").split("|")) if TIMING in cell}


def drift(old_rows, new_rows):
    """The reproducible cells that differ: (row, column, old, new)."""
    out = []
    skip = timing_columns(new_rows[0]) if new_rows else set()
    for r, (a, b) in enumerate(zip(old_rows, new_rows)):
        for c, (x, y) in enumerate(zip(a.strip("|").split("|"), b.strip("|").split("|"))):
            if c not in skip and x.strip() != y.strip():
                out.append((r, c, x.strip(), y.strip()))
    if len(old_rows) != len(new_rows):
        out.append((len(old_rows), 0, f"{len(old_rows)} rows", f"{len(new_rows)} rows"))
    return out


def table_inventory(text):
    """(line number, header, how) for every table of the text: the regenerating block's name,
    the hand-measured marker, or "not marked" (descriptive tables)."""
    lines = text.splitlines()
    out, block = [], None
    for k, line in enumerate(lines):
        opened = re.match(r" *<!-- readme_tables: (\w+) -->", line)
        if opened:
            block = opened.group(1)
        elif "<!-- /readme_tables -->" in line:
            block = None
        starts = line.lstrip().startswith("|") and (k == 0 or not lines[k - 1].lstrip().startswith("|"))
        if not starts:
            continue
        above = lines[k - 1].strip() if k > 0 else ""
        marker = re.match(r"<!-- readme_tables: (hand-measured.*?) -->", above)
        how = (f"regenerated: {block}" if block else marker.group(1) if marker else "not marked")
        out.append((k + 1, line.strip()[:60], how))
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--file", "--readme", dest="file", default=str(ROOT / "docs" / "benchmarks.md"),
                   help="the Markdown file holding the tables (default: docs/benchmarks.md)")
    p.add_argument("--tmdem", default=str(ROOT / "build" / "tmdem"))
    p.add_argument("--only", choices=sorted(TABLES) + sorted(SLOW_TABLES), action="append")
    p.add_argument("--check", action="store_true", help="compare only; exit 1 on drift")
    p.add_argument("--list", action="store_true", help="list every table and how it is kept")
    args = p.parse_args(argv)
    text = pathlib.Path(args.file).read_text()
    shown = os.path.relpath(args.file, ROOT) if os.path.isabs(args.file) else args.file
    if args.list:
        for line, header, how in table_inventory(text):
            print(f"{shown}:{line}: {how}: {header}")
        return 0
    drifted = False
    with tempfile.TemporaryDirectory() as work:
        for name in args.only or sorted(TABLES):
            pattern = re.compile(r"(<!-- readme_tables: " + name + r" -->\n)(.*?)(\n *<!-- /readme_tables -->)",
                                 re.S)
            found = pattern.search(text)
            if not found:
                sys.exit(f"{args.file}: no <!-- readme_tables: {name} --> ... <!-- /readme_tables --> block")
            indent = re.match(r" *", found.group(2)).group(0)
            old_rows = [line.strip() for line in found.group(2).splitlines() if line.strip()]
            new_rows = {**TABLES, **SLOW_TABLES}[name](args.tmdem, work)
            for r, c, old, new in drift(old_rows, new_rows):
                drifted = True
                print(f"{name}: row {r}, column {c + 1}: {shown} {old!r}, now {new!r}")
            block = "\n".join(indent + row for row in new_rows)
            text = text[:found.start(2)] + block + text[found.end(2):]
    if args.check:
        print(f"{shown}: tables drifted from fresh runs: rewrite them with scripts/readme_tables.py "
              "(and check the prose that cites them)" if drifted
              else f"{shown}: tables match fresh runs (timing columns aside)")
        return 1 if drifted else 0
    pathlib.Path(args.file).write_text(text)
    print(f"rewrote {', '.join(args.only or sorted(TABLES))} in {shown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""`python dev/bench.py`: the quench-chain benchmark, this code against a baseline, side by side (a maintainer's
tool, not part of the user command line).

Absolute times on a shared machine are noise; a ratio measured in one session, with the two codes run
alternately on the same case, is not (much). Each run is a separate ``python -m quenchsim.cli run`` process
(the wall time a user waits for, imports and the numba cache included); the baseline is another
interpreter with another checkout of quenchsim installed (``--baseline-python``), or a commit that the
command checks out into a git worktree and installs into its own venv (``--baseline-commit``).

    python dev/bench.py --baseline-commit cc353be                      # ring A, condition 1, default mesh, 3 x 2 runs
    python dev/bench.py --baseline-python /tmp/venv_old/bin/python --mesh 2 1 0.5 --repeat 1
    python dev/bench.py --baseline-commit cc353be --profile runs/bench/prof --out docs/experiments/bench.md
    python dev/bench.py --baseline-commit cc353be --set time.max_dX=0.01 --reference runs/ring_a_fine

Per mesh factor it prints the median wall and CPU time of each side, their ratios, the median time of each stage of
the run on each side and its ratio, the time per DOF per step, the largest differences of the results (dimension
change, probe t500, HRC58 depth, residual hoop stress) between the sides, and the largest relative difference over
every number of summary.json that both sides write (timings left out) and every value of probes.csv; with
``--reference`` (a run folder of the same case at converged settings, e.g. steps refined until the results stop
moving), of each side from the reference too: a speed-up counts at equal accuracy. The 1-minute load average is
taken before each run. ``--set`` options go to both sides' runs (e.g. the same step control for both).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import pstats
import resource
import statistics
import subprocess
import sys
import time
import tomllib
from pathlib import Path
from typing import Any

import numpy as np

import quenchsim

CASE = "cases/crb_outer_ring.toml"
CONDITION = "1"
PROBE_SCRIPT = "import pathlib, quenchsim; print(pathlib.Path(quenchsim.__file__).resolve().parents[1])"
STAGES = ("thermal_metallurgy_s", "mechanics_s")
"""The stages of the time loop: their sum per DOF per step is the cost that should not grow with the mesh."""
TIMING_KEYS = ("solver.wall_time_s", "solver.stage_time_s.")
"""summary.json numbers that are timings (or start with these), not results: left out of the sides' comparison."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--baseline-python", type=Path, help="interpreter that imports the baseline quenchsim")
    parser.add_argument("--baseline-commit", help="git commit of the baseline: checked out and installed into "
                        "a venv under --work (reused when present)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per side and mesh factor (median; default 3)")
    parser.add_argument("--mesh", type=float, nargs="+", default=[1.0],
                        help="mesh factors (element sizes times the factor; default 1)")
    parser.add_argument("--case", default=CASE, help=f"case file, relative to each side's checkout (default {CASE})")
    parser.add_argument("--condition", default=CONDITION, help=f"condition (default {CONDITION})")
    parser.add_argument("--work", type=Path, default=Path("runs/bench"), help="run folders and the baseline venv")
    parser.add_argument("--profile", action="store_true", help="one more run per side under cProfile at the "
                        "first mesh factor; the top functions go into the report")
    parser.add_argument("--out", type=Path, help="write the Markdown report here (and its JSON beside it)")
    parser.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                        help="case override passed to both sides' runs (repeatable), e.g. time.max_dX=0.01")
    parser.add_argument("--reference", type=Path, help="run folder of the same case at converged settings: each "
                        "side's results are compared with its summary.json")


# -- sides -------------------------------------------------------------------------------------------
def checkout_root(python: str, env: dict[str, str], cwd: Path) -> Path:
    """The folder holding the quenchsim package that ``python`` imports (run from ``cwd``, a folder without
    a quenchsim package, since ``python -c`` puts the working folder first on the path)."""
    return Path(subprocess.run([python, "-c", PROBE_SCRIPT], env=env, capture_output=True, text=True,
                               check=True, cwd=cwd).stdout.strip())


def baseline_from_commit(commit: str, work: Path) -> Path:
    """A worktree of ``commit`` with its own venv (system site packages, the checkout installed editable)."""
    source = Path(quenchsim.__file__).resolve().parents[1]
    tree, venv = (work / f"baseline_{commit}").resolve(), (work / f"venv_{commit}").resolve()
    if not tree.exists():
        subprocess.run(["git", "-C", str(source), "worktree", "add", "--detach", str(tree), commit], check=True)
    python = venv / "bin" / "python"
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
        subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-deps", "-e", str(tree)], check=True)
    return python


def side_env(root: Path | None) -> dict[str, str]:
    """Environment of a side's runs: single-threaded BLAS (as the CLI sets) and, for this checkout, its
    folder first on the path (for the baseline nothing, so its own install is imported)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env.update({"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"})
    if root is not None:
        env["PYTHONPATH"] = str(root)
    return env


def mesh_overrides(case_path: Path, factor: float) -> list[str]:
    """``--set`` options that scale the case's element sizes by ``factor``."""
    if factor == 1.0:
        return []
    mesh = tomllib.loads(case_path.read_text())["mesh"]
    return ["--set", f"mesh.size_mm={mesh['size_mm'] * factor:g}",
            "--set", f"mesh.surface_size_mm={mesh['surface_size_mm'] * factor:g}"]


# -- one run -----------------------------------------------------------------------------------------
def results_of(summary: dict[str, Any]) -> dict[str, float]:
    """The compared results: dimension changes, probe t500, HRC58 depths, residual hoop stresses."""
    out = {f"dimension_change_{k}_mm": v for k, v in summary["dimensions_mm"]["change"].items()}
    out.update({f"t500_{name}_s": p["t_to_500C_s"] for name, p in summary["probes"].items()
                if isinstance(p, dict) and p.get("t_to_500C_s") is not None})
    out.update({f"{k}_mm": v for k, v in summary["hardness"]["depth_mm"].items()})
    out.update({f"hoop_{k}_MPa": v for k, v in summary["residual_stress_MPa"]["hoop"].items()})
    return out


def children_cpu_s() -> float:
    """User + system CPU time of the finished child processes so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_once(python: str, env: dict[str, str], root: Path, case: str, condition: str, factor: float, out: Path,
             profile: Path | None = None, overrides: list[str] | tuple[str, ...] = ()) -> dict[str, Any]:
    """One ``quenchsim run`` in its own process; its wall and CPU time, the solver's record and the results.

    The CPU time (user + system of the process) is less disturbed than the wall time by other work on a shared
    machine: the process waiting for a core does not count."""
    case_path = root / case
    prefix = [python] + (["-m", "cProfile", "-o", str(profile)] if profile else []) + ["-m", "quenchsim.cli"]
    cmd = prefix + ["run", str(case_path), "--condition", condition, "--out", str(out), "--quiet",
                    *mesh_overrides(case_path, factor), *(a for o in overrides for a in ("--set", o))]
    load, cpu0, t0 = os.getloadavg()[0], children_cpu_s(), time.perf_counter()
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=root)
    wall, cpu = time.perf_counter() - t0, children_cpu_s() - cpu0
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({proc.returncode}): {proc.stderr[-2000:]}")
    summary = json.loads((out / "summary.json").read_text())
    solver = summary["solver"]
    loop = sum(solver["stage_time_s"].get(k, 0.0) for k in STAGES)
    return {"wall_s": wall, "cpu_s": cpu, "loop_s": loop, "steps": solver["steps"], "dofs": solver["dofs"],
            "loop_us_per_dof_step": 1e6 * loop / (solver["dofs"] * solver["steps"]),
            "wall_us_per_dof_step": 1e6 * wall / (solver["dofs"] * solver["steps"]),
            "stage_time_s": solver["stage_time_s"], "results": results_of(summary), "load_1min": load,
            "out": str(out)}


def summary_numbers(summary: Any, prefix: str = "") -> dict[str, float]:
    """Every number of a summary.json (nested keys joined by dots, list items by [i]), timings left out."""
    if isinstance(summary, dict):
        return {k: v for key, sub in summary.items() for k, v in summary_numbers(sub, f"{prefix}{key}.").items()}
    if isinstance(summary, list):
        return {k: v for i, sub in enumerate(summary) for k, v in summary_numbers(sub, f"{prefix[:-1]}[{i}].").items()}
    name = prefix[:-1]
    if isinstance(summary, bool) or not isinstance(summary, (int, float)) or name.startswith(TIMING_KEYS):
        return {}
    return {name: float(summary)}


def relative_difference(a: float, b: float) -> float:
    """|a - b| over the larger magnitude (0 for equal numbers, NaN and NaN included)."""
    if a == b or (a != a and b != b):
        return 0.0
    return abs(a - b) / max(abs(a), abs(b))


def equality(old_out: Path, new_out: Path) -> dict[str, Any]:
    """The largest relative difference between two runs over every summary.json number both write (timings left
    out) and over every probes.csv value, with where it is and what only one side writes."""
    old = summary_numbers(json.loads((old_out / "summary.json").read_text()))
    new = summary_numbers(json.loads((new_out / "summary.json").read_text()))
    common = [k for k in old if k in new]
    worst = max(common, key=lambda k: relative_difference(old[k], new[k]), default=None)
    probes_old = np.genfromtxt(old_out / "probes.csv", delimiter=",", skip_header=1)
    probes_new = np.genfromtxt(new_out / "probes.csv", delimiter=",", skip_header=1)
    same_shape = probes_old.shape == probes_new.shape
    probe_diff = (float(np.max(np.vectorize(relative_difference)(probes_old, probes_new), initial=0.0))
                  if same_shape else float("nan"))
    return {"summary_numbers": len(common), "summary_max_rel": relative_difference(old[worst], new[worst]) if worst else 0.0,
            "summary_max_rel_key": worst, "only_baseline": sorted(set(old) - set(new)),
            "only_current": sorted(set(new) - set(old)), "probe_values": int(probes_new.size) if same_shape else 0,
            "probes_same_shape": same_shape, "probes_max_rel": probe_diff}


def compare(old: dict[str, float], new: dict[str, float]) -> dict[str, float]:
    """|new - old| of every result both sides have."""
    return {k: abs(new[k] - old[k]) for k in old if k in new}


def median_of(runs: list[dict[str, Any]], key: str) -> float:
    return statistics.median(r[key] for r in runs)


# -- profile -----------------------------------------------------------------------------------------
def top_functions(profile: Path, root: Path, n: int = 15) -> list[dict[str, Any]]:
    """The ``n`` functions with the most own time in a cProfile dump (paths relative to the checkout)."""
    stats = pstats.Stats(str(profile))
    rows = []
    for (file, line, name), (_, calls, own, cumulative, _) in stats.stats.items():  # type: ignore[attr-defined]
        where = file.replace(str(root) + os.sep, "").replace(str(Path(sys.prefix)), "<python>")
        rows.append({"function": f"{where}:{line}({name})", "calls": calls, "own_s": own, "cumulative_s": cumulative})
    return sorted(rows, key=lambda r: -r["own_s"])[:n]


# -- report ------------------------------------------------------------------------------------------
def markdown(record: dict[str, Any]) -> str:
    md = [f"Case `{record['case']}` condition {record['condition']}, full chain, run by `python dev/bench.py` on "
          f"{record['machine']}: {record['repeat']} runs per side and mesh factor, the two sides alternating "
          "(baseline, this code, baseline, ...), each a separate `quenchsim run` process; medians. Other load on "
          f"the machine: 1-minute load average {record['load_before']:.1f} before and {record['load_after']:.1f} "
          f"after the benchmark, {_load_range(record)} before the single runs.", "",
          f"Baseline: `{record['baseline']}`; this code: `{record['current']}`."
          + (f" Case overrides for both sides: `{' '.join(record['overrides'])}`." if record.get("overrides") else ""), "",
          "| mesh factor | DOFs | steps (baseline / this code) | baseline wall s | this code wall s | speed-up (wall) "
          "| baseline CPU s | this code CPU s | speed-up (CPU) | baseline loop us/DOF/step | this code loop us/DOF/step "
          "| largest result differences between the sides |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for row in record["rows"]:
        md.append(f"| {row['mesh_factor']:g} | {row['dofs']} | {row['baseline_steps']} / {row['steps']} | "
                  f"{row['baseline_wall_s']:.1f} | {row['current_wall_s']:.1f} | **{row['speedup']:.2f}** | "
                  f"{row['baseline_cpu_s']:.1f} | {row['current_cpu_s']:.1f} | **{row['cpu_speedup']:.2f}** | "
                  f"{row['baseline_loop_us_per_dof_step']:.2f} | {row['current_loop_us_per_dof_step']:.2f} | "
                  f"{_differences_text(row['largest_differences'])} |")
    md += ["", "Median time of each stage of the run (`summary.json` solver.stage_time_s) and its ratio, baseline over this "
           "code:", "", "| mesh factor | stage | baseline s | this code s | speed-up |", "|---|---|---|---|---|"]
    md += [f"| {row['mesh_factor']:g} | {stage} | {old:.2f} | {new:.2f} | **{old / new if new > 0 else float('nan'):.2f}** |"
           for row in record["rows"] for stage, (old, new) in row["stages"].items()]
    md += ["", "The sides' results compared number by number (the first run of each side): every number of "
           "`summary.json` that both write (timings left out) and every value of `probes.csv`; the keys only one side "
           "writes are listed.", "", "| mesh factor | summary numbers compared | largest relative difference (key) | "
           "probe values compared | largest relative difference | only the baseline writes | only this code writes |",
           "|---|---|---|---|---|---|---|"]
    for row in record["rows"]:
        eq = row["equality"]
        md.append(f"| {row['mesh_factor']:g} | {eq['summary_numbers']} | {eq['summary_max_rel']:.2g}"
                  f"{_worst_key_text(eq)} | "
                  f"{eq['probe_values'] if eq['probes_same_shape'] else 'different shapes'} | {eq['probes_max_rel']:.2g} | "
                  f"{_keys_text(eq['only_baseline'])} | {_keys_text(eq['only_current'])} |")
    if record.get("reference"):
        md += ["", f"Largest differences from the reference run `{record['reference']}`:", "",
               "| mesh factor | baseline | this code |", "|---|---|---|"]
        md += [f"| {row['mesh_factor']:g} | {_differences_text(row['from_reference']['baseline'])} | "
               f"{_differences_text(row['from_reference']['current'])} |" for row in record["rows"]]
    if len(record["rows"]) > 1:
        for side in ("baseline", "current"):
            per = [r[f"{side}_loop_us_per_dof_step"] for r in record["rows"]]
            md.append(f"\n{'Baseline' if side == 'baseline' else 'This code'}: time-loop cost per DOF per step from "
                      f"{min(per):.2f} to {max(per):.2f} us over the mesh factors (max/min {max(per) / min(per):.2f}).")
    md.append("\nThe loop time is the thermal + metallurgy and mechanics stages of `summary.json`; the wall time also "
              "holds the imports, meshing, set-up and output of the process.")
    for side, rows in record.get("profiles", {}).items():
        md += ["", f"### Profile: {side} (cProfile, one run, own time)", "", "| function | calls | own s | cumulative s |",
               "|---|---|---|---|"]
        md += [f"| `{r['function']}` | {r['calls']} | {r['own_s']:.2f} | {r['cumulative_s']:.2f} |" for r in rows]
    return "\n".join(md) + "\n"


def _worst_key_text(eq: dict[str, Any]) -> str:
    return f" (`{eq['summary_max_rel_key']}`)" if eq["summary_max_rel"] > 0 else ""


def _load_range(record: dict[str, Any]) -> str:
    loads = [r["load_1min"] for row in record["rows"] for side in row["runs"].values() for r in side]
    return f"{min(loads):.1f}-{max(loads):.1f}" if loads else "not taken"


def _keys_text(keys: list[str], most: int = 6) -> str:
    """A few keys of a list (``probes.P1.HRC``...), with the count of the rest."""
    if not keys:
        return "none"
    shown = ", ".join(f"`{k}`" for k in keys[:most])
    return shown + (f" and {len(keys) - most} more" if len(keys) > most else "")


def _differences_text(diffs: dict[str, float]) -> str:
    return (f"dimension {diffs['dimension_mm']:.2g} mm, t500 {diffs['t500_s']:.2g} s, HRC58 depth "
            f"{diffs['depth_mm']:.2g} mm, hoop {diffs['hoop_MPa']:.2g} MPa")


def largest_differences(runs_old: list[dict[str, Any]], runs_new: list[dict[str, Any]]) -> dict[str, float]:
    diff = compare(runs_old[0]["results"], runs_new[0]["results"])

    def worst(prefix: str) -> float:
        return max((v for k, v in diff.items() if k.startswith(prefix)), default=float("nan"))

    return {"dimension_mm": worst("dimension_change"), "t500_s": worst("t500"), "depth_mm": worst("HRC58"),
            "hoop_MPa": worst("hoop")}


def run(args: argparse.Namespace) -> int:
    from quenchsim.errors import InputError
    from quenchsim.results.reader import read_summary

    if (args.baseline_python is None) == (args.baseline_commit is None):
        raise InputError("--baseline-python/--baseline-commit", None, "give exactly one of them")
    if args.repeat < 1:
        raise InputError("--repeat", args.repeat, "must be >= 1")
    reference = None
    if args.reference is not None:
        summary = read_summary(args.reference)
        if summary is None:
            raise InputError("--reference", str(args.reference), "must be a run folder with a summary.json")
        reference = {"results": results_of(summary)}
    work = args.work.resolve()
    work.mkdir(parents=True, exist_ok=True)
    old_python = str(args.baseline_python or baseline_from_commit(args.baseline_commit, work))
    new_root = Path(quenchsim.__file__).resolve().parents[1]
    old_env, new_env = side_env(None), side_env(new_root)
    old_root = checkout_root(old_python, old_env, work)
    sides = {"baseline": (old_python, old_env, old_root), "current": (sys.executable, new_env, new_root)}
    record: dict[str, Any] = {"case": args.case, "condition": args.condition, "repeat": args.repeat,
                              "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
                              "baseline": f"{old_root} ({old_python})", "current": f"{new_root} ({sys.executable})",
                              "load_before": os.getloadavg()[0], "rows": [], "overrides": args.overrides,
                              "reference": str(args.reference) if reference else None}
    for factor in args.mesh:
        runs: dict[str, list[dict[str, Any]]] = {"baseline": [], "current": []}
        for rep in range(args.repeat):
            for side, (python, env, root) in sides.items():
                res = run_once(python, env, root, args.case, args.condition, factor, work / f"{side}_m{factor:g}_{rep}",
                               overrides=args.overrides)
                runs[side].append(res)
                print(f"mesh x{factor:g} run {rep + 1}/{args.repeat} {side}: {res['wall_s']:.1f} s wall, {res['cpu_s']:.1f} s CPU, "
                      f"{res['steps']} steps, {res['loop_us_per_dof_step']:.2f} us/DOF/step in the loop", flush=True)
        old_wall, new_wall = median_of(runs["baseline"], "wall_s"), median_of(runs["current"], "wall_s")
        old_cpu, new_cpu = median_of(runs["baseline"], "cpu_s"), median_of(runs["current"], "cpu_s")
        row = {"mesh_factor": factor, "dofs": runs["current"][0]["dofs"], "steps": runs["current"][0]["steps"],
               "baseline_steps": runs["baseline"][0]["steps"],
               "baseline_wall_s": old_wall, "current_wall_s": new_wall, "speedup": old_wall / new_wall,
               "baseline_cpu_s": old_cpu, "current_cpu_s": new_cpu, "cpu_speedup": old_cpu / new_cpu,
               **{f"{s}_loop_us_per_dof_step": median_of(runs[s], "loop_us_per_dof_step") for s in runs},
               **{f"{s}_loop_s": median_of(runs[s], "loop_s") for s in runs},
               "largest_differences": largest_differences(runs["baseline"], runs["current"]),
               "stages": {stage: tuple(statistics.median(r["stage_time_s"].get(stage, 0.0) for r in runs[side])
                                       for side in ("baseline", "current"))
                          for stage in dict.fromkeys(k for side in runs.values() for r in side for k in r["stage_time_s"])},
               "equality": equality(Path(runs["baseline"][0]["out"]), Path(runs["current"][0]["out"])),
               "differences": compare(runs["baseline"][0]["results"], runs["current"][0]["results"]),
               "runs": runs}
        if reference:
            row["from_reference"] = {side: largest_differences([reference], runs[side]) for side in runs}
        record["rows"].append(row)
        print(f"mesh x{factor:g}: baseline {old_wall:.1f} s, this code {new_wall:.1f} s, speed-up x{row['speedup']:.2f} "
              f"(CPU x{row['cpu_speedup']:.2f}); "
              f"largest differences {row['largest_differences']}", flush=True)
    if args.profile:
        record["profiles"] = {}
        for side, (python, env, root) in sides.items():
            prof = work / f"{side}.prof"
            run_once(python, env, root, args.case, args.condition, args.mesh[0], work / f"{side}_profile", profile=prof,
                     overrides=args.overrides)
            record["profiles"][side] = top_functions(prof, root)
    record["load_after"] = os.getloadavg()[0]
    text = markdown(record)
    print(text)
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(text)
        args.out.with_suffix(".json").write_text(json.dumps(record, indent=1, default=str))
    return 0


def main(argv: list[str] | None = None) -> int:
    """Command-line entry: ``python dev/bench.py --baseline-commit REV [...]``; bad input: one line, exit 2."""
    from quenchsim.errors import InputError

    parser = argparse.ArgumentParser(prog="dev/bench.py", description=__doc__.splitlines()[0])
    configure(parser)
    args = parser.parse_args(argv)
    try:
        return run(args)
    except InputError as err:
        print(f"dev/bench.py: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

"""`quenchsim optimise`: the optimiser on analytic problems with known answers, a resumed study, the checks of a
study file, and a small case study end to end (a constraint no run meets is said plainly, closest runs reported)."""

from __future__ import annotations

import csv
import importlib.util
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import tomli_w
from scipy.optimize import minimize

from quenchsim.cli import main
from quenchsim.design.optimise import Evaluation, Problem, evaluated, pareto_front, records, recommend, run_trials
from quenchsim.design.spec import Constraint, Objective, Variable, parse_study
from quenchsim.errors import InputError

ROOT = Path(__file__).resolve().parents[1]


# -- analytic problems ---------------------------------------------------------------------------------------------
def branin(x1: float, x2: float) -> float:
    """Branin-Hoo (Dixon & Szego 1978), x1 in [-5, 10], x2 in [0, 15]; global minimum 0.397887."""
    b, c, t = 5.1 / (4 * math.pi ** 2), 5 / math.pi, 1 / (8 * math.pi)
    return (x2 - b * x1 ** 2 + c * x1 - 6) ** 2 + 10 * (1 - t) * math.cos(x1) + 10


def branin_points(points):
    return [Evaluation({"f": branin(-5 + 15 * p["u"], 15 * p["v"]), "g": p["u"] * p["v"]}) for p in points]


BRANIN = Problem("branin", (Variable("u", 0.0, 1.0), Variable("v", 0.0, 1.0)), (Objective("f", "min"),),
                 (Constraint("g", ">=", 0.2),), startup=10, seed=0)
"""Branin on the unit square with the constraint u v >= 0.2, which cuts off all three unconstrained minima (at
(0.124, 0.818), (0.543, 0.152), (0.962, 0.165)); its constrained optimum is found independently below."""


def test_branin_constraint_optimum_is_known():
    """The reference answer, by SLSQP from a grid of starts: f* = 0.7330 at (0.9695, 0.2063), on the constraint."""
    best = min((minimize(lambda x: branin(-5 + 15 * x[0], 15 * x[1]), [u, v], method="SLSQP", bounds=[(0, 1)] * 2,
                         constraints=[{"type": "ineq", "fun": lambda x: x[0] * x[1] - 0.2}])
                for u in np.linspace(0.05, 0.95, 7) for v in np.linspace(0.05, 0.95, 7)), key=lambda r: r.fun)
    assert best.fun == pytest.approx(0.7330, abs=1e-3)
    assert best.x == pytest.approx([0.9695, 0.2063], abs=1e-3)


def test_constrained_branin_found_in_100_evaluations():
    """TPE (10 Latin-hypercube points, then 90 asked two at a time) ends in the constrained optimum's basin: its
    best feasible point within 0.5 of f* = 0.733 (the three unconstrained minima, 0.398, are all infeasible; the
    other feasible basins lie above 4) and within 0.03 of (0.9695, 0.2063) on the unit square."""
    study, interrupted = run_trials(BRANIN, branin_points, 100, batch=2)
    recs = records(study, BRANIN)
    assert not interrupted and len(recs) == 100
    best = recommend(pareto_front(recs, BRANIN.objectives), BRANIN.objectives)
    assert best.feasible and best.quantities["g"] >= 0.2
    assert best.quantities["f"] - 0.7330 < 0.5
    assert math.hypot(best.params["u"] - 0.9695, best.params["v"] - 0.2063) < 0.03


def binh_korn(points):
    return [Evaluation({"f1": 4 * p["x"] ** 2 + 4 * p["y"] ** 2, "f2": (p["x"] - 5) ** 2 + (p["y"] - 5) ** 2,
                        "g1": (p["x"] - 5) ** 2 + p["y"] ** 2, "g2": (p["x"] - 8) ** 2 + (p["y"] + 3) ** 2})
            for p in points]


def binh_korn_front(n: int = 4001) -> np.ndarray:
    """The Pareto front of Binh & Korn (1997), in closed form: x = y in [0, 3], then y = 3, x in [3, 5]."""
    t, s = np.linspace(0.0, 3.0, n), np.linspace(3.0, 5.0, n)
    return np.vstack([np.column_stack([8 * t ** 2, 2 * (t - 5) ** 2]), np.column_stack([4 * s ** 2 + 36, (s - 5) ** 2 + 4])])


def hypervolume_2d(points: np.ndarray, ref: np.ndarray) -> float:
    h, last = 0.0, ref[1]
    for a, b in points[np.argsort(points[:, 0])]:
        if b < last:
            h += (ref[0] - a) * (last - b)
            last = b
    return h


def test_two_objective_front_found_in_100_evaluations():
    """Binh-Korn (two objectives, two constraints): after 100 evaluations every front point found lies within 0.03
    of the true front (objectives scaled by the front's ranges) and the front covers >= 95 % of the true front's
    hypervolume (reference point (140, 50))."""
    problem = Problem("bk", (Variable("x", 0.0, 5.0), Variable("y", 0.0, 3.0)),
                      (Objective("f1", "min"), Objective("f2", "min")),
                      (Constraint("g1", "<=", 25.0), Constraint("g2", ">=", 7.7)), startup=10, seed=0)
    study, _ = run_trials(problem, binh_korn, 100, batch=2)
    front = pareto_front(records(study, problem), problem.objectives)
    found = np.array([[r.quantities["f1"], r.quantities["f2"]] for r in front])
    true = binh_korn_front()
    scale = np.ptp(true, axis=0)
    distance = [np.min(np.linalg.norm((true - f) / scale, axis=1)) for f in found]
    assert len(found) >= 20 and max(distance) < 0.03
    ref = np.array([140.0, 50.0])
    assert hypervolume_2d(found, ref) / hypervolume_2d(true, ref) > 0.95


def test_interrupted_study_resumes_without_rerunning_finished_trials(tmp_path):
    """Ctrl-C in the third batch: its points are asked again on the next call, no finished point is run again."""
    calls: list[tuple[float, float]] = []
    stop = {"at": 3, "batch": 0}

    def evaluate(points):
        stop["batch"] += 1
        if stop["batch"] == stop["at"]:
            raise KeyboardInterrupt
        calls.extend((p["u"], p["v"]) for p in points)
        return branin_points(points)

    storage = tmp_path / "study.db"
    study, interrupted = run_trials(BRANIN, evaluate, 12, storage=storage, batch=2)
    assert interrupted and evaluated(study) == 4
    lost = [tuple(t.params.values()) for t in study.trials if t.state.name == "FAIL"]
    study, interrupted = run_trials(BRANIN, evaluate, 12, storage=storage, batch=2)
    assert not interrupted and evaluated(study) == 12 and len(calls) == 12
    assert len(set(calls)) == 12                       # nothing evaluated twice
    assert set(lost) <= set(calls)                     # the interrupted batch was asked again


# -- study files ------------------------------------------------------------------------------------------------
def small_ring(path: Path, mechanics: bool = False) -> Path:
    """The small SUJ3 ring of cases/example_sweep_script.py (table HTCs) as a case file, cooled to room temperature."""
    spec = importlib.util.spec_from_file_location("example_sweep_script", ROOT / "cases" / "example_sweep_script.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    case = module.build_case(wall_mm=5.0, mesh_mm=4.0, quench_time_s=20.0, air_time_s=3000.0)
    case["mechanics"] = {"enabled": mechanics}
    case["output"] = {"frames": 2}
    path.write_text(tomli_w.dumps(case))
    return path


STUDY = {"study": {"case": "ring.toml", "trials": 2, "startup": 2, "seed": 3},
         "variables": {"quench": {"time_s": [10.0, 30.0]}},
         "objectives": {"hardness.core_HRC": "max"},
         "constraints": ["hardness.core_HRC >= 67"], "confirm": {"uncertainty": 2}}


def _with(**tables) -> dict:
    study = json.loads(json.dumps(STUDY))
    for key, value in tables.items():
        study[key] = value
    return study


@pytest.mark.parametrize("tables, field, words", [
    ({"variables": {"quench.bath_speed_mm_s": [1.0, 2.0]}}, "variables.quench.bath_speed_mm_s", "unknown key"),
    ({"variables": {"quench.time_s": [-5.0, 30.0]}}, "variables.quench.time_s", "allows: must be > 0"),
    ({"variables": {"quench.time_s": [30.0, 10.0]}}, "variables.quench.time_s", "low must be below high"),
    ({"objectives": {"hardness.core_hrc": "max"}}, "objectives.hardness.core_hrc", "did you mean hardness.core_HRC"),
    ({"objectives": {"dimensions_mm.change.id": "min"}}, "objectives.dimensions_mm.change.id", "not a number"),
    ({"constraints": ["hardness.depth_mm.HRC58_bore_mid >= 6"]}, "constraints", "at most 5.1"),
    ({"constraints": ["hardness.core_HRC >= 70"]}, "constraints", "no run can satisfy it"),
    ({"constraints": ["phases_final.martensite.mean >= 0.8", "phases_final.martensite.mean <= 0.5"]}, "constraints",
     "no run can satisfy both"),
    ({"constraints": ["hardness.core_HRC => 60"]}, "constraints", "QUANTITY >= NUMBER"),
    ({"fidelity": {"mesh": 2.0}}, "fidelity.tolerance", "needs the tolerance"),
    ({"study": {"case": "ring.toml", "map": ["quench.time_s", "x"]}}, "study.map", "two of the numeric variables"),
])
def test_bad_study_files_are_one_line_errors(tmp_path, tables, field, words):
    small_ring(tmp_path / "ring.toml")
    with pytest.raises(InputError) as err:
        parse_study(_with(**tables), tmp_path)
    assert err.value.field == field and words in str(err.value) and "\n" not in str(err.value)


@pytest.mark.slow   # seven small-ring runs: ~40 s on an idle machine, minutes under load
def test_case_study_that_no_run_satisfies_says_so_and_resumes(tmp_path):
    """A thermal-only study whose constraint (core HRC >= 67: within the HRC scale, so not refused) no run meets:
    exit 1, a plain line, the closest run confirmed at the full chain with the priors' bands (two draws), every trial
    in trials.csv; a second call with one trial more runs only that trial (the finished runs are read from the
    cache)."""
    small_ring(tmp_path / "ring.toml")
    (tmp_path / "study.toml").write_text(tomli_w.dumps(STUDY))
    cmd = [sys.executable, "-m", "quenchsim.cli", "optimise", str(tmp_path / "study.toml"), "--out", str(tmp_path / "o"),
           "--workers", "0", "--quiet"]
    first = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert first.returncode == 1, first.stderr
    assert "NO RUN MET THE CONSTRAINTS (hardness.core_HRC >= 67); closest runs:" in first.stdout
    rows = list(csv.DictReader((tmp_path / "o" / "trials.csv").open()))
    assert len(rows) == 2 and all(r["state"] == "ok" and r["feasible"] == "False" for r in rows)
    result = json.loads((tmp_path / "o" / "optimise.json").read_text())
    assert result["constraints_met"] is False and result["closest"][0]["trial"] in (0, 1)
    assert result["confirmations"][0]["role"] == "closest"
    bands = result["confirmations"][0]["uncertainty"]        # two runs with the inputs drawn from the priors
    assert bands["runs"] == 2 and bands["quantities"]["hardness.core_HRC"]["p5"] <= bands["quantities"]["hardness.core_HRC"]["p95"]
    assert "### No run met the constraints" in (tmp_path / "o" / "optimise.md").read_text()
    runs = {p.name: (p / "summary.json").stat().st_mtime_ns for p in (tmp_path / "o" / "runs").iterdir()}
    assert main(["optimise", str(tmp_path / "study.toml"), "--out", str(tmp_path / "o"), "--workers", "0", "--quiet",
                 "--trials", "3"]) == 1
    assert len(list(csv.DictReader((tmp_path / "o" / "trials.csv").open()))) == 3
    after = {p.name: (p / "summary.json").stat().st_mtime_ns for p in (tmp_path / "o" / "runs").iterdir()}
    assert all(after[name] == stamp for name, stamp in runs.items())     # no finished run ran again
    assert len(after) - len(runs) <= 2                                   # the new trial (and a new closest's check)


def test_cli_bad_study_is_one_line_and_exit_2(tmp_path, capsys):
    small_ring(tmp_path / "ring.toml")
    (tmp_path / "study.toml").write_text(tomli_w.dumps(_with(objectives={"hardness.cor_HRC": "max"})))
    assert main(["optimise", str(tmp_path / "study.toml"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "objectives.hardness.cor_HRC" in err
    assert not (tmp_path / "o").exists()                                 # nothing written, nothing run

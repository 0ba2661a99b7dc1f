"""Calibration on every kind of measured datum: cooling curves, a probe order, a hardness traverse, a phase bound and a
dimension, with a model-discrepancy group -- a synthetic problem whose true inputs are known.

A small SUJ3 ring quenched in a slow oil (table; ~2 s a run, the pearlite share at mid-wall 0.07-0.73 over the
pearlite time scale's prior) is run at known inputs (SUJ3's pearlite time scale and the martensite's volume change); its
probes.csv and hardness traverse, with noise, become the "measured" files, its phases and ID change the measured
statements. The calibration must put the true inputs inside the posterior's 90 % bands, pin the pearlite down, meet
every datum, find no conflicting pair and a small discrepancy. Bad data of each kind: one line naming the field.
"""

from __future__ import annotations

import copy
import csv
from pathlib import Path

import numpy as np
import pytest
import tomli_w

from quenchsim.calibration import calibrate, free_input, parse_calibration
from quenchsim.calibration.data import Measurement, Observable, Term, read_term
from quenchsim.calibration.likelihood import Likelihood
from quenchsim.calibration.runs import request, run_requests
from quenchsim.calibration.surrogate import Surrogate
from quenchsim.case import load_case
from quenchsim.errors import InputError
from test_calibration import AIR, OIL

INPUTS = ["material.SUJ3.kinetics.pearlite.tau_ref_s", "material.SUJ3.mechanics.free_strain.volume_change_pct.martensite"]
TRUE_U = np.array([0.35, 0.6])
SLOW_OIL = 0.12
"""The oil table's coefficients x this: the 12 mm wall cools at t500 ~ 41 s, through SUJ3's pearlite nose."""
NOISE = {"K": 2.0, "HRC": 0.5, "mm": 0.002}


def ring_case() -> dict:
    oil = copy.deepcopy(OIL)
    oil["h_W_m2K"] = [SLOW_OIL * h for h in oil["h_W_m2K"]]
    return {"name": "test_ring", "material": "SUJ3",
            "geometry": {"type": "rectangular", "inner_diameter_mm": 40.0, "outer_diameter_mm": 64.0, "width_mm": 12.0,
                         "chamfer_mm": 1.0},
            "mesh": {"size_mm": 3.0, "surface_size_mm": 1.5, "surface_layer_mm": 3.0},
            "quench": {"time_s": 200.0, "htc_model": "table", "htc_table": oil},
            "air": {"until_max_C": 40.0, "time_s": 3000.0, "htc_model": "table", "htc_table": copy.deepcopy(AIR)},
            "output": {"frames": 2},
            "probes": [{"name": "bore", "r_mm": 21.0, "z_mm": 6.0}, {"name": "mid", "r_mm": 26.0, "z_mm": 6.0},
                       {"name": "od", "r_mm": 31.0, "z_mm": 6.0}]}


def measured_files(folder: Path, truth_run: Path, rng: np.random.Generator) -> None:
    """The truth run's cooling curves (every 4th row, +- 2 K) and hardness at four depths (+- 0.5 HRC) as the
    'measured' CSVs of the calibration file."""
    with (truth_run / "probes.csv").open() as fh:
        rows = list(csv.DictReader(fh))[::4]
    with (folder / "thermocouples.csv").open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time_s", "bore", "od"])
        for r in rows:
            w.writerow([r["time_s"], float(r["bore_C"]) + NOISE["K"] * rng.standard_normal(),
                        float(r["od_C"]) + NOISE["K"] * rng.standard_normal()])
    lines = ["depth_mm,HRC"]
    for depth in (1.0, 3.0, 6.0, 9.0):
        hrc = read_term({}, truth_run, f"traverse.bore@{depth:g}")
        assert hrc is not None
        lines.append(f"{depth:g},{hrc + NOISE['HRC'] * rng.standard_normal():.3f}")
    (folder / "hardness.csv").write_text("\n".join(lines) + "\n")


def cal_table(truth: dict) -> dict:
    source = "synthetic: the run at known inputs, with noise"
    return {
        "name": "synthetic_all_kinds", "inputs": list(INPUTS), "cases": {"ring": {"file": "ring.toml"}},
        "measurements": [
            {"kind": "curve", "case": "ring", "file": "thermocouples.csv", "temperatures_C": [700, 600, 500, 400, 300],
             "uncertainty_K": NOISE["K"], "source": source},
            {"kind": "order", "case": "ring", "quantity": "t_to_500C_s", "probes": truth["order"], "tolerance": 0.3,
             "source": source},
            {"kind": "traverse", "case": "ring", "file": "hardness.csv", "side": "bore", "uncertainty": NOISE["HRC"],
             "source": source},
            {"kind": "bound", "case": "ring", "quantity": "probes.mid.phases.pearlite", "min": truth["pearlite"] - 0.1,
             "max": truth["pearlite"] + 0.1, "uncertainty": 0.03, "source": source},
            {"case": "ring", "quantity": "dimensions_mm.change.id", "value": truth["id"], "uncertainty": NOISE["mm"],
             "source": source}],
        "discrepancy": {"probes": {"scale": 0.5, "unit": "s", "reason": "synthetic: the model is exact"}},
        "design": {"screening_trajectories": 2, "training_runs": 10, "holdout_runs": 3, "seed": 5, "refine_waves": 1,
                   "refine_runs": 4},
        "sampler": {"walkers": 12, "steps": 1000, "burn": 300}}


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory):
    folder = tmp_path_factory.mktemp("calibration_data")
    (folder / "ring.toml").write_text(tomli_w.dumps(ring_case()))
    inputs = [free_input(p) for p in INPUTS]
    true_factors = [inp.factor(u) for inp, u in zip(inputs, TRUE_U)]
    req = request(load_case(folder / "ring.toml"), inputs, true_factors)
    done = run_requests([req], folder / "truth", workers=0, progress=False)
    summary, run_dir = done.summaries[req.folder_name()], folder / "truth" / req.folder_name()
    rng = np.random.default_rng(7)
    measured_files(folder, run_dir, rng)
    times = {p: summary["probes"][p]["t_to_500C_s"] for p in ("bore", "mid", "od")}
    truth = {"order": sorted(times, key=times.get), "pearlite": summary["probes"]["mid"]["phases"]["pearlite"],
             "id": summary["dimensions_mm"]["change"]["id"] + NOISE["mm"] * rng.standard_normal()}
    spec = parse_calibration(cal_table(truth), folder)
    result = calibrate(spec, folder / "out", workers=0, progress=False)
    return {"spec": spec, "result": result, "truth": truth, "summary": summary}


def test_every_kind_becomes_its_observables(synthetic):
    spec = synthetic["spec"]
    kinds = {m.kind: len(m.observables) for m in spec.measurements}
    assert kinds == {"curve": 10, "order": 2, "traverse": 4, "bound": 1, "value": 1}
    curve = spec.measurements[0].observables
    assert curve[0].label == "ring/-:probes.bore.t_to_C_s.700" and curve[0].sd > 0
    # the measured crossing lies within a few sd of the truth run's own
    for o in curve:
        probe, T = o.terms[0].path.split(".")[1], o.terms[0].path.split(".")[-1]
        assert abs(o.value - synthetic["summary"]["probes"][probe]["t_to_C_s"][T]) < 4 * o.sd + 0.2


def test_true_inputs_recovered_within_the_posterior_bands(synthetic):
    result = synthetic["result"]
    assert result["status"] == "ok"
    inputs = [free_input(p) for p in INPUTS]
    for row, inp, u in zip(result["posterior"], inputs, TRUE_U):
        truth = inp.factor(u)
        assert row["factor_5pct"] <= truth <= row["factor_95pct"], (row["input"], truth, row)
    # the phases and the hardness pin the pearlite down; the ID (+- 2 um) moves 5 um over the volume's whole prior
    assert result["posterior"][0]["width_ratio"] < 0.5, result["posterior"][0]


def test_every_datum_met_no_pair_conflicts_and_a_small_discrepancy(synthetic):
    result = synthetic["result"]
    assert all(row["reached"] for row in result["predictive_check"]), result["predictive_check"]
    assert all(row["met"] for row in result["calibrated_run"].values()), result["calibrated_run"]
    assert result["conflicts"] and not any(c["conflict"] for c in result["conflicts"])
    assert all(p["met_alone"] for p in result["pulls"])
    (disc,) = result["discrepancy"]
    assert disc["group"] == "probes" and disc["median"] < 0.6745 * 0.5 * 1.5
    page = (Path(result["calibrated_files"]["material"]).parents[1] / "calibration.md").read_text()
    for heading in ("## Model discrepancy", "## Which data pull which inputs where", "## Which data conflict"):
        assert heading in page


def _write(folder: Path) -> None:
    (folder / "ring.toml").write_text(tomli_w.dumps(ring_case()))
    (folder / "tc.csv").write_text("time_s,bore_C\n0,845\n10,600\n20,450\n40,300\n")
    (folder / "hv.csv").write_text("depth_mm,HRC\n1,60\n5,55\n")


BASE = {"case": "ring", "source": "s"}


@pytest.mark.parametrize("datum, field, message", [
    ({"kind": "curve", "file": "tc.csv", "uncertainty_K": 2.0, "temperatures_C": [550]}, "temperatures_C", "some of"),
    ({"kind": "curve", "file": "nope.csv", "uncertainty_K": 2.0}, "file", "file not found"),
    ({"kind": "curve", "file": "tc.csv", "uncertainty_K": 2.0, "probes": ["od"]}, "probes", "no column"),
    ({"kind": "curve", "file": "tc.csv"}, "uncertainty_K", "required"),
    ({"kind": "traverse", "file": "hv.csv", "side": "middle", "uncertainty": 1.0}, "side", "bore, od"),
    ({"kind": "order", "quantity": "t_to_500C_s", "probes": ["bore"], "tolerance": 1.0}, "probes", "at least 2"),
    ({"kind": "order", "quantity": "t_to_500C_s", "probes": ["bore", "P9"], "tolerance": 1.0}, "probes", "not probes"),
    ({"kind": "bound", "quantity": "probes.mid.phases.pearlite", "uncertainty": 0.1}, "min", "min and/or max"),
    ({"kind": "bound", "quantity": "probes.mid.phases.pearlite", "min": 0.6, "max": 0.5, "uncertainty": 0.1}, "max",
     "must exceed min"),
    ({"kind": "depth", "side": "bore", "value": 2.0, "tolerance": 3.0, "uncertainty": 0.5}, "tolerance", "below the depth"),
    ({"quantity": "dimensions_mm.change.id", "value": 0.1, "uncertainty": 0.01, "relation": "ratio"}, "relation",
     "relative_to"),
    ({"kind": "spline", "quantity": "dimensions_mm.change.id"}, "kind", "must be one of"),
    ({"quantity": "dimensions_mm.change.id", "value": 0.1, "uncertainty": 0.01, "tolerance": 1.0}, "measurements[0]",
     "allowed keys"),
])
def test_bad_datum_of_each_kind_is_one_line_naming_the_field(tmp_path, datum, field, message):
    _write(tmp_path)
    table = {"name": "bad", "inputs": INPUTS[:1], "cases": {"ring": {"file": "ring.toml"}},
             "measurements": [{**BASE, **datum}]}
    with pytest.raises(InputError) as err:
        parse_calibration(table, tmp_path)
    assert field in str(err.value) and message in str(err.value) and "\n" not in str(err.value)


def test_a_discrepancy_group_no_datum_is_in_is_refused(tmp_path):
    _write(tmp_path)
    table = {"name": "bad", "inputs": INPUTS[:1], "cases": {"ring": {"file": "ring.toml"}},
             "measurements": [{**BASE, "quantity": "dimensions_mm.change.id", "value": 0.1, "uncertainty": 0.01}],
             "discrepancy": {"probes": {"scale": 1.0, "reason": "r"}}}
    with pytest.raises(InputError, match="no measurement is in this group"):
        parse_calibration(table, tmp_path)


def test_depth_becomes_two_bounds_on_the_traverse(tmp_path):
    _write(tmp_path)
    table = {"name": "d", "inputs": INPUTS[:1], "cases": {"ring": {"file": "ring.toml"}},
             "measurements": [{**BASE, "kind": "depth", "side": "bore", "value": 5.0, "tolerance": 1.0,
                               "uncertainty": 0.5}]}
    (m,) = parse_calibration(table, tmp_path).measurements
    (a, b) = m.observables
    assert (a.terms[0].path, a.lower, a.upper) == ("traverse.bore@4", 58.0, None)
    assert (b.terms[0].path, b.lower, b.upper) == ("traverse.bore@6", None, 58.0)


class _Constant:
    """A 'surrogate' of one observable: mean m, sd s everywhere."""

    def __init__(self, m: float, s: float) -> None:
        self.m, self.s = m, s

    def predict(self, u, return_std=False):
        n = np.atleast_2d(u).shape[0]
        return (np.full(n, self.m), np.full(n, self.s)) if return_std else np.full(n, self.m)


def test_likelihood_terms_are_the_gaussian_and_the_probit_with_the_discrepancy_added():
    from scipy.stats import norm

    value = Observable("v", (Term("c", None, "x"),), value=1.0, sd=0.3, group="g")
    bound = Observable("b", (Term("c", None, "y"),), lower=2.0, sd=0.4, group="g")
    lk = Likelihood(Surrogate({"v": _Constant(1.5, 0.1), "b": _Constant(1.8, 0.2)}, 1), (value, bound), ("g",))
    u, delta = np.zeros((1, 1)), np.array([[0.5]])
    terms = lk.terms(u, delta)[0]
    assert terms[0] == pytest.approx(norm.logpdf(1.0, 1.5, np.sqrt(0.3**2 + 0.1**2 + 0.5**2)))
    assert terms[1] == pytest.approx(norm.logcdf((1.8 - 2.0) / np.sqrt(0.4**2 + 0.2**2 + 0.5**2)))
    assert lk.misfit(u)[0] == pytest.approx(0.5**2 / 0.1 - 2 * norm.logcdf(-0.2 / np.sqrt(0.2)))


def test_the_guides_example_reads_and_holds_every_kind():
    """docs/guide/calibrate_example: the calibration file the guide runs loads with all its data files."""
    from quenchsim.calibration import load_calibration

    folder = Path(__file__).resolve().parents[1] / "docs" / "guide" / "calibrate_example"
    spec = load_calibration(folder / "ring.cal.toml")
    assert {m.kind for m in spec.measurements} == {"curve", "order", "traverse", "bound", "value"}
    assert len(spec.observables) == 18 and [g.name for g in spec.discrepancy] == ["probes"]


def test_the_fast_prediction_is_scikit_learns():
    """FastGP (Rasmussen & Williams, Algorithm 2.1 with the Matern 5/2 kernel) predicts what scikit-learn's fitted
    GaussianProcessRegressor predicts, mean and standard deviation."""
    from quenchsim.calibration.surrogate import fit_surrogate

    rng = np.random.default_rng(0)
    u = rng.uniform(size=(40, 4))
    y = 3.0 + 2.0 * np.sin(u @ np.array([2.0, -1.0, 0.5, 3.0])) + 0.1 * u[:, 0] ** 3
    model = fit_surrogate(u, {"y": y}, seed=1).models["y"]
    at = rng.uniform(size=(25, 4))
    mean, sd = model.predict(at, return_std=True)
    ref_mean, ref_sd = model.fitted.predict(at, return_std=True)
    np.testing.assert_allclose(mean, ref_mean, rtol=0, atol=1e-10)
    np.testing.assert_allclose(sd, ref_sd, rtol=0, atol=1e-10)
    assert np.all(sd > 0) and np.max(np.abs(model.predict(u) - y)) < 0.05   # it interpolates its training data


def _measurement(label: str, observable: Observable) -> Measurement:
    return Measurement(kind="value", case="r", condition="1", label=label, source="test", group=None,
                       observables=(observable,))


def test_meets_is_within_two_sd_of_a_value_and_not_beyond_a_bound_by_more():
    """A value datum 1.0 +- 0.1 is met at 0.8 and 1.2 (2 sd) and not at 0.79; a bound >= 0 soft by 0.5 is met down
    to -1.0; a missing or non-finite run value never meets."""
    from quenchsim.calibration.conflicts import meets
    term = (Term("r", "1", "x"),)
    value = Observable("v", term, value=1.0, sd=0.1)
    assert meets(value, 0.8 + 1e-12) and meets(value, 1.2 - 1e-12) and not meets(value, 0.79) and not meets(value, 1.21)
    bound = Observable("b", term, lower=0.0, sd=0.5)
    assert meets(bound, -1.0) and meets(bound, 100.0) and not meets(bound, -1.01)
    both = Observable("w", term, lower=4.0, upper=6.0, sd=0.5)
    assert meets(both, 6.99) and not meets(both, 7.01) and not meets(both, 2.99)
    assert not meets(value, None) and not meets(value, float("nan"))


def test_cosatisfaction_counts_each_datum_each_pair_and_all_together():
    """Three runs, two data (a = 0 +- 1, b = 10 +- 1): run 1 meets both, run 2 only a, run 3 neither: per datum 2
    and 1, the pair 1, all 1, the best run first with nothing missed."""
    from quenchsim.calibration.conflicts import cosatisfaction
    a = _measurement("a", Observable("a", (Term("r", "1", "a"),), value=0.0, sd=1.0))
    b = _measurement("b", Observable("b", (Term("r", "1", "b"),), value=10.0, sd=1.0))
    runs = [{"a": 0.5, "b": 9.0}, {"a": -1.5, "b": 20.0}, {"a": 5.0, "b": None}]
    out = cosatisfaction([a, b], runs, [[1.0], [2.0], [3.0]], best=2)
    assert out["per_datum"] == {"a": 2, "b": 1} and out["all"] == 1 and out["most"] == 2 and out["runs"] == 3
    assert out["pairs"] == [{"a": "a", "b": "b", "runs_a": 2, "runs_b": 1, "runs_both": 1}]
    assert out["best_runs"][0] == {"met": 2, "missed": [], "factors": [1.0]}
    assert out["best_runs"][1]["missed"] == ["b"]


def test_spread_subset_takes_the_farthest_points_first():
    """From a unit square's corners and its centre, 5 points: the centre first (nearest the median), then the four
    corners; a subset is drawn from the samples and is the same for the same seed."""
    from quenchsim.calibration.design import spread_subset
    samples = np.array([[0.5, 0.5], [0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [0.45, 0.5], [0.5, 0.55]])
    chosen = spread_subset(samples, 5, seed=1)
    assert np.allclose(chosen[0], [0.5, 0.5])
    assert {tuple(p) for p in chosen[1:]} == {(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)}
    rng = np.random.default_rng(3)
    many = rng.random((5000, 3))
    assert np.array_equal(spread_subset(many, 8, seed=4), spread_subset(many, 8, seed=4))
    assert all(any(np.array_equal(p, q) for q in many) for p in spread_subset(many, 8, seed=4))

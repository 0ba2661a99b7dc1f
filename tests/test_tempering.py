"""The [temper] stage and the tempering model (issue 45): the clock's additivity and its closed form, the processes
through their published points, bad tempering input refused in one line before any work, a small ring quenched and
tempered (both states in summary.json, the run table and the files), and `quenchsim stability` on it."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys

import numpy as np
import pytest

import quenchsim as qs
from quenchsim.case import case_from_dict
from quenchsim.commands.run import summary_table
from quenchsim.commands.stability import stability
from quenchsim.errors import InputError
from quenchsim.materials import load_material, materials_dir
from quenchsim.metallurgy import load_kinetics, load_tempering
from quenchsim.metallurgy.tempering import hollomon_jaffe_advance, isothermal_hold, jmak_through
from quenchsim.results import files
from test_run_resume import plastic_ring


@pytest.fixture(scope="module")
def tempering():
    material = load_material("SUJ3")
    return load_tempering(material, load_kinetics(material, 845.0))


def test_the_clock_of_an_isothermal_hold_is_hollomon_jaffe_in_any_steps(tempering):
    C = tempering.clock_constant
    P = np.zeros(3)
    for dt in (1.0, 10.0, 100.0, 3600.0, 3489.0):   # 2 h in unequal steps at 180 C
        P = hollomon_jaffe_advance(P, 180.0, 180.0, dt, C)
    assert P == pytest.approx((180.0 + 273.15) * (C + math.log10(2.0)), rel=1e-6)
    assert isothermal_hold(tempering, 0.0, 180.0, 2.0) == pytest.approx(P[0], rel=1e-6)


def test_a_process_passes_through_its_two_points():
    process = jmak_through([(100.0, 1.0, 0.05), (250.0, 2.0, 0.95)], 15.5, "test")
    for T, t, x in ((100.0, 1.0, 0.05), (250.0, 2.0, 0.95)):
        assert float(process.progress((T + 273.15) * (15.5 + math.log10(t)))) == pytest.approx(x, rel=1e-9)


def _case(temper: dict | None = None, material: str | None = None) -> dict:
    data = plastic_ring()
    if temper is not None:
        data["temper"] = temper
    if material is not None:
        data["material"] = material
    return data


@pytest.mark.parametrize("temper, message", [
    ({"temperature_C": 900.0, "time_s": 7200.0},
     "temper.temperature_C = 900.0: must be below the austenitising temperature"),
    ({"temperature_C": 180.0, "time_s": -60.0}, "temper.time_s = -60.0: must be > 0 s"),
    ({"temperature_C": 500.0, "time_s": 7200.0}, "temper.temperature_C = 500.0: must lie above the room temperature"),
    ({"temperature_C": 180.0, "time_s": 7200.0, "durartion_s": 1.0}, "temper"),
])
def test_bad_tempering_input_is_one_line_before_any_work(temper, message):
    with pytest.raises(InputError) as err:
        case_from_dict(_case(temper))
    assert str(err.value).startswith(message) and "\n" not in str(err.value)


def test_a_steel_without_tempering_data_is_refused_when_the_case_loads(tmp_path):
    steel = (materials_dir() / "SUJ3.toml").read_text().replace('tempering = "data/tempering_1C_Cr.toml"', "")
    (tmp_path / "bare.toml").write_text(steel.replace('name = "SUJ3"', 'name = "bare"'))
    shutil.copy(materials_dir() / "SUJ3.mechanics.toml", tmp_path / "bare.mechanics.toml")
    case_from_dict(_case(material=str(tmp_path / "bare.toml")))          # quenching it is fine
    with pytest.raises(InputError, match="has no tempering data"):
        case_from_dict(_case({"temperature_C": 180.0, "time_s": 7200.0}, str(tmp_path / "bare.toml")))


def test_a_case_without_a_temper_resolves_as_before():
    case = case_from_dict(_case())
    assert case.temper is None and "temper" not in case.data


@pytest.fixture(scope="module")
def tempered_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("tempered")
    case = case_from_dict(_case({"temperature_C": 180.0, "time_s": 7200.0}))
    return qs.run(case, out, progress=False)


def test_the_tempered_ring_keeps_both_states(tempered_run):
    s = tempered_run.summary
    t = s["tempered"]
    assert s["status"] == "ok" and t["temper"]["temperature_C"] == 180.0
    assert t["hardness"]["core_HRC"] < s["hardness"]["core_HRC"] - 1.0      # tempered martensite is softer
    assert t["phases_final"]["austenite"]["mean"] < s["phases_final"]["austenite"]["mean"]
    for where, hoop in s["residual_stress_MPa"]["hoop"].items():             # the relaxation lowers the stress
        assert abs(t["residual_stress_MPa"]["hoop"][where]) < abs(hoop)
    assert "tempering_relaxation" in t["tempering_budget_mm"]
    for k, change in t["change_by_temper_mm"].items():
        assert change == pytest.approx(t["dimensions_mm"]["after"][k] - s["dimensions_mm"]["after"][k], abs=1e-12)
    budget = t["distortion_budget_mm"]
    assert sum(p["od"] for p in budget["parts"].values()) == pytest.approx(budget["total"]["od"], abs=2e-4)
    for name in (files.HARDNESS_TRAVERSE_CSV, files.RESIDUAL_TRAVERSE_CSV, files.OUTLINE_CSV):
        assert (tempered_run.out_dir / name).is_file()
        assert (tempered_run.out_dir / (files.TEMPERED_PREFIX + name)).is_file()
    table = summary_table(s, tempered_run.out_dir)
    assert "temper 180 C, 2 h in the furnace" in table and "retained austenite (mean)" in table


def test_stability_of_the_tempered_ring(tempered_run, tempering):
    none = stability(tempered_run.out_dir, 120.0, 1e-12)
    assert abs(none["strain_ppm"]["total"]) < 1e-6
    long = stability(tempered_run.out_dir, 170.0, 1e4)      # the austenite's decomposition runs to its end
    assert long["retained_austenite"]["after"] == pytest.approx(0.0, abs=2e-3)
    assert long["strain_ppm"]["austenite_decomposition"] > 0.0
    one = stability(tempered_run.out_dir, 120.0, 10.0)
    assert 0.0 < one["retained_austenite"]["after"] < one["retained_austenite"]["before"]
    ratio = one["dimension_change_mm"]["od"] / one["dimension_change_mm"]["id"]
    assert ratio == pytest.approx(50.0 / 40.0, rel=0.01)   # one uniform strain times each dimension


def test_stability_refuses_a_hold_hotter_than_the_temper(tempered_run):
    proc = subprocess.run([sys.executable, "-m", "quenchsim.cli", "stability", str(tempered_run.out_dir),
                           "--temperature-C", "200", "--years", "1"], capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stderr.strip().count("\n") == 0
    assert "--temperature-C = 200.0" in proc.stderr
    ok = subprocess.run([sys.executable, "-m", "quenchsim.cli", "stability", str(tempered_run.out_dir),
                         "--temperature-C", "100", "--years", "2", "--json"], capture_output=True, text=True)
    assert ok.returncode == 0 and json.loads(ok.stdout)["years"] == 2.0

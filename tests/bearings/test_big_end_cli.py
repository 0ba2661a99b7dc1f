"""`quenchsim bearings big-end` CLI: JSON keys of a short run, and clear errors for bad inputs."""

import json
import re
from pathlib import Path

import pytest

from quenchsim.bearings.big_end.case import load_case
from quenchsim.cli import main
from quenchsim.errors import InputError

CASE = Path(__file__).resolve().parents[2] / "cases" / "big_end_two_stroke.toml"
RIG = Path(__file__).resolve().parents[2] / "cases" / "big_end_rig.toml"


def test_cli_short_engine_run_prints_statistics(capsys, tmp_path):
    code = main(["bearings", "big-end", str(CASE), "--clearance-set", "2", "--revolutions", "0.05",
                 "--out", str(tmp_path), "--json"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out["cage_slip_pct"]) == {"mean_abs", "min", "max"}
    assert set(out["pocket_force_N"]) == {"max", "mean_abs"}
    for key in ("roller_orbital_slip_mean_abs_pct", "roller_spin_slip_mean_abs_pct", "revolutions", "wall_time_s"):
        assert key in out
    assert out["revolutions"] == 0.05
    assert out["cage_slip_pct"]["min"] <= out["cage_slip_pct"]["max"]
    assert Path(out["csv"]).is_file() and Path(out["plot"]).is_file()


def test_rig_case_file_loads_both_table1_cases():
    case = load_case(RIG)
    assert len(case.clearance_sets) == 2
    assert case.clearance_sets[0].radial == pytest.approx(-7e-6)
    assert case.clearance_sets[1].load_n == pytest.approx(3000.0)
    assert case.operations["rig"].cage_unbalance_kg_m == pytest.approx(13.0e-6)


def _edited(tmp_path, old, new, source=CASE):
    text = source.read_text()
    assert re.search(old, text, flags=re.M)
    path = tmp_path / "case.toml"
    path.write_text(re.sub(old, new, text, count=1, flags=re.M))
    return path


@pytest.mark.parametrize("old,new,field", [
    (r"^roller_diameter_mm = 2.999", "roller_diameter_mm = 11.0", "bearing.roller_diameter_mm"),
    (r"^guide_mm = 0.20", "guide_mm = -0.20", "clearance_set[1].guide_mm"),     # arrays count from 0, as every
    (r"^pocket_mm = 0.10", "pocket_mm = -0.05", "clearance_set[0].pocket_mm"),  # input file's
    (r"^radial_mm = 0.030", "radial_mm = -0.5", "clearance_set[2].radial_mm"),
    (r"^n_rollers = 11", "n_rollers = 0", "bearing.n_rollers"),
    (r"^n_rollers = 11", "n_rollers = 40", "bearing.n_rollers"),
    (r'^oil = "engine_oil_sae30"', 'oil = "castor_bean"', "lubrication.oil"),
    (r"^width_mm = 9.8", "width_mm = 7.0", "bearing.width_mm"),
])
def test_bad_inputs_give_one_line_errors(tmp_path, capsys, old, new, field):
    path = _edited(tmp_path, old, new)
    with pytest.raises(InputError) as err:
        load_case(path)
    assert err.value.field == field and str(err.value).startswith(f"{path}: {field}")   # the file, then the key
    assert main(["bearings", "big-end", str(path), "--json"]) == 2
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and field in captured.err


def test_unknown_oil_exit_code(tmp_path, capsys):
    path = _edited(tmp_path, r'^oil = "engine_oil_sae30"', 'oil = "castor_bean"')
    assert main(["bearings", "big-end", str(path), "--json"]) == 2
    err = capsys.readouterr().err
    assert "lubrication.oil" in err and "engine_oil_sae30" in err


def test_missing_mode_section_and_clearance_set(capsys):
    assert main(["bearings", "big-end", str(CASE), "--mode", "rig", "--json"]) == 2
    assert "mode" in capsys.readouterr().err
    assert main(["bearings", "big-end", str(CASE), "--clearance-set", "7", "--json"]) == 2
    assert "clearance_set" in capsys.readouterr().err


@pytest.mark.parametrize("case,mode,set_number", [(CASE, "static", "2"), (RIG, "rig", "1")])
def test_cli_static_and_rig_modes(capsys, case, mode, set_number):
    code = main(["bearings", "big-end", str(case), "--mode", mode, "--clearance-set", set_number,
                 "--revolutions", "0.05", "--json"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["mode"] == mode and out["integrator"] == "LSODA"
    assert out["pocket_force_N"]["max"] >= out["pocket_force_N"]["mean_abs"] >= 0.0

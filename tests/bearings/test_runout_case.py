"""Run-out case files: bad inputs give one-line errors naming the key; the CLI verb end to end."""

from __future__ import annotations

import copy
import json
import math
import pathlib

import numpy as np
import pytest

from quenchsim.bearings.runout import parse_case
from quenchsim.bearings.runout.contact_angle import free_contact_angle_rad, loaded_contact_angle_rad
from quenchsim.bearings.runout.hertz3d import hertz_constant_N_m15
from quenchsim.cli import main
from quenchsim.errors import InputError

CASES = pathlib.Path(__file__).resolve().parents[2] / "cases"
BASE = {
    "model": "linear2d",
    "bearing": {"pitch_diameter_mm": 9.0, "ball_diameter_mm": 2.0, "balls": 8, "contact_angle_deg": 19.8},
    "operation": {"rotating": "inner", "speed_rpm": 1800, "axial_load_N": 7.8, "revolutions": 10, "step_deg": 1.0},
}


def _with(path, value):
    data = copy.deepcopy(BASE)
    *head, last = path
    node = data
    for key in head:
        node = node[key]
    if value is None:
        del node[last]
    else:
        node[last] = value
    return data


@pytest.mark.parametrize("path, value, field", [
    (("bearing", "ball_diameter_mm"), 9.0, "bearing.ball_diameter_mm"),
    (("bearing", "ball_diameter_mm"), 12.0, "bearing.ball_diameter_mm"),
    (("bearing", "balls"), 0, "bearing.balls"),
    (("bearing", "balls"), 2, "bearing.balls"),
    (("bearing", "balls"), 20, "bearing.balls"),          # 20 balls of 2 mm do not fit on 9 mm
    (("bearing", "balls"), 8.5, "bearing.balls"),
    (("bearing", "contact_angle_deg"), 0.0, "bearing.contact_angle_deg"),
    (("bearing", "inner_groove_radius_ratio"), 0.49, "bearing.inner_groove_radius_ratio"),
    (("bearing", "poisson"), 0.6, "bearing.poisson"),
    (("bearing", "pitch_diamter_mm"), 9.0, "bearing.pitch_diamter_mm"),   # misspelt key
    (("operation", "rotating"), "cage", "operation.rotating"),
    (("operation", "speed_rpm"), -5.0, "operation.speed_rpm"),
    (("operation", "axial_load_N"), 0.0, "operation.axial_load_N"),
    (("operation", "step_deg"), 90.0, "operation.samples"),
    (("model",), "dynamic", "model"),
])
def test_bad_bearing_and_operation_inputs(path, value, field):
    with pytest.raises(InputError) as err:
        parse_case(_with(path, value))
    assert err.value.field == field
    assert str(err.value).startswith(f"{field} = ")


@pytest.mark.parametrize("row, field", [
    ({"part": "inner", "order": 0, "amplitude_um_pp": 0.1}, "waviness[0].order"),
    ({"part": "inner", "order": -3, "amplitude_um_pp": 0.1}, "waviness[0].order"),
    ({"part": "inner", "order": 2.5, "amplitude_um_pp": 0.1}, "waviness[0].order"),
    ({"part": "cage", "order": 2, "amplitude_um_pp": 0.1}, "waviness[0].part"),
    ({"part": "ball", "order": 2, "amplitude_um_pp": 0.1, "ball": 8}, "waviness[0].ball"),
    ({"part": "inner", "order": 2, "amplitude_um_pp": -0.1}, "waviness[0].amplitude_um_pp"),
    ({"part": "inner", "order": 400, "amplitude_um_pp": 0.1}, "waviness[0].order"),   # above Nyquist
])
def test_bad_waviness(row, field):
    data = copy.deepcopy(BASE)
    data["waviness"] = [row]
    with pytest.raises(InputError) as err:
        parse_case(data)
    assert err.value.field == field


def test_linear_spring_only_for_the_linear_model():
    data = copy.deepcopy(BASE)
    data["model"] = "hertz3d"
    data["bearing"]["ball_spring_N_per_m"] = 1e7
    with pytest.raises(InputError, match="only for model = 'linear2d'"):
        parse_case(data)


def test_clearance_inputs():
    data = _with(("bearing", "contact_angle_deg"), None)
    # -50e-6 m * 1e6 is -49.99999999999999 in floating point: the message must show what was typed
    data["bearing"]["radial_clearance_um"] = -50.0
    with pytest.raises(InputError, match="bearing.radial_clearance_um = -50.0: must be >= 0"):
        parse_case(data)
    data["bearing"]["radial_clearance_um"] = 500.0     # 2 B D = 100 um for f = 0.52 / 0.53, D = 2 mm
    with pytest.raises(InputError, match="radial_clearance_um"):
        parse_case(data)
    both = copy.deepcopy(BASE)
    both["bearing"]["radial_clearance_um"] = 10.0
    with pytest.raises(InputError, match="exactly one"):
        parse_case(both)


def test_loaded_contact_angle_from_clearance():
    """Free angle: cos a0 = 1 - Pd/(2 B D); loaded angle: Harris' thrust-load equation holds."""
    D, dm, fi, fo, E, nu, Z, Fa = 1e-3, 7e-3, 0.52, 0.53, 2.08e11, 0.3, 8, 20.0
    a0 = free_contact_angle_rad(10e-6, D, fi, fo)
    assert math.cos(a0) == pytest.approx(1.0 - 10e-6 / (2 * 0.05 * D), rel=1e-12)
    a = loaded_contact_angle_rad(a0, Fa, Z, D, dm, fi, fo, E, nu)
    assert a > a0
    data = {"model": "hertz3d", "bearing": {"pitch_diameter_mm": 7.0, "ball_diameter_mm": 1.0, "balls": Z,
                                            "radial_clearance_um": 10.0},
            "operation": {"rotating": "outer", "speed_rpm": 5400, "axial_load_N": Fa, "revolutions": 72,
                          "samples": 4096}}
    case = parse_case(data)
    K = hertz_constant_N_m15(case)
    lhs = Fa / (Z * K * (0.05 * D) ** 1.5)
    assert math.sin(a) * (math.cos(a0) / math.cos(a) - 1.0) ** 1.5 == pytest.approx(lhs, rel=1e-8)
    assert case.contact_angle_rad == pytest.approx(a, rel=1e-12)


def test_cli_json_and_outputs(tmp_path, capsys):
    out = tmp_path / "out"
    code = main(["bearings", "runout", str(CASES / "runout_695_inner9.toml"), "--out", str(out), "--json"])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "linear2d"
    assert set(data["runout_um_pp"]) == {"radial", "axial"}
    top = data["peaks"][0]
    assert set(top) >= {"direction", "frequency_hz", "order_per_rev", "amplitude_um_pp", "source"}
    # inner 9 lobes, 0.1 um p-p: radial 0.1 um at 8 f_i + f_r (ratio 1); one ball 0.01 um larger: 4/Z x 0.01 at f_c
    radial = {p["source"]: p["amplitude_um_pp"] for p in data["peaks"] if p["direction"] == "radial"}
    assert radial["8 f_i + f_r"] == pytest.approx(0.1, rel=2e-3)
    assert radial["f_c"] == pytest.approx(0.04 * 0.01 / 0.08, rel=2e-3)
    csv = np.loadtxt(data["trajectory_csv"], delimiter=",", skiprows=1)
    assert csv.shape == (3600, 4)
    assert all(pathlib.Path(p).is_file() for p in data["plots"])
    spec = np.loadtxt(data["spectra_csv"][0], delimiter=",", skiprows=1)
    assert spec.shape == (1801, 4)


def test_cli_without_out_writes_under_runs(tmp_path, monkeypatch, capsys):
    """Without --out the verb wrote a runout_<stem> folder into the current directory (issue 36)."""
    monkeypatch.chdir(tmp_path)
    assert main(["bearings", "runout", str(CASES / "runout_695_inner9.toml"), "--json", "--no-plots"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [p.name for p in tmp_path.iterdir()] == ["runs"]
    assert pathlib.Path(data["trajectory_csv"]).parent == pathlib.Path("runs") / "runout_695_inner9"


def test_cli_bad_input_exit_2(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text((CASES / "runout_695_inner9.toml").read_text().replace("balls = 8", "balls = 0"))
    assert main(["bearings", "runout", str(bad), "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bearing.balls = 0" in err[0]
    assert main(["bearings", "runout", str(tmp_path / "missing.toml"), "--json"]) == 2


@pytest.mark.parametrize("path", sorted(CASES.glob("runout_*.toml")), ids=lambda p: p.name)
def test_example_cases_run(path):
    from quenchsim.bearings.runout import load_case, run

    result = run(load_case(path))
    assert result.peaks and all(p.source != "unmatched" for p in result.peaks)

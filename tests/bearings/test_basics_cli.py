"""CLI verbs grease-life, kinematics, hertz, free-run: JSON output and one-line errors (exit 2)."""

import json
import math

import numpy as np
import pytest

from quenchsim.bearings import free_run as fr
from quenchsim.cli import main


def _run(capsys, *argv):
    code = main(["bearings", *argv, "--json"])
    out, err = capsys.readouterr()
    return code, (json.loads(out) if code == 0 else None), err


def test_grease_life_cli(capsys):
    code, inner, _ = _run(capsys, "grease-life", "--grease", "urea", "--base-oil", "mineral", "--bearing", "6204",
                          "--speed", "10000", "--temperature", "150", "--load-ratio", "0.016")
    assert code == 0 and inner["K"] == 1.0 and inner["dmN"] == pytest.approx(335000.0)
    assert inner["within_validity"] is True and inner["warnings"] == []
    code, outer, _ = _run(capsys, "grease-life", "--grease", "urea", "--base-oil", "mineral", "--bearing", "6204",
                          "--speed", "10000", "--outer-ring-rotation", "--temperature", "150", "--load-ratio", "0.016")
    assert outer["L50_h"] / inner["L50_h"] == pytest.approx(0.39, abs=0.015)
    assert outer["within_validity"] is False and any("K*dmN" in w for w in outer["warnings"])
    code, dm, _ = _run(capsys, "grease-life", "--grease", "lithium", "--base-oil", "ester", "--dm", "33.5",
                       "--speed", "6000", "--temperature", "160", "--load-ratio", "0.03", "--weibull-slope", "1.5")
    assert code == 0 and dm["within_validity"] is False and dm["L10_h"] < dm["L50_h"]


def test_kinematics_cli(capsys):
    code, r, _ = _run(capsys, "kinematics", "--bearing", "6205", "--inner-rpm", "1797", "--measured-cage-rpm", "700")
    assert code == 0
    assert r["orders_of_relative_speed"]["ball_pass_inner_hz"] == pytest.approx(5.4152, rel=2e-4)
    assert r["slip_ratio_pct"] == pytest.approx(100.0 * (1.0 - 700.0 / r["cage_rpm"]))
    code, r, _ = _run(capsys, "kinematics", "--pitch-diameter-mm", "33.5", "--ball-diameter-mm", "7.938",
                      "--balls", "8", "--outer-rpm", "10000")
    assert code == 0 and r["cage_rpm"] == pytest.approx(6150.0, rel=0.012)


def test_hertz_cli(capsys):
    code, r, _ = _run(capsys, "hertz", "point", "--load", "100", "--rx1-mm", "5", "--ry1-mm", "5",
                      "--rx2-mm", "1e9", "--ry2-mm", "1e9")
    e_star = 2.08e11 / (1 - 0.09) / 2
    assert code == 0 and r["a_m"] == pytest.approx((3 * 100 * 0.005 / (4 * e_star)) ** (1 / 3), rel=1e-6)
    code, r, _ = _run(capsys, "hertz", "line", "--load", "1000", "--length-mm", "10", "--r1-mm", "5",
                      "--r2-mm", "-20")
    assert code == 0 and r["max_shear_Pa"] == pytest.approx(0.3003 * r["p_max_Pa"], rel=1e-3)
    code, r, _ = _run(capsys, "hertz", "ball-race", "--bearing", "6204", "--inner-groove-ratio", "0.52",
                      "--outer-groove-ratio", "0.52", "--load", "500")
    assert code == 0 and r["inner"]["p_max_Pa"] > r["outer"]["p_max_Pa"]
    Q = 500.0
    delta = (Q / r["inner_N_m15"]) ** (2 / 3) + (Q / r["outer_N_m15"]) ** (2 / 3)
    assert delta == pytest.approx(r["inner"]["approach_m"] + r["outer"]["approach_m"], rel=1e-9)


@pytest.fixture(scope="module")
def pulses_csv(tmp_path_factory):
    t = fr.simulate_pulse_times(1.72e-3, lambda w: 0.05, 3600 * math.pi / 30, 7.5, clock_hz=1e6,
                                jitter_s=2e-6, rng=np.random.default_rng(3))
    path = tmp_path_factory.mktemp("fr") / "pulses.csv"
    path.write_text("t_s\n" + "\n".join(f"{v:.7f}" for v in t) + "\n")
    counts = path.with_name("counts.csv")
    counts.write_text("\n".join(str(int(round(v * 1e6))) for v in t) + "\n")
    return path, counts


def test_free_run_cli(capsys, pulses_csv, tmp_path):
    path, counts = pulses_csv
    code, r, _ = _run(capsys, "free-run", str(path), "--inertia", "1.72e-3")
    assert code == 0 and r["method"] == "n-omega" and r["torque_Nm"] == pytest.approx(0.05, rel=0.005)
    png = tmp_path / "fr.png"
    code, r, _ = _run(capsys, "free-run", str(counts), "--clock-hz", "1e6", "--inertia", "1.72e-3",
                      "--method", "model", "--plot", str(png))
    assert code == 0 and r["torque_Nm"] == pytest.approx(0.05, rel=0.01) and png.stat().st_size > 0
    code, r, _ = _run(capsys, "free-run", str(path), "--rotor-inertia", "1.7e-3", "--bearing", "6206",
                      "--bearings-count", "2", "--method", "t-omega")
    assert code == 0 and r["inertia_kg_m2"] > 1.7e-3 and r["n_used"] > 5


@pytest.mark.parametrize("argv, field", [
    (["grease-life", "--grease", "urea", "--base-oil", "mineral", "--bearing", "9999", "--speed", "1000",
      "--temperature", "100", "--load-ratio", "0.02"], "bearing"),
    (["grease-life", "--grease", "urea", "--base-oil", "castor", "--dm", "30", "--speed", "1000",
      "--temperature", "100", "--load-ratio", "0.02"], "base_oil"),
    (["grease-life", "--grease", "urea", "--base-oil", "pao", "--dm", "30", "--speed", "1000",
      "--outer-ring-rotation", "--temperature", "100", "--load-ratio", "0.02"], "--ball-diameter-mm"),
    (["kinematics", "--bearing", "6204x"], "bearing"),
    (["kinematics", "--pitch-diameter-mm", "5", "--ball-diameter-mm", "6", "--balls", "8"], "--pitch-diameter-mm"),
    (["hertz", "point", "--load=-5", "--rx1-mm", "5", "--ry1-mm", "5", "--rx2-mm", "9", "--ry2-mm", "9"],
     "--load"),
    (["hertz", "line", "--load", "5", "--r1-mm", "5", "--r2-mm", "9"], "--length-mm"),
    (["hertz", "ball-race", "--bearing", "6204", "--inner-groove-ratio", "0.52"], "--outer-groove-ratio"),
])
def test_bad_input_one_line_exit_2(capsys, argv, field):
    code, _, err = _run(capsys, *argv)
    assert code == 2 and field in err and err.count("\n") == 1


def test_free_run_bad_input(capsys, tmp_path, pulses_csv):
    path, _ = pulses_csv
    few = tmp_path / "few.csv"
    few.write_text("0\n0.1\n0.2\n0.3\n")
    back = tmp_path / "back.csv"
    back.write_text("0\n0.1\n0.2\n0.15\n0.3\n0.4\n")
    cases = [
        ([str(few), "--inertia", "1e-3"], "at least 5"),
        ([str(back), "--inertia", "1e-3"], "increase strictly"),
        ([str(path), "--inertia=-1e-3"], "--inertia = -0.001"),
        ([str(path), "--rotor-inertia", "1e-3", "--bearing", "7010C"], "unknown bearing"),
        ([str(path), "--rotor-inertia", "1e-3"], "--rotor-inertia"),
        ([str(path), "--inertia", "1e-3", "--method", "fft"], "method"),
        ([str(tmp_path / "none.csv"), "--inertia", "1e-3"], "file not found"),
    ]
    for argv, text in cases:
        code, _, err = _run(capsys, "free-run", *argv)
        assert code == 2 and text in err and err.count("\n") == 1, (argv, err)

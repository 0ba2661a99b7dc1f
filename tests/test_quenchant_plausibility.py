"""What a user brings to `quenchsim quenchant fit` (issue 36): a probe curve the ISO 9950 probe cannot have produced
(time in ms, in minutes) is refused on one line before the fit; a fitted h(T_s) beyond any oil's is warned about;
the README's `quenchant fit CURVE.csv --out ...` works without --source and records that none was given."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

import quenchsim.fitting.quenchant as q
from quenchsim.cli import main
from quenchsim.errors import InputError
from quenchsim.fitting.probe import ProbeModel
from quenchsim.fitting.probe_bounds import MAX_OIL_HTC_W_M2K, check_probe_plausible, htc_warning

T_NODES = np.array([100.0, 300.0, 500.0, 700.0, 850.0])
OIL_H = np.array([300.0, 400.0, 4000.0, 1500.0, 800.0])


def _oil_curve(h: np.ndarray = OIL_H, t_end_s: float = 20.0) -> tuple[np.ndarray, np.ndarray]:
    """The probe centre's curve under h(T_s) at the nodes, sampled every 0.2 s."""
    ref = ProbeModel().cool(T_NODES, h, np.arange(0.02, t_end_s + 1e-9, 0.02))
    t = np.arange(0.0, t_end_s + 1e-9, 0.2)
    return t, np.interp(t, np.r_[0.0, ref.time_s], np.r_[850.0, ref.centre_C])


def _fake_fit(h: np.ndarray):
    """A stand-in for q.fit_probe_curve that returns ``h`` at once (the fit itself, tens of seconds, is
    test_fitting_quenchant's)."""
    t, T = _oil_curve()
    curve = ProbeModel().cool(T_NODES, h, np.arange(0.02, 20.0 + 1e-9, 0.02))
    return lambda data, **kwargs: q.ProbeFit(
        T_C=T_NODES, h_W_m2K=h, data=data, bath_C=40.0, curve=curve, residual_rms=0.5, residual_max=1.0,
        residual_unit="K", h_std_W_m2K=np.full(h.size, 10.0), identified_C=(300.0, 850.0), alpha=0.2, sigma=0.5,
        iterations=1, simulations=1.0, seconds=0.1, measured=q.cooling_figures(t, T),
        simulated=q.cooling_figures(curve.time_s, curve.centre_C))


def _write(path, t, T):
    path.write_text("time_s,temperature_C\n" + "\n".join(f"{a:.4f},{b:.2f}" for a, b in zip(t, T)) + "\n")
    return path


def test_an_oil_curve_in_seconds_passes():
    t, T = _oil_curve()
    check_probe_plausible(t, T, None)
    check_probe_plausible(None, np.array([800.0, 600.0, 300.0]), np.array([40.0, 90.0, 5.0]))


def test_time_in_ms_is_refused_on_one_line_before_the_fit(tmp_path, capsys):
    t, T = _oil_curve()
    path = _write(tmp_path / "ms.csv", t * 1000.0, T)
    assert main(["quenchant", "fit", str(path), "--out", str(tmp_path / "oil.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "ms.csv: time_s (first point at or below 300 C)" in err
    assert "must be <= 600 s" in err and "in ms?" in err
    assert not (tmp_path / "oil.toml").exists()


def test_time_in_minutes_exceeds_the_probes_conduction_limit(tmp_path, capsys):
    t, T = _oil_curve()
    path = _write(tmp_path / "min.csv", t / 60.0, T)
    assert main(["quenchant", "fit", str(path), "--out", str(tmp_path / "oil.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "min.csv: cooling rate at" in err and "must be <= 450 C/s" in err


def test_a_rate_curve_above_the_conduction_limit_is_refused():
    with pytest.raises(InputError, match=r"cooling rate at 600 C = 900.0: must be <= 450 C/s"):
        check_probe_plausible(None, np.array([800.0, 600.0, 300.0]), np.array([100.0, 900.0, 20.0]))


def test_thermocouple_noise_on_fine_samples_is_not_a_rate(tmp_path):
    """2 K of noise between samples 0.01 s apart reads 400 C/s point to point; over the 0.5 s window it is none."""
    t = np.arange(0.0, 20.0, 0.01)
    t_ref, T_ref = _oil_curve()
    T = np.interp(t, t_ref, T_ref) + np.where(np.arange(t.size) % 2, 2.0, -2.0)
    assert np.max(-np.diff(T) / np.diff(t)) > 450.0
    check_probe_plausible(t, T, None)


def test_a_fitted_h_beyond_any_oil_is_warned_about(tmp_path, capsys, monkeypatch):
    assert htc_warning(T_NODES, OIL_H) is None
    water = np.array([2000.0, 42300.0, 30000.0, 20000.0, 15000.0])
    assert "42,300 W/m2K at 300 C, above 20,000 W/m2K" in htc_warning(T_NODES, water)
    assert MAX_OIL_HTC_W_M2K == 20000.0
    t, T = _oil_curve()
    monkeypatch.setattr(q, "fit_probe_curve", _fake_fit(water))
    path = _write(tmp_path / "curve.csv", t, T)
    assert main(["quenchant", "fit", str(path), "--out", str(tmp_path / "oil.toml")]) == 0
    out = capsys.readouterr().out
    assert "WARNING: the fitted h(T_s) reaches 42,300 W/m2K" in out


def test_the_readme_example_needs_no_source_and_records_none(tmp_path, capsys, monkeypatch):
    """`quenchsim quenchant fit CURVE.csv --out ...` (README) failed: --source was required."""
    t, T = _oil_curve()
    monkeypatch.setattr(q, "fit_probe_curve", _fake_fit(OIL_H))
    out = tmp_path / "oils" / "MY_OIL.toml"
    assert main(["quenchant", "fit", str(_write(tmp_path / "CURVE.csv", t, T)), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "WARNING" not in printed and 'source = "not given by the user"' in printed
    oil = tomllib.loads(out.read_text())
    assert oil["name"] == "MY_OIL" and oil["source"] == "not given by the user"

"""Quenchant from a probe curve (issue 17 items 1-2): inverse verification, library oils, bad input, file round trip."""

from __future__ import annotations

import numpy as np
import pytest

from quenchsim.cli import main
from quenchsim.errors import InputError
from quenchsim.fitting.probe import ProbeMesh, ProbeModel
from quenchsim.bath.quenchant import library, load_probe_quenchant
from quenchsim.fitting.quenchant import (TIME_TEMPERATURE, ProbeData, check_probe_data, cooling_figures, fit_probe_curve,
                                         quenchant_document, read_probe_csv, write_quenchant)
from quenchsim.materials import load_data_file

# a known h(T_s) of oil-like shape (film plateau, boiling peak at 550 C, convection), nodes every 100 K
KNOWN_T_C = np.array([100.0, 200.0, 300.0, 400.0, 500.0, 600.0, 700.0, 800.0, 850.0])
KNOWN_H = np.array([350.0, 450.0, 800.0, 1500.0, 2600.0, 2800.0, 900.0, 500.0, 450.0])
NOISE_K = 0.5     # thermocouple + logger noise (type K, 0.1 s sampling), 1 sigma


def synthetic_curve(T_C: np.ndarray, h: np.ndarray, t_end_s: float, seed: int = 1) -> ProbeData:
    """The probe curve that h(T_s) produces on a finer mesh and with 5 ms steps (not the fitter's model), sampled at
    10 Hz with Gaussian noise."""
    fine = ProbeModel(mesh=ProbeMesh(8, 12, 0.3))
    ref = fine.cool(T_C, h, np.arange(0.005, t_end_s + 1e-9, 0.005))
    t = np.arange(0.1, t_end_s + 1e-9, 0.1)
    T = np.interp(t, ref.time_s, ref.centre_C) + np.random.default_rng(seed).normal(0.0, NOISE_K, t.size)
    return ProbeData(TIME_TEMPERATURE, T, time_s=t)


def test_inverse_fit_recovers_a_known_curve_within_5_percent_over_300_800C():
    """Verification: h(T_s) of known shape drives a finer probe model; the single coarse level of the fitter (100 K
    nodes, 2 K steps) recovers it from the noisy centre curve. 14 s of curve (centre down to 330 C) take the
    surface below 235 C, so every node of 300-800 C is identified (25 s of curve gave the same errors, 3.4 % at
    most, in three times the time: 23 s vs 7 s)."""
    data = synthetic_curve(KNOWN_T_C, KNOWN_H, 14.0)
    fit = fit_probe_curve(data, sigma=NOISE_K, levels=((100.0, 2.0),))
    assert fit.identified_C[0] < 250.0  # the surface went below every node checked
    inside = (fit.T_C >= 300.0) & (fit.T_C <= 800.0)
    error = fit.h_W_m2K[inside] / np.interp(fit.T_C[inside], KNOWN_T_C, KNOWN_H) - 1.0
    assert np.max(np.abs(error)) < 0.05, error
    assert fit.residual_rms < 1.5 * NOISE_K  # re-simulates the curve to the noise level


def test_library_oils_reproduce_their_published_maximum_rate_and_its_temperature():
    names = library()
    assert "astm_d6200_fast_oil" in names
    for name in names:
        oil = load_probe_quenchant(name)
        published = load_data_file(name, "quenchants")["fit"]["measured"]
        model = ProbeModel(bath_temperature_C=oil.bath_temperature_C)
        curve = model.cool(oil.T_C, oil.h_W_m2K, np.concatenate([np.arange(0.01, 30.0, 0.01), np.arange(30.0, 60.0, 0.25)]))
        got = cooling_figures(curve.time_s, curve.centre_C)
        assert abs(got["CRmax_C_s"] / published["CRmax_C_s"] - 1.0) < 0.10, (name, got, published)
        assert abs(got["T_CRmax_C"] - published["T_CRmax_C"]) < 30.0, (name, got, published)


def test_quenchant_file_round_trip(tmp_path):
    data = synthetic_curve(KNOWN_T_C, KNOWN_H, 12.0)
    model = ProbeModel()
    ends = np.arange(0.02, 12.0 + 1e-9, 0.02)
    curve = model.cool(KNOWN_T_C, KNOWN_H, ends)
    from quenchsim.fitting.quenchant import ProbeFit

    fit = ProbeFit(T_C=KNOWN_T_C, h_W_m2K=KNOWN_H, data=data, bath_C=40.0, curve=curve, residual_rms=0.5,
                   residual_max=1.5, residual_unit="K", h_std_W_m2K=np.full(KNOWN_T_C.size, 10.0),
                   identified_C=(300.0, 850.0), alpha=0.2, sigma=0.5, iterations=1, simulations=1.0, seconds=0.1,
                   measured=cooling_figures(data.time_s, data.temperature_C),
                   simulated=cooling_figures(curve.time_s, curve.centre_C))
    path = write_quenchant(tmp_path / "oil.toml", quenchant_document(fit, name="test oil", source="synthetic",
                                                                    tag="computed", agitation_m_s=0.3))
    oil = load_probe_quenchant(str(path))
    assert np.allclose(oil.T_C, KNOWN_T_C) and np.allclose(oil.h_W_m2K, KNOWN_H)
    assert oil.bath_temperature_C == 40.0 and oil.agitation_m_s == 0.3
    assert oil.h(550.0) == pytest.approx(2700.0)


# --- bad input: one-line errors naming the field and the value ----------------------------------------------------

def _csv(tmp_path, text):
    path = tmp_path / "curve.csv"
    path.write_text(text)
    return path


def test_curve_that_heats_up_names_the_point_and_value(tmp_path):
    t = np.arange(0.0, 30.0, 1.0)
    T = np.linspace(850.0, 250.0, t.size)
    T[10] = T[9] + 15.0
    path = _csv(tmp_path, "time_s,temperature_C\n" + "\n".join(f"{a},{b}" for a, b in zip(t, T)))
    with pytest.raises(InputError, match=r"temperature_C \(point 11.*heats up"):
        read_probe_csv(path)


def test_non_monotone_time_names_the_point(tmp_path):
    path = _csv(tmp_path, "time_s,temperature_C\n0,850\n1,840\n2,800\n1.5,780\n3,700\n4,290\n")
    with pytest.raises(InputError, match=r"time_s \(point 4\) = 1.5: must increase strictly"):
        read_probe_csv(path)


def test_curve_that_never_reaches_300C_is_refused():
    data = ProbeData(TIME_TEMPERATURE, np.linspace(850.0, 420.0, 20), time_s=np.arange(20.0))
    with pytest.raises(InputError, match=r"temperature_C \(lowest\) = 420.0: the curve never reaches 300 C"):
        check_probe_data(data)


def test_rate_curve_with_negative_rate_is_heating(tmp_path):
    path = _csv(tmp_path, "temperature_C,rate_C_s\n840,10\n700,60\n600,-5\n400,30\n280,5\n")
    with pytest.raises(InputError, match=r"rate_C_s \(point 3, T = 600 C\) = -5.0"):
        read_probe_csv(path)


def test_unknown_oil_names_it_and_lists_the_known(capsys):
    with pytest.raises(InputError, match=r"quenchant = 'no_such_oil': unknown; known: .*astm_d6200_fast_oil"):
        load_probe_quenchant("no_such_oil")
    assert main(["quenchant", "show", "no_such_oil"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "NAME = 'no_such_oil'" in err


def test_cli_bad_curve_exits_2_with_one_line(tmp_path, capsys):
    path = _csv(tmp_path, "time_s,temperature_C\n0,850\n1,840\n1,800\n2,700\n3,290\n")
    assert main(["quenchant", "fit", str(path), "--out", str(tmp_path / "x.toml"), "--source", "test"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "time_s (point 3) = 1.0" in err


def test_reference_oil_is_not_a_still_bath_curve():
    with pytest.raises(InputError, match="is a liquid quenchant file"):
        load_probe_quenchant("reference_quench_oil")

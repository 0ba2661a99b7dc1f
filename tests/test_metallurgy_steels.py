"""SUJ2 / SUJ3 / 100Cr6 kinetics against published numbers: Ms, retained austenite, hardenability, hardness."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from quenchsim.materials import load_material
from quenchsim.metallurgy import advance, hardness_HV, hv_to_hrc, initial_state, load_kinetics, phase_hardness_HV
from quenchsim.metallurgy.cct import cct_diagram, critical_rate_C_s

T_AUST = 840.0  # mid of the 830-850 C practice for through-hardening SUJ2/SUJ3 (docs/reference/quench_cases.md)


@pytest.fixture(scope="module")
def kinetics():
    return {name: load_kinetics(load_material(name), T_AUST) for name in ("SUJ2", "SUJ3")}


def test_dissolved_carbon_is_used_for_ms(kinetics):
    """Ms with the carbon dissolved at T_aust lands at the measured 210-230 C (ShKh15 210, 100Cr6 229,
    100CrMnSi6-4 210: docs/reference/materials_and_kinetics.md 1a); the bulk 1 %C would give far less."""
    for name, kin in kinetics.items():
        assert 0.55 <= kin.dissolved["C"] <= 0.7 < kin.composition["C"]
        assert 205.0 <= kin.Ms_C <= 235.0, (name, kin.Ms_C)
        bulk_ms = 561 - 474 * kin.composition["C"] - 33 * kin.composition["Mn"] - 17 * kin.composition["Cr"]
        assert bulk_ms < 100.0
    # Mn-Si SUJ3 below SUJ2 by about the 19 K Furlan et al. measured between 100CrMnSi6-4 and 100Cr6
    assert 10.0 <= kinetics["SUJ2"].Ms_C - kinetics["SUJ3"].Ms_C <= 30.0


def test_peer_100cr6_ms_and_alpha():
    kin = load_kinetics(load_material("100Cr6_furlan"), 850.0)
    assert kin.Ms_C == pytest.approx(526.29 - 29702 * 0.01, abs=1e-9)
    assert kin.alpha_per_K == pytest.approx(7.14e-3 + 0.0198 * np.exp(-156 * 0.01), rel=1e-3)


@pytest.mark.parametrize("name", ["SUJ2", "SUJ3"])
def test_retained_austenite_after_oil_quench_about_ten_percent(kinetics, name):
    """Oil quench (fast enough to be martensitic) into oil at 70 C, then air to 20 C: RA about 10 % as measured in
    oil-quenched 52100 (docs/reference/materials_and_kinetics.md 1a/2c); in the oil at 70 C it is still higher."""
    kin = kinetics[name]
    s = initial_state((1,), kin)
    s = advance(s, kin, T_AUST, 70.0, (T_AUST - 70.0) / 60.0)
    ra_in_oil = s.fractions["austenite"][0]
    s = advance(s, kin, 70.0, 20.0, 200.0)
    ra = s.fractions["austenite"][0]
    assert 0.07 <= ra <= 0.14, ra
    assert ra_in_oil == pytest.approx(np.exp(-kin.alpha_per_K * (kin.Ms_C - 70.0)), rel=0.05)


def _target(steel: str, metric: str) -> dict:
    """A published target of the steel's validation study (validation/materials/<steel>/targets.toml)."""
    path = Path(__file__).resolve().parents[1] / "validation" / "materials" / steel / "targets.toml"
    with path.open("rb") as fh:
        return next(t for t in tomllib.load(fh)["targets"] if t["metric"] == metric)


def test_suj2_critical_rate_within_factor_1_5_of_kawulok():
    """SUJ2 fitted to 100Cr6 data: the slowest linear cooling from 850 C with at most 5 % pearlite + bainite lies
    within the band around Kawulok et al.'s (2020) 12 C/s (the Li composition model needed 54.5 C/s)."""
    target = _target("SUJ2", "critical_rate_C_s")
    kin = load_kinetics(load_material("SUJ2"), 850.0)
    assert target["min"] <= critical_rate_C_s(kin, 0.05, 850.0) <= target["max"]


def test_slow_cooling_gives_fine_pearlite(kinetics):
    """Slow cooling gives pearlite of the fine-pearlite level (~35-40 HRC) in both steels. (Whether SUJ3 is the more
    hardenable grade, as its makers say, is a validation target of validation/materials/SUJ3 that the declared
    pearlite calibration on the jet bath now misses: reports/materials_SUJ3.md.)"""
    rates = np.array([0.1, 0.3])
    for kin in kinetics.values():
        d = cct_diagram(kin, rates, T_AUST)
        assert np.all(d.final_fractions["pearlite"] > 0.99)
        assert np.all((30.0 < d.hardness_HRC) & (d.hardness_HRC < 42.0))


@pytest.mark.parametrize("name", ["SUJ2", "SUJ3"])
def test_bainite_hardness_within_measured_52100_range(kinetics, name):
    """Bainite of the bulk composition at 700 C rates of 10-100 C/s: within the 595-645 HV measured for fully
    lower-bainitic 52100 (Yurtseven, METU; validation/materials/SUJ2/targets.toml)."""
    target = _target("SUJ2", "bainite_HV_10_C_s")
    hv = phase_hardness_HV(kinetics[name], "bainite", np.array([10.0, 30.0, 100.0]))
    assert np.all((target["min"] <= hv) & (hv <= target["max"])), hv


@pytest.mark.parametrize("name", ["SUJ2", "SUJ3"])
def test_as_quenched_hardness_matches_52100_practice(kinetics, name):
    """Fast oil quench of a thin section: 64-67 HRC as-quenched (ASM One Minute Mentor for 52100)."""
    kin = kinetics[name]
    s = initial_state((1,), kin)
    T, rate = T_AUST, 100.0
    for T_new in np.linspace(T_AUST - 10.0, 20.0, 83):
        s = advance(s, kin, T, T_new, (T - T_new) / rate)
        T = T_new
    hrc = hv_to_hrc(hardness_HV(s, kin))[0]
    assert 63.5 <= hrc <= 67.0, hrc

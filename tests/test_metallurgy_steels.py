"""SUJ2 / SUJ3 / 100Cr6 kinetics against published numbers: Ms, retained austenite, hardenability, hardness."""

from __future__ import annotations

import numpy as np
import pytest

from quenchsim.materials import load_material
from quenchsim.metallurgy import advance, hardness_HV, hv_to_hrc, initial_state, load_kinetics
from quenchsim.metallurgy.cct import cct_diagram

T_AUST = 840.0  # mid of the 830-850 C practice for through-hardening SUJ2/SUJ3 (quench_cases.md)


@pytest.fixture(scope="module")
def kinetics():
    return {name: load_kinetics(load_material(name), T_AUST) for name in ("SUJ2", "SUJ3")}


def test_dissolved_carbon_is_used_for_ms(kinetics):
    """Ms with the carbon dissolved at T_aust lands at the measured 210-230 C (ShKh15 210, 100Cr6 229,
    100CrMnSi6-4 210: materials_and_kinetics.md 1a); the bulk 1 %C would give far less."""
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
    oil-quenched 52100 (materials_and_kinetics.md 1a/2c); in the oil at 70 C it is still higher."""
    kin = kinetics[name]
    s = initial_state((1,), kin)
    s = advance(s, kin, T_AUST, 70.0, (T_AUST - 70.0) / 60.0)
    ra_in_oil = s.fractions["austenite"][0]
    s = advance(s, kin, 70.0, 20.0, 200.0)
    ra = s.fractions["austenite"][0]
    assert 0.07 <= ra <= 0.14, ra
    assert ra_in_oil == pytest.approx(np.exp(-kin.alpha_per_K * (kin.Ms_C - 70.0)), rel=0.05)


def _rate_for_products(diagram, limit: float) -> float:
    """Slowest rate of the (increasing) rate grid with pearlite + bainite <= limit, interpolated in log rate."""
    products = diagram.final_fractions["pearlite"] + diagram.final_fractions["bainite"]
    k = int(np.argmax(products <= limit))
    assert k > 0 and np.all(products[k:] <= limit + 1e-9)
    x0, x1 = np.log(diagram.rates_C_s[k - 1]), np.log(diagram.rates_C_s[k])
    w = (products[k - 1] - limit) / (products[k - 1] - products[k])
    return float(np.exp(x0 + w * (x1 - x0)))


def test_suj3_clearly_more_hardenable_than_suj2(kinetics):
    """The composition model (Li 1998 on the dissolved composition) makes Mn-Si SUJ3 the deeper-hardening grade."""
    rates = np.logspace(-1, 3, 21)
    d2 = cct_diagram(kinetics["SUJ2"], rates, T_AUST)
    d3 = cct_diagram(kinetics["SUJ3"], rates, T_AUST)
    crit2, crit3 = _rate_for_products(d2, 0.05), _rate_for_products(d3, 0.05)
    half2, half3 = _rate_for_products(d2, 0.5), _rate_for_products(d3, 0.5)
    assert crit2 / crit3 > 4.0 and half2 / half3 > 4.0, (crit2, crit3, half2, half3)
    at_5 = np.searchsorted(rates, 5.0)
    assert d3.hardness_HRC[at_5] > 58.0 > d2.hardness_HRC[at_5]
    # slow cooling gives pearlite in both, of fine-pearlite hardness (~35-40 HRC for 1 %C steels)
    for d in (d2, d3):
        assert d.final_fractions["pearlite"][0] > 0.99
        assert 30.0 < d.hardness_HRC[0] < 42.0


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

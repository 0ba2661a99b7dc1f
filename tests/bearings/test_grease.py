"""Grease life: the paper's L50 data, the outer-ring-rotation example, validity warnings, Weibull."""

import math

import numpy as np
import pytest

from quenchsim.bearings import grease, kinematics as kin
from quenchsim.errors import InputError

DATA = grease.grease_data()["fitted_data"]["urea"]
DM_6204 = kin.bearing("6204").pitch_diameter_m * 1e3
POINTS = grease.published_points("urea")


def _life(**kw):
    args = dict(grease="urea", base_oil="pao+ester", dm_mm=DM_6204, speed_rpm=10000.0,
                temperature_C=150.0, load_ratio=0.016)
    args.update(kw)
    return grease.grease_life(**args)


def _fit():
    p = POINTS
    return grease.fit_base_oil_factor("urea", p.dm_mm, p.speed_rpm, p.temperature_C, p.load_ratio, p.L50_h)


def test_repeat_scatter_is_the_spread_of_the_nominal_repeats():
    repeats = DATA["nominal_repeats_L50_h"]
    # each repeat value is a published value of the nominal condition (10000 rpm, 150 C, lightest load)
    nominal = (POINTS.speed_rpm == 10000.0) & (POINTS.temperature_C == 150.0) & (POINTS.load_ratio <= 0.016)
    assert sorted(POINTS.L50_h[nominal]) == sorted(repeats[:3])
    assert repeats[3] == DATA["same_cage_speed"]["inner_L50_h"]
    tol = grease.repeat_scatter_log10("urea")
    assert tol == pytest.approx(math.log10(2117.0 / 1559.0), rel=1e-12)   # factor 1.36


def test_every_published_point_within_paper_scatter_with_fitted_base_oil_factor():
    """The test grease's base oil is not stated: K1 is estimated from all nine points (least squares
    in log10 L) and then every point must lie within the paper's repeat scatter."""
    assert POINTS.L50_h.size == 9
    fit = _fit()
    tol = grease.repeat_scatter_log10("urea")
    residual = fit.residuals_log10(fit.k1_least_squares)
    assert np.all(np.abs(residual) <= tol), (fit.k1_least_squares, residual, tol)
    # least squares: residuals sum to zero and any other K1 has a larger sum of squares
    assert residual.sum() == pytest.approx(0.0, abs=1e-12)
    for dk in (-1e-3, 1e-3):
        assert np.sum(fit.residuals_log10(fit.k1_least_squares + dk) ** 2) > np.sum(residual**2)
    # the estimate lies in the K1 range that keeps every point within the scatter
    lo, hi = fit.feasible_interval(tol)
    assert lo <= fit.k1_least_squares <= hi and lo <= fit.k1_minimax <= hi
    # the residuals are those of the public formula: with a named base oil, grease_life gives them
    for oil in ("pao+ester", "mineral"):
        k1 = grease.base_oil_factor("urea", oil)
        lives = [_life(base_oil=oil, speed_rpm=n, temperature_C=T, load_ratio=F).L50_h
                 for n, T, F in zip(POINTS.speed_rpm, POINTS.temperature_C, POINTS.load_ratio)]
        np.testing.assert_allclose(np.log10(np.array(lives) / POINTS.L50_h), fit.residuals_log10(k1), atol=1e-12)


def test_fitted_factor_predicts_the_same_cage_speed_points():
    # not used in the fit: inner ring 10000 rpm (1636 h) and outer ring 6150 rpm (1765 h), nominal T and load
    fit = _fit()
    tol = grease.repeat_scatter_log10("urea")
    same = DATA["same_cage_speed"]
    K = kin.equivalent_inner_speed_factor(kin.bearing("6204").geometry)
    for rpm, k, L in ((same["inner_rpm"], 1.0, same["inner_L50_h"]), (same["outer_rpm"], K, same["outer_L50_h"])):
        model = grease.log10_life_without_base_oil("urea", DM_6204, rpm, 150.0, 0.016, k) + fit.k1_least_squares
        assert abs(model - math.log10(L)) <= tol, (rpm, 10**model, L)


def test_fit_recovers_a_known_base_oil_factor():
    k1 = grease.base_oil_factor("urea", "ether")
    p = POINTS
    exact = np.array([_life(base_oil="ether", speed_rpm=n, temperature_C=T, load_ratio=F).L50_h
                      for n, T, F in zip(p.speed_rpm, p.temperature_C, p.load_ratio)])
    fit = grease.fit_base_oil_factor("urea", p.dm_mm, p.speed_rpm, p.temperature_C, p.load_ratio, exact)
    assert fit.k1_least_squares == pytest.approx(k1, abs=1e-12)
    assert fit.k1_minimax == pytest.approx(k1, abs=1e-12)
    assert fit.k1_standard_error < 1e-12
    # a uniform factor 2 on every life shifts K1 by log10 2 and nothing else
    shifted = grease.fit_base_oil_factor("urea", p.dm_mm, p.speed_rpm, p.temperature_C, p.load_ratio, 2.0 * exact)
    assert shifted.k1_least_squares == pytest.approx(k1 + math.log10(2.0), abs=1e-12)


def test_temperature_series_shape():
    # the formula's temperature trend L(T)/L(150 C) reproduces the series independently of K1 and speed
    s = DATA["temperature_series"]
    tol = grease.repeat_scatter_log10("urea")
    ref = s["L50_h"][1]
    for T, L in zip(s["temperature_C"], s["L50_h"]):
        model_ratio = _life(temperature_C=T).L50_h / _life(temperature_C=150.0).L50_h
        assert abs(math.log10(model_ratio / (L / ref))) <= tol / 2


def test_outer_ring_rotation_example():
    K = kin.equivalent_inner_speed_factor(kin.bearing("6204").geometry)
    inner = _life()
    outer = _life(speed_factor=K)
    ratio = outer.L50_h / inner.L50_h
    assert ratio == pytest.approx(0.39, abs=0.015)           # the paper's 0.39
    lo, hi = DATA["outer_rotation_ratio_measured"]
    assert lo <= ratio <= hi                                   # measured 0.32 - 0.43
    # the same outer-ring speed as 10000 rpm x K on the inner ring gives the same life
    assert outer.L50_h == pytest.approx(_life(speed_rpm=10000.0 * K).L50_h, rel=1e-12)
    # same cage speed: outer ring at 6150 rpm vs inner ring at 10000 rpm -> same life (1765 vs 1636 h)
    same = DATA["same_cage_speed"]
    r = _life(speed_rpm=same["outer_rpm"], speed_factor=K).L50_h / _life(speed_rpm=same["inner_rpm"]).L50_h
    measured = same["outer_L50_h"] / same["inner_L50_h"]
    assert abs(math.log10(r / measured)) <= grease.repeat_scatter_log10("urea")
    assert r == pytest.approx(1.0, abs=0.02)


def test_base_oils_and_mixtures():
    assert grease.base_oil_factor("urea", "PAO+Ester") == 0.0
    assert grease.base_oil_factor("urea", "ester+mineral") == -0.16
    assert grease.base_oil_factor("lithium", "silicone") == 0.54
    a = grease.grease_life("lithium", "ester", 33.5, 10000.0, 100.0, 0.03)
    b = grease.grease_life("lithium", "diester", 33.5, 10000.0, 100.0, 0.03)
    assert math.log10(a.L50_h / b.L50_h) == pytest.approx(0.42 + 0.50, rel=1e-12)
    with pytest.raises(InputError, match="base_oil"):
        grease.base_oil_factor("lithium", "pao+ester")  # no lithium mixture factor published
    with pytest.raises(InputError, match="grease"):
        grease.base_oil_factor("calcium", "mineral")


def test_validity_warnings():
    ok = _life(temperature_C=120.0, load_ratio=0.03)
    assert ok.within_validity and ok.warnings == ()
    hot = grease.grease_life("lithium", "mineral", 33.5, 5000.0, 160.0, 0.03)
    assert not hot.within_validity and any("temperature" in w for w in hot.warnings)
    assert _life(temperature_C=160.0).within_validity           # urea is valid up to 180 C
    fast = _life(speed_rpm=15000.0)
    assert not fast.within_validity and any("dmN" in w for w in fast.warnings)
    # outer-ring rotation: the equivalent speed K dmN counts
    K = kin.equivalent_inner_speed_factor(kin.bearing("6204").geometry)
    assert _life(speed_rpm=11000.0).within_validity
    assert not _life(speed_rpm=11000.0, speed_factor=K).within_validity
    small = _life(dm_mm=8.0)
    assert any("dm =" in w for w in small.warnings)
    heavy = _life(load_ratio=0.2)
    assert any("P/Cr" in w for w in heavy.warnings) and heavy.L50_h > 0


def test_weibull_helper():
    assert grease.weibull_life(1000.0, 1.0) == pytest.approx(1000.0 * math.log(0.9) / math.log(0.5))
    assert grease.weibull_life(1000.0, 2.0, reliability=0.5) == pytest.approx(1000.0)
    # steeper slope -> L10 closer to L50
    assert grease.weibull_life(1000.0, 3.0) > grease.weibull_life(1000.0, 1.5)


def test_bad_input():
    with pytest.raises(InputError, match="temperature_C = 1000.0: must be within -60..250 C"):
        _life(temperature_C=1000.0)
    with pytest.raises(InputError, match="speed_rpm"):
        _life(speed_rpm=-1.0)
    with pytest.raises(InputError, match="load_ratio"):
        _life(load_ratio=1.5)
    with pytest.raises(InputError, match="speed_factor"):
        _life(speed_factor=0.5)
    with pytest.raises(InputError, match="slope"):
        grease.weibull_life(1000.0, 0.0)
    p = POINTS
    with pytest.raises(InputError, match="L50_h"):
        grease.fit_base_oil_factor("urea", p.dm_mm, 10000.0, 150.0, 0.016, [1559.0])
    with pytest.raises(InputError, match="L50_h"):
        grease.fit_base_oil_factor("urea", p.dm_mm, 10000.0, 150.0, 0.016, [1559.0, -1.0])
    with pytest.raises(InputError, match="conditions"):
        grease.fit_base_oil_factor("urea", p.dm_mm, p.speed_rpm[:3], p.temperature_C, p.load_ratio, p.L50_h)
    with pytest.raises(InputError, match="grease"):
        grease.published_points("lithium")      # the reference gives no lithium data points

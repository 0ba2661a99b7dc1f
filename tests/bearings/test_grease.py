"""Grease life: the paper's L50 data, the outer-ring-rotation example, validity warnings, Weibull."""

import math

import pytest

from quenchsim.bearings import grease, kinematics as kin
from quenchsim.errors import InputError

DATA = grease.grease_data()["fitted_data"]["urea"]
DM_6204 = kin.bearing("6204").pitch_diameter_m * 1e3


def _repeat_scatter_log10():
    """The paper's own scatter: its L50 values for the same nominal condition (6204, 10000 rpm inner,
    150 C, lightest load) from the speed, load and temperature series and the inner-ring reference of
    the same-cage-speed test span this factor (in log10)."""
    base = [DATA["speed_series"]["L50_h"][0], DATA["load_series"]["L50_h"][0],
            DATA["temperature_series"]["L50_h"][1], DATA["same_cage_speed"]["inner_L50_h"]]
    return math.log10(max(base) / min(base))


def _life(**kw):
    args = dict(grease="urea", base_oil=DATA["base_oil"], dm_mm=DM_6204, speed_rpm=10000.0,
                temperature_C=150.0, load_ratio=0.016)
    args.update(kw)
    return grease.grease_life(**args)


def test_speed_and_load_series_within_paper_scatter():
    tol = _repeat_scatter_log10()
    assert 0.1 < tol < 0.2  # 1559 ... 2117 h for one nominal condition
    s = DATA["speed_series"]
    for n, L in zip(s["speed_rpm"], s["L50_h"]):
        r = _life(speed_rpm=n, temperature_C=s["temperature_C"], load_ratio=s["load_ratio"])
        assert abs(math.log10(r.L50_h / L)) <= tol, (n, r.L50_h, L)
    s = DATA["load_series"]
    for F, L in zip(s["load_ratio"], s["L50_h"]):
        r = _life(load_ratio=F)
        assert abs(math.log10(r.L50_h / L)) <= tol, (F, r.L50_h, L)


def test_temperature_series_shape_and_uniform_offset():
    # the series' other conditions are not stated; the formula must reproduce its temperature trend
    s = DATA["temperature_series"]
    tol = _repeat_scatter_log10()
    ref = s["L50_h"][1]
    residual = []
    for T, L in zip(s["temperature_C"], s["L50_h"]):
        model_ratio = _life(temperature_C=T).L50_h / _life(temperature_C=150.0).L50_h
        assert abs(math.log10(model_ratio / (L / ref))) <= tol / 2
        residual.append(math.log10(_life(temperature_C=T).L50_h / L))
    # the level differs by one common offset (an unstated condition), not by a trend
    mean = sum(residual) / 3
    assert max(abs(r - mean) for r in residual) < 0.03


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
    assert abs(math.log10(r / measured)) <= _repeat_scatter_log10()
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
    with pytest.raises(InputError, match="speed_rpm"):
        _life(speed_rpm=-1.0)
    with pytest.raises(InputError, match="load_ratio"):
        _life(load_ratio=1.5)
    with pytest.raises(InputError, match="speed_factor"):
        _life(speed_factor=0.5)
    with pytest.raises(InputError, match="slope"):
        grease.weibull_life(1000.0, 0.0)

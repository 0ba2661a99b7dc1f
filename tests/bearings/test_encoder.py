"""Magnetic encoder: closed-form field against the plain Fourier sum and a coarse FE, Hall switching and the pulse
measures against closed forms, CLI and bad input."""

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from quenchsim.bearings import encoder as enc
from quenchsim.bearings.encoder import fe
from quenchsim.cli import main
from quenchsim.errors import InputError


def test_closed_form_matches_the_fourier_sum_and_the_reference_numbers():
    e = enc.Encoder(1.5e-3, 1e-3, 1.0)
    n = np.arange(1, 4001, 2.0)
    k = n * math.pi / 1.5e-3
    for g, x in ((0.2e-3, 0.0), (1e-3, 0.4e-3), (2.5e-3, 1.1e-3)):
        amp = 4 / (n * math.pi) * np.sin(n * math.pi / 2) * 0.5 * (1 - np.exp(-k * 1e-3)) * np.exp(-k * g)
        bx, by = enc.field_T(e, x, g)
        assert by == pytest.approx(np.sum(amp * np.cos(k * x)), abs=1e-9)
        assert bx == pytest.approx(np.sum(amp * np.sin(k * x)), abs=1e-9)
    # reference notes sec. 2.4: B/B_r = 0.068 at g = 1 mm (0.077 on iron), so 15 mT implies B_r ~ 0.22 (0.19) T
    assert enc.pole_centre_field_T(e, 1e-3) == pytest.approx(0.068, abs=1e-3)
    assert enc.pole_centre_field_T(enc.Encoder(1.5e-3, 1e-3, 1.0, backing="iron"), 1e-3) == pytest.approx(0.077, abs=1e-3)
    assert enc.remanence_for_field_T(0.015, 1e-3, 1.5e-3, 1e-3) == pytest.approx(0.22, abs=0.005)
    # far field: the fundamental alone, exp(-pi g / p) per unit gap
    ratio = enc.pole_centre_field_T(e, 6e-3) / enc.pole_centre_field_T(e, 5e-3)
    assert ratio == pytest.approx(math.exp(-math.pi / 1.5), rel=1e-6)


def test_layer_factor_limits():
    k = np.array([100.0, 2000.0, 1e5])
    assert enc.layer_factor(k, 1e-3) == pytest.approx((1 - np.exp(-k * 1e-3)) / 2, rel=1e-12)
    assert enc.layer_factor(k, 1e-3, backing="iron") == pytest.approx(enc.layer_factor(k, 2e-3), rel=1e-12)
    assert enc.layer_factor(1e9, 1e-3, 1.5) == pytest.approx(1 / 2.5, rel=1e-9)   # thick: 1/(mu_r + 1)


@pytest.mark.parametrize("mu, backing", [(1.0, "air"), (1.3, "iron")])
def test_fe_pole_pair_matches_the_closed_form(mu, backing):
    e = enc.Encoder(1.5e-3, 1e-3, 0.2, mu, backing)
    gaps = np.array([0.0, 1e-3, 3e-3])
    r = fe.solve_pole_pair(e, gaps, step_m=1.5e-3 / 12, far_m=6e-3)
    assert r.pole_centre_T == pytest.approx(np.asarray(enc.pole_centre_field_T(e, gaps)), rel=5e-3)


def _ring(**kw):
    args = dict(poles=64, magnet_diameter_m=30.55e-3, thickness_m=1e-3, remanence_T=0.22, gap_m=1e-3, operate_T=3e-3,
                release_T=-3e-3)
    args.update(kw)
    return enc.RingEncoder(**args)


def test_ideal_and_eccentric_pulse_trains():
    m = enc.pulse_metrics(_ring())
    assert m.pulses_per_revolution == 32
    assert m.pitch_error_pct.max() < 1e-8 and np.abs(m.duty_pct - 50).max() < 1e-8
    assert np.abs(m.lead_deg - 90).max() < 1e-8
    e = 0.05e-3
    ring = _ring(eccentricity_m=e, operate_T=1e-5, release_T=-1e-5)
    theory = e / (ring.radius_m + ring.gap_m) * math.sin(math.pi / 32) / (math.pi / 32)
    assert enc.pulse_metrics(ring).once_per_rev_period_modulation == pytest.approx(theory, rel=2e-3)


def test_unipolar_duty_follows_the_field_profile():
    ring = _ring(operate_T=5e-3, release_T=1e-3)
    p, g = ring.pole_width_m, ring.gap_m
    by = lambda x, level: enc.field_T(ring.layer, x, g)[1] - level   # noqa: E731
    rise = brentq(by, -p, 0.0, args=(ring.operate_T,))                # south centre -> north centre
    fall = brentq(by, 0.0, p, args=(ring.release_T,))
    duty = 100 * (fall - rise) / (2 * p)
    assert enc.pulse_metrics(ring).duty_pct == pytest.approx(np.full(32, duty), abs=1e-6)


def test_bad_input():
    with pytest.raises(InputError, match="poles"):
        _ring(poles=63)
    with pytest.raises(InputError, match="release_T"):
        _ring(release_T=4e-3)
    with pytest.raises(InputError, match="backing"):
        enc.Encoder(1.5e-3, 1e-3, 0.2, backing="steel")


def test_cli(capsys):
    assert main(["bearings", "encoder", "remanence", "--poles", "64", "--magnet-diameter-mm", "30.55", "--thickness-mm",
                 "1", "--gap-mm", "1", "--field-mT", "15", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["remanence_T"] == pytest.approx(0.2196, abs=1e-3)
    assert main(["bearings", "encoder", "pulses", "--poles", "64", "--magnet-diameter-mm", "30.55", "--thickness-mm",
                 "1", "--remanence-T", "0.22", "--gap-mm", "1", "--operate-mT", "3", "--release-mT", "-3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pulses_per_revolution"] == 32 and out["sensor_b_offset_mm"] == pytest.approx(0.75, rel=1e-3)


@pytest.mark.parametrize("argv, option, allowed", [
    (["field", "--pole-width-mm", "1.5", "--thickness-mm", "1", "--remanence-T", "3", "--gap-mm", "1"],
     "--remanence-T", "in (0, 2] T"),
    (["field", "--pole-width-mm", "1.5", "--thickness-mm", "1", "--remanence-T", "0.2", "--gap-mm", "-1"],
     "--gap-mm", "in [0, 1000] mm"),
    (["field", "--thickness-mm", "1", "--remanence-T", "0.2", "--gap-mm", "1"], "--pole-width-mm", "--poles"),
    (["pulses", "--poles", "64", "--magnet-diameter-mm", "30.55", "--thickness-mm", "1", "--remanence-T", "0.22",
      "--gap-mm", "2.5", "--operate-mT", "3", "--release-mT", "-3"], "--operate-mT", "would miss poles"),
    (["pulses", "--poles", "63", "--magnet-diameter-mm", "30.55", "--thickness-mm", "1", "--remanence-T", "0.22",
      "--gap-mm", "1", "--operate-mT", "3", "--release-mT", "-3"], "--poles", "must be even"),
])
def test_cli_bad_input_is_one_line(argv, option, allowed, capsys):
    assert main(["bearings", "encoder", *argv, "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"quenchsim: error: {option} = ") and allowed in err[0], err


def test_remanence_temperature_law_of_bonded_ferrite():
    # Modelica's PlasticHardFerrite: alpha_Br = -0.002 1/K about 20 C; the field is linear in B_r
    data = enc.magnet_data()
    assert data["remanence_temperature_coefficient_per_K"] == -0.002 and data["reference_temperature_C"] == 20.0
    assert enc.remanence_at_temperature_T(0.21, 20.0) == 0.21
    assert enc.remanence_at_temperature_T(0.21, 120.0) == pytest.approx(0.21 * 0.8)
    assert enc.remanence_at_temperature_T(0.21, -40.0) == pytest.approx(0.21 * 1.12)
    hot = enc.Encoder(1.5e-3, 1e-3, enc.remanence_at_temperature_T(0.21, 120.0))
    assert enc.pole_centre_field_T(hot, 1e-3) == pytest.approx(0.8 * enc.pole_centre_field_T(enc.Encoder(1.5e-3, 1e-3, 0.21), 1e-3))
    with pytest.raises(InputError, match="temperature_C"):
        enc.remanence_at_temperature_T(0.21, 600.0)


def test_stray_field_margin_is_the_field_beyond_the_hall_points():
    e = enc.Encoder(1.5e-3, 1e-3, 0.2)
    b = enc.pole_centre_field_T(e, 1e-3)
    # symmetric latch: the stray bias may reach B_enc - B_op of either sign; an asymmetric one is set by the nearer point
    assert enc.stray_field_margin_T(e, 1e-3, 3e-3, -3e-3) == pytest.approx(b - 3e-3)
    assert enc.stray_field_margin_T(e, 1e-3, 5e-3, -1e-3) == pytest.approx(b - 5e-3)
    # with that bias the biased field still reaches the operate point and, at the other pole, the release point
    bias = enc.stray_field_margin_T(e, 1e-3, 5e-3, -1e-3)
    assert b + bias >= 5e-3 - 1e-15 and -b + bias <= -1e-3 + 1e-15
    with pytest.raises(InputError, match="release_T"):
        enc.stray_field_margin_T(e, 1e-3, 1e-3, 2e-3)

"""Free-run friction torque: synthetic coast-downs from known torque laws with realistic timing
noise (1 MHz counter, 2 us trigger jitter, one pulse per revolution, down to 2 % of the start
speed), the published (n - omega') and (t - omega') methods and the model fit."""

import math

import numpy as np
import pytest

from quenchsim.bearings import free_run as fr
from quenchsim.bearings import kinematics as kin
from quenchsim.errors import InputError

INERTIA = 1.72e-3            # kg m^2, the spindle of the free-run paper (I_eq = 1.7203e-3 at 80 N preload)
OMEGA0 = 3600.0 * math.pi / 30.0   # 3600 rpm, the paper's higher steady speed
LAWS = {  # torque (N m) of omega (rad/s): constant; Coulomb + viscous; Coulomb + linear + quadratic
    "constant": (0.05, 0.0, 0.0),
    "coulomb+viscous": (0.03, 8.0e-5, 0.0),
    "coulomb+linear+quadratic": (0.02, 5.0e-5, 2.0e-7),
}


def torque(law):
    c0, c1, c2 = LAWS[law]
    return lambda w: c0 + c1 * w + c2 * w * w


def coast_down(law, seed, clock_hz=1e6, jitter_s=2e-6, end=0.02):
    return fr.simulate_pulse_times(INERTIA, torque(law), OMEGA0, end * OMEGA0, clock_hz=clock_hz,
                                   jitter_s=jitter_s, rng=np.random.default_rng(seed))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_n_omega_recovers_constant_torque(seed):
    t = coast_down("constant", seed)
    r = fr.friction_torque(t, INERTIA, "n-omega", alpha_percent=1.0)
    assert r.torque_Nm == pytest.approx(0.05, rel=0.005)
    assert 5 <= r.n_used <= t.size


@pytest.mark.parametrize("law", list(LAWS))
@pytest.mark.parametrize("seed", [11, 12])
def test_model_recovers_start_torque_of_every_law(law, seed):
    t = coast_down(law, seed)
    r = fr.friction_torque(t, INERTIA, "model")
    assert r.torque_Nm == pytest.approx(torque(law)(OMEGA0), rel=0.01)
    assert r.omega0_rad_s == pytest.approx(OMEGA0, rel=1e-4)
    assert r.n_used == t.size


def test_model_recovers_palmgren_like_power_law():
    # Coulomb + viscous term growing as omega^(2/3) (Palmgren's (nu n)^(2/3)): only the power family
    law = lambda w: 0.03 + 0.03 * (w / OMEGA0) ** (2.0 / 3.0)  # noqa: E731
    t = fr.simulate_pulse_times(INERTIA, law, OMEGA0, 0.02 * OMEGA0, clock_hz=1e6, jitter_s=2e-6,
                                rng=np.random.default_rng(21))
    r = fr.friction_torque(t, INERTIA, "model")
    assert r.torque_Nm == pytest.approx(0.06, rel=0.01)
    assert r.detail.law.family == "power" and r.detail.law.params[2] == pytest.approx(2.0 / 3.0, abs=0.02)


def test_linear_fit_methods_are_biased_for_speed_dependent_torque():
    t = coast_down("coulomb+linear+quadratic", 5)
    true = torque("coulomb+linear+quadratic")(OMEGA0)
    t_omega = fr.friction_torque(t, INERTIA, "t-omega").torque_Nm
    model = fr.friction_torque(t, INERTIA, "model").torque_Nm
    # a straight line through omega'(t) over the whole coast-down misses the curvature
    assert abs(t_omega / true - 1.0) > 0.05
    assert abs(model / true - 1.0) < 0.002


def test_published_methods_exact_without_noise_for_constant_torque():
    t = coast_down("constant", 0, clock_hz=None, jitter_s=0.0)
    for method in ("n-omega", "t-omega", "model"):
        assert fr.friction_torque(t, INERTIA, method).torque_Nm == pytest.approx(0.05, rel=1e-6)


def test_model_forward_matches_independent_integration():
    law = "coulomb+linear+quadratic"
    t = coast_down(law, 0, clock_hz=None, jitter_s=0.0)
    c = tuple(v / INERTIA for v in LAWS[law])
    theta = 2.0 * math.pi * np.arange(t.size)
    speeds = fr.speed_samples(t).omega_rad_s
    model = fr.model_pulse_times(theta, OMEGA0, fr.TorqueLaw("polynomial", c), 0.5 * speeds.min(), 3 * t.size)
    assert np.max(np.abs(model - t)) < 1e-8  # s, over ~14 s of coast-down


def test_cumulative_slopes_match_direct_fits():
    rng = np.random.default_rng(4)
    t = np.cumsum(rng.uniform(0.01, 0.02, 40))
    w = 300.0 - 20.0 * t + rng.normal(0.0, 0.05, t.size)
    s = fr.cumulative_slopes(fr.SpeedSamples(t, w))
    direct = [np.polyfit(t[:n], w[:n], 1)[0] for n in range(2, t.size + 1)]
    assert np.allclose(s, direct, rtol=1e-9, atol=1e-9)


def test_n_omega_window_keeps_everything_for_exact_line_and_drops_noisy_start():
    t = np.linspace(0.01, 10.0, 200)
    exact = fr.SpeedSamples(t, 400.0 - 25.0 * t)
    d = fr.n_omega_method(exact, 1.0)
    assert d.n_used == t.size - 1 and d.decel_rad_s2 == pytest.approx(25.0, rel=1e-10)
    noisy_w = 400.0 - 25.0 * t
    noisy_w[:5] += np.array([3.0, -3.0, 3.0, -3.0, 3.0])  # disturbed first revolutions
    d = fr.n_omega_method(fr.SpeedSamples(t, noisy_w), 1.0)
    assert not d.retained[:5].any() and d.retained[-1]


def test_equivalent_inertia_is_kinetic_energy_consistent():
    b = kin.bearing("6206")
    g = b.geometry
    I_orbit, I_spin = fr.ball_inertias_kg_m2(g, bearings=2)
    I_r, I_cage = 1.5e-3, 2.0e-5
    I_eq = fr.equivalent_inertia(I_r, I_cage + I_orbit, I_spin, g, form="energy")
    f = kin.frequencies(g, inner_hz=1.0, outer_hz=0.0)  # speeds per unit inner-ring speed
    energy = I_r + (I_cage + I_orbit) * f.cage_hz**2 + I_spin * f.ball_spin_hz**2
    assert I_eq == pytest.approx(energy, rel=1e-12)
    published = fr.equivalent_inertia(I_r, I_cage + I_orbit, I_spin, g, form="published")
    assert published == pytest.approx(I_r + (I_cage + I_orbit) * f.cage_hz + I_spin * f.ball_spin_hz, rel=1e-12)
    rho = 7810.0
    m = rho * math.pi * b.ball_diameter_m**3 / 6.0
    assert I_spin == pytest.approx(2 * b.balls * 0.4 * m * (b.ball_diameter_m / 2) ** 2, rel=1e-12)


def test_read_pulses_counts_and_periods(tmp_path):
    counts = tmp_path / "counts.csv"
    counts.write_text("count\n0\n16667\n33340\n50020\n66710\n")
    t = fr.read_pulses(counts, clock_hz=1e6)
    assert t[1] == pytest.approx(0.016667)
    periods = tmp_path / "periods.csv"
    periods.write_text("0.0167\n0.0168\n0.0169\n0.0170\n")
    t = fr.read_pulses(periods, periods=True)
    assert t.size == 5 and t[-1] == pytest.approx(0.0674)


def test_bad_inputs(tmp_path):
    with pytest.raises(InputError, match="increase strictly"):
        fr.validate_pulse_times([0.0, 0.1, 0.2, 0.2, 0.3, 0.4])
    with pytest.raises(InputError, match="at least 5"):
        fr.validate_pulse_times([0.0, 0.1, 0.2, 0.3])
    t = coast_down("constant", 0)
    with pytest.raises(InputError, match="inertia_kg_m2"):
        fr.friction_torque(t, -1e-3, "n-omega")
    with pytest.raises(InputError, match="method"):
        fr.friction_torque(t, 1e-3, "spline")
    with pytest.raises(InputError, match="rotor_inertia_kg_m2"):
        fr.equivalent_inertia(-1.0, 0.0, 0.0, kin.bearing("6204").geometry)
    with pytest.raises(InputError, match="must decrease"):
        fr.friction_torque(t[-1] - t[::-1], 1e-3, "t-omega")  # the record played backwards speeds up
    with pytest.raises(InputError, match="file not found"):
        fr.read_pulses(tmp_path / "missing.csv")

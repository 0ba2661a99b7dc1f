"""Each bath correlation against its published formula at a hand-checked point."""

import math

import ht
import numpy as np
import pytest

from quenchsim.bath import correlations as c
from quenchsim.bath.quenchant import fit_vogel, load_oil
from quenchsim.errors import InputError

G = 9.80665


def test_vogel_fit_reproduces_printed_viscosities_and_stays_physical():
    oil = load_oil("reference_quench_oil")
    assert np.allclose(oil.viscosity([40.0, 60.0, 100.0]), [0.0244, 0.0119, 0.0044], rtol=1e-9)
    T = np.linspace(20.0, 600.0, 200)
    mu = oil.viscosity(T)
    assert np.all(mu > 0) and np.all(np.diff(mu) < 0)
    # hand check of the closed form: mu(80 C) = exp(A + B/(353.15 - C))
    v = oil.viscosity
    assert float(v(80.0)) == pytest.approx(math.exp(v.A + v.B_K / (353.15 - v.C_K)))
    assert 0.0044 < float(v(80.0)) < 0.0119


def test_vogel_fit_rejects_unphysical_tables():
    with pytest.raises(InputError, match="viscosity"):
        fit_vogel([40.0, 60.0, 100.0], [0.01, 0.02, 0.005], "viscosity")
    with pytest.raises(InputError):
        fit_vogel([40.0, 60.0], [0.02, 0.01], "viscosity")


def test_round_jet_core_and_decay():
    # potential core: full exit speed up to x = 5.8 d; beyond, U_c = U_0 5.8 d / x (Pope 2000, Table 5.1)
    assert float(c.jet_centreline_velocity(2.0, 0.01, 0.05)) == pytest.approx(2.0)
    assert float(c.jet_centreline_velocity(2.0, 0.01, 0.20)) == pytest.approx(2.0 * 5.8 * 0.01 / 0.20)
    assert float(c.jet_half_width(0.01, 0.20)) == pytest.approx(0.094 * 0.20)
    assert float(c.jet_half_width(0.01, 0.01)) == pytest.approx(0.005)


def test_plane_wall_jet():
    # U_m = 3.5 sqrt(J'/(rho x)): J' = 10 N/m, rho = 860, x = 0.1 m -> 3.5 sqrt(10/86) = 1.1935 m/s
    assert float(c.plane_wall_jet_velocity(10.0, 860.0, 0.1)) == pytest.approx(1.19349, rel=1e-4)


@pytest.mark.parametrize("Re, Pr", [(1e3, 20.0), (3e4, 5.0), (1e6, 50.0)])
def test_flat_plate_local_nusselt(Re, Pr):
    laminar = 0.5 * 0.6774 * Re**0.5 * Pr ** (1 / 3) * (1 + (0.0468 / Pr) ** (2 / 3)) ** -0.25
    turbulent = 0.8 * 0.036 * Re**0.8 * Pr ** (1 / 3)
    assert float(c.flat_plate_local_nusselt(Re, Pr)) == pytest.approx(max(laminar, turbulent), rel=1e-12)
    # the local value is m times the plate average of ht (laminar m = 1/2, turbulent m = 0.8)
    assert laminar == pytest.approx(0.5 * ht.Nu_horizontal_plate_laminar_Churchill_Ozoe(Re, Pr))


def test_flat_plate_local_nusselt_hand_value():
    # Re = 1e5, Pr = 1: turbulent local 0.0288 Re^0.8 = 0.0288 * 10^4 = 288; laminar 0.3387 * 316.2 * 0.9894 = 106
    assert float(c.flat_plate_local_nusselt(1e5, 1.0)) == pytest.approx(288.0, rel=1e-9)


def test_vertical_plate_churchill_chu():
    Pr, Gr = 20.0, 1e8
    Ra = Pr * Gr
    expected = (0.825 + 0.387 * Ra ** (1 / 6) / (1 + (0.492 / Pr) ** (9 / 16)) ** (8 / 27)) ** 2
    assert float(c.vertical_plate_natural_nusselt(Pr, Gr)) == pytest.approx(expected)


@pytest.mark.parametrize("Ra", [1e5, 1e8, 1e11])
@pytest.mark.parametrize("up", [True, False])
def test_horizontal_plate_matches_ht_mcadams(Ra, up):
    Pr = 10.0
    ours = float(c.horizontal_plate_natural_nusselt(np.array(Pr), np.array(Ra / Pr), np.array(up)))
    assert ours == pytest.approx(ht.Nu_horizontal_plate_McAdams(Pr, Ra / Pr, buoyancy=up))


def test_zuber_water_textbook_value():
    # saturated water at 1 atm with K = 0.149: q_max = 1.26 MW/m2 (Incropera & DeWitt, Example 10.1)
    q = c.zuber_critical_heat_flux(0.0589, 2.257e6, 957.9, 0.5955, 0.149)
    assert q == pytest.approx(1.26e6, rel=0.01)


def test_ivey_morris_factor():
    # 1 + 0.1 (rho_l/rho_v)^0.75 c_p dT_sub / h_fg with rho_l/rho_v = 160, c_p dT/h_fg = 2000*100/2e5 = 1
    assert c.ivey_morris_factor(800.0, 5.0, 2000.0, 100.0, 2e5, 0.1) == pytest.approx(1 + 0.1 * 160**0.75)
    assert c.ivey_morris_factor(800.0, 5.0, 2000.0, -5.0, 2e5, 0.1) == 1.0


def test_rohsenow_heat_flux():
    rho_l, rho_v, mu, k, cp, hfg, sigma, Csf, n, dT = 860.0, 5.6, 5e-4, 0.13, 2000.0, 2e5, 0.01, 0.02, 1.7, 100.0
    Pr = cp * mu / k
    expected = mu * hfg * math.sqrt(G * (rho_l - rho_v) / sigma) * (cp * dT / (Csf * hfg * Pr**n)) ** 3
    assert float(c.rohsenow_heat_flux(dT, rho_l, rho_v, mu, k, cp, hfg, sigma, Csf, n)) == pytest.approx(expected, rel=1e-6)
    assert float(c.rohsenow_heat_flux(-3.0, rho_l, rho_v, mu, k, cp, hfg, sigma, Csf, n)) == 0.0


def test_bromley_and_forced_film_boiling():
    kv, rho_v, rho_l, mu_v, hfg, L, dT = 0.035, 5.0, 860.0, 1e-5, 2.5e5, 0.0125, 400.0
    expected = 0.62 * (kv**3 * rho_v * (rho_l - rho_v) * G * hfg / (mu_v * L * dT)) ** 0.25
    assert float(c.bromley_film_htc(dT, L, kv, rho_v, rho_l, mu_v, hfg, 0.62)) == pytest.approx(expected)
    assert float(c.forced_film_htc(1.0, dT, L, kv, rho_v, hfg, 2.7)) == pytest.approx(
        2.7 * math.sqrt(1.0 * kv * rho_v * hfg / (L * dT)))


def test_radiation_linearised():
    Ts, Ta = 800.0, 60.0
    h = float(c.radiation_htc(Ts, Ta, 0.8))
    q = 0.8 * 5.670374419e-8 * ((Ts + 273.15) ** 4 - (Ta + 273.15) ** 4)
    assert h * (Ts - Ta) == pytest.approx(q)


def test_churchill_usagi():
    assert float(c.churchill_usagi(3.0, 4.0, 2.0)) == pytest.approx(5.0)


def test_crossflow_drift_pratte_baines():
    # y/(R d) = 2.05 (x/(R d))^0.28: a jet with R = 0.4/0.2 = 2, d = 8 mm penetrating 60 mm drifts
    # x = R d (y/(2.05 R d))^(1/0.28) = 0.016 * 1.8293^3.5714 = 0.016 * 8.644 = 0.1383 m
    x = c.crossflow_drift(0.4, 0.008, 0.06, 0.2)
    assert x == pytest.approx(0.016 * (0.06 / (2.05 * 0.016)) ** (1 / 0.28), rel=1e-12)
    assert x == pytest.approx(0.1383, rel=1e-3)
    Rd = 2 * 0.008
    assert 0.06 / Rd == pytest.approx(2.05 * (x / Rd) ** 0.28)   # the trajectory passes through (x, y)
    assert c.crossflow_drift(0.4, 0.008, 0.06, 0.0) == 0.0
    assert c.crossflow_drift(2.0, 0.008, 0.06, 0.2) < c.crossflow_drift(1.0, 0.008, 0.06, 0.2)

"""Plausibility bounds on what a user brings to ``quenchsim quenchant fit``: the probe curve (checked before the fit,
one-line :class:`InputError`) and the fitted h(T_s) (a warning printed with the result).

The probe is the ISO 9950 / ASTM D6200 one: Inconel 600, 12.5 mm diameter, centre thermocouple, 850 C start
(materials/quenchants/iso9950_probe_inconel600.toml). The bounds are wide on purpose: they catch a wrong unit or a
wrong column (time in ms or in minutes, a water curve given as an oil), not an unusual oil.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from quenchsim.errors import InputError

MAX_CENTRE_RATE_C_S = 450.0
"""Upper bound of the probe's centre cooling rate, C/s: the conduction limit. With its surface held at the bath
temperature from immersion (infinite h), the centre of an infinite 12.5 mm Inconel 600 cylinder from 850 C into
40 C peaks at 312-419 C/s after ~1 s (Fourier series of the Dirichlet problem, diffusivity 4.0-5.3e-6 m2/s from the
data sheet's k, rho, c_p at 20-800 C, materials/quenchants/iso9950_probe_inconel600.toml); no quenchant can do more.
Measured oils give 40-150 C/s, water ~200-300 C/s (ASTM D6200 / ISO 9950 data sheets)."""

MAX_TIME_TO_300_C_S = 600.0
"""Upper bound of the time the probe's centre takes to reach 300 C, s. Even at h = 100 W/m2K on the whole
surface -- below the film-boiling h of any quench oil, about still air's convection plus radiation at 850 C -- the
lumped probe (rho c_p R / 2h = 8470 x 540 x 6.25e-3 / 200 = 143 s) reaches 300 C from 850 C in a 40 C bath in
ln(810 / 260) x 143 = 163 s, in a 200 C hot oil in ln(650 / 100) x 143 = 268 s. A curve that takes longer has its
time in the wrong unit (e.g. ms: 52,000 s)."""

MAX_OIL_HTC_W_M2K = 20000.0
"""Upper bound of a quench oil's still-bath h(T_s), W/m2K. The nucleate-boiling peak of quench oils lies at a few
thousand W/m2K (the shipped fast oil, materials/quenchants/astm_d6200_fast_oil.toml, peaks at 5,455 W/m2K at 567 C;
the quasi-steady starting estimate of the fit, quenchsim.fitting.quenchant.quasi_steady_htc, is clipped at this
constant); h well above 20,000 W/m2K is water or brine boiling, not oil. A fit above it is kept (the user may know
better) but warned about."""


PROBE_START_C = 850.0
"""The temperature the ISO 9950 / ASTM D6200 probe is quenched from, C (materials/quenchants/iso9950_probe_inconel600.toml)."""

KELVIN = 273.15


def kelvin_hint(temperature: npt.ArrayLike) -> str:
    """``"; is it in K? ..."`` when a probe curve's highest value is the probe's 850 C start in kelvin (within 100 K
    of 1123 K), else ``""``: the end of a message refusing the curve (in K a curve in an oil bath above 27 C never
    reaches 300 "C")."""
    T = np.asarray(temperature, dtype=float)
    if abs(float(T.max()) - KELVIN - PROBE_START_C) > 100.0:
        return ""
    return (f"; is it in K? (its highest value {float(T.max()):g} is the probe's {PROBE_START_C:g} C start in K; "
            "give degrees C)")


RATE_WINDOW_S = 0.5
"""Time window, s, over which a time curve's cooling rate is taken for :data:`MAX_CENTRE_RATE_C_S` (2 K of noise
between samples 0.01 s apart would read as 200 C/s; over 0.5 s as 4 C/s; the conduction-limit peak is ~1 s wide)."""


def check_probe_plausible(time_s: npt.ArrayLike | None, temperature_C: npt.ArrayLike, rate_C_s: npt.ArrayLike | None,
                          where: str = "curve") -> None:
    """Refuse a probe curve the ISO 9950 probe cannot have produced in a liquid: a centre rate above
    :data:`MAX_CENTRE_RATE_C_S` or, for a time curve, a time to 300 C above :data:`MAX_TIME_TO_300_C_S`."""
    T = np.asarray(temperature_C, dtype=float)
    if time_s is not None:
        t = np.asarray(time_s, dtype=float)
        below = np.flatnonzero(T <= 300.0)
        if below.size and t[below[0]] > MAX_TIME_TO_300_C_S:
            raise InputError(f"{where}: time_s (first point at or below 300 C)", float(t[below[0]]),
                             f"must be <= {MAX_TIME_TO_300_C_S:g} s: the 12.5 mm probe reaches 300 C in oil within "
                             "minutes (~160 s even at h = 100 W/m2K); is the time in ms?")
        # the rate over at least RATE_WINDOW_S, so thermocouple noise on finely sampled data is not a rate
        j = np.minimum(np.searchsorted(t, t + RATE_WINDOW_S), t.size - 1)
        keep = j > np.arange(t.size)
        i0, j = np.flatnonzero(keep), j[keep]
        rate = (T[i0] - T[j]) / (t[j] - t[i0])
        T_mid = 0.5 * (T[i0] + T[j])
    else:
        rate, T_mid = np.asarray(rate_C_s, dtype=float), T
    i = int(np.argmax(rate))
    if rate[i] > MAX_CENTRE_RATE_C_S:
        raise InputError(f"{where}: cooling rate at {T_mid[i]:.0f} C", round(float(rate[i]), 1),
                         f"must be <= {MAX_CENTRE_RATE_C_S:g} C/s, the probe's conduction limit (surface at the bath "
                         "temperature from immersion); is the time in minutes, or the rate in C/min?")


def htc_warning(T_C: np.ndarray, h_W_m2K: np.ndarray) -> str | None:
    """A warning when the fitted h(T_s) exceeds :data:`MAX_OIL_HTC_W_M2K` anywhere, else None."""
    h = np.asarray(h_W_m2K, dtype=float)
    i = int(np.argmax(h))
    if h[i] <= MAX_OIL_HTC_W_M2K:
        return None
    return (f"the fitted h(T_s) reaches {h[i]:,.0f} W/m2K at {float(T_C[i]):.0f} C, above {MAX_OIL_HTC_W_M2K:,.0f} "
            "W/m2K, the bound for a quench oil (oils peak at a few thousand; more is water boiling): check the "
            "curve's units, the bath temperature and that it is the probe's centre")

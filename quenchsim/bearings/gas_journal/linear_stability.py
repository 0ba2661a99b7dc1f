"""Linear whirl threshold of a rigid rotor from the frequency-dependent film impedance (Lund 1968).

A rigid rotor of dimensionless mass M (M = m c omega^2 / (8 pa L r), reference section 1) on the film:
M d2e/dT2 = -Z e. A neutral whirl e ~ exp(i tau T) (tau = 2 gamma, gamma = whirl frequency / rotor speed)
needs det(Z(gamma) - M tau^2 I) = 0: one eigenvalue lambda(gamma) of the 2 x 2 impedance real and positive,
M = lambda / tau^2. Because the gas film's impedance depends on the frequency, the threshold is found on the
real frequency axis: the eigenvalues are tracked over a scan of gamma, each sign change of Im(lambda) with
Re(lambda) > 0 is refined by Brent's method, and the lightest such rotor is the threshold (a rotor lighter
than every neutral one is stable when the film is: the orbit method checks that side). Mbar = 144 M / Lambda^2.

Away from the threshold the whirl of a rotor of mass M grows or decays: det(Z(gamma) - M tau^2 I) = 0 at a
complex tau, found by the secant method from the neutral whirl; exp(i tau T) grows at -Im(tau) per unit T,
the quantity the orbit method measures (orbit.whirl_analysis).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from quenchsim.bearings.gas_journal.linear import LinearisedFilm
from quenchsim.errors import SolverError, require

WHIRL_SCAN = (0.02, 1.0, 50)  # gamma from, to, points (whirl slower than the rotor)
NEAR_WINDOW, NEAR_POINTS = 0.08, 9  # scan about a coarser grid's neutral whirls: +-0.08 in gamma, 9 points
NEUTRAL_TOLERANCE = 1e-6  # a neutral whirl with Re(lambda) above -this x max |lambda| counts (M = 0 when <= 0)


@dataclass
class LinearThreshold:
    """Threshold mass M and Mbar = 144 M / Lambda^2 with its whirl ratio (NaN when no neutral whirl was found),
    and every neutral whirl found on the scan as (whirl ratio, M)."""

    critical_mass: float
    critical_mass_parameter: float
    whirl_ratio: float
    crossings: list[tuple[float, float]] = field(default_factory=list)


def _sorted_like(values: np.ndarray, previous: np.ndarray) -> np.ndarray:
    """Order the two eigenvalues ``values`` to follow ``previous`` (nearest match)."""
    keep = abs(values[0] - previous[0]) + abs(values[1] - previous[1])
    swap = abs(values[1] - previous[0]) + abs(values[0] - previous[1])
    return values if keep <= swap else values[::-1]


def linear_threshold(film: LinearisedFilm, whirl_scan: tuple[float, float, int] = WHIRL_SCAN,
                     near: tuple[float, ...] = ()) -> LinearThreshold:
    """Lightest rotor with a neutral whirl of ``film`` over whirl ratios ``whirl_scan`` (from, to, points).

    ``near``: whirl ratios of the neutral whirls found on a coarser grid of the same bearing; the scan is then
    only over windows of +-``NEAR_WINDOW`` about them (``NEAR_POINTS`` points each, ~1/3 of the full scan's
    film solves), and falls back to the full scan when no neutral whirl is found there."""
    lo, hi, n = whirl_scan
    require(0.0 < lo < hi and int(n) >= 3, "whirl_scan", whirl_scan, "must be (from, to, points) with "
            "0 < from < to and points >= 3")
    crossings = [c for g in near for c in _crossings(film, np.linspace(max(lo, g - NEAR_WINDOW),
                                                                         min(hi, g + NEAR_WINDOW), NEAR_POINTS))]
    if not crossings:
        crossings = _crossings(film, np.linspace(lo, hi, int(n)))
    if not crossings:
        return LinearThreshold(math.nan, math.nan, math.nan, [])
    gamma, mass = min(crossings, key=lambda c: c[1])
    return LinearThreshold(mass, 144.0 * mass / film.lam ** 2, gamma, sorted(set(crossings)))


def _crossings(film: LinearisedFilm, gammas: np.ndarray) -> list[tuple[float, float]]:
    """Neutral whirls (whirl ratio, M) between neighbouring whirl ratios of ``gammas`` (ascending)."""
    eig_list = [np.linalg.eigvals(film.impedance(gammas[0]))]
    for g in gammas[1:]:
        eig_list.append(_sorted_like(np.linalg.eigvals(film.impedance(g)), eig_list[-1]))
    eig = np.array(eig_list)
    crossings = []
    for branch in range(2):
        im = eig[:, branch].imag
        for k in np.nonzero(np.sign(im[:-1]) * np.sign(im[1:]) < 0)[0]:
            g0, g1 = gammas[k], gammas[k + 1]
            ref0, ref1 = eig[k], eig[k + 1]

            def tracked(g: float) -> complex:
                guess = ref0 + (ref1 - ref0) * (g - g0) / (g1 - g0)
                vals = _sorted_like(np.linalg.eigvals(film.impedance(g)), guess)
                return complex(vals[branch])

            g_star = brentq(lambda g: tracked(g).imag, g0, g1, xtol=1e-10, rtol=1e-10)
            lam = tracked(g_star)
            # Re(lambda) ~ 0 is the force-free whirl of a concentric plain film (threshold M = 0)
            if lam.real > -NEUTRAL_TOLERANCE * np.abs(eig).max():
                crossings.append((float(g_star), float(max(lam.real, 0.0) / (2.0 * g_star) ** 2)))
    return crossings


def whirl_root(film: LinearisedFilm, mass: float, whirl_guess: complex, tol: float = 1e-10,
               max_iterations: int = 50) -> tuple[float, float]:
    """(growth rate per unit T, whirl ratio) of the rotor of mass M = ``mass`` on ``film``: the root tau of
    det(Z(tau / 2) - M tau^2 I) = 0 nearest ``2 whirl_guess`` (secant iteration; a complex guess
    gamma - i g / 2 continues a root of growth rate g)."""
    require(mass > 0.0, "mass", mass, "must be > 0")

    def residual(tau: complex) -> complex:
        z = film.impedance(tau / 2.0) - mass * tau * tau * np.eye(2)
        return complex(z[0, 0] * z[1, 1] - z[0, 1] * z[1, 0])

    t0, t1 = complex(2.0 * whirl_guess), complex(2.0 * whirl_guess * (1.0 + 1e-3) + 1e-3j)
    r0, r1 = residual(t0), residual(t1)
    for _ in range(max_iterations):
        if r1 == r0:
            break
        t2 = t1 - r1 * (t1 - t0) / (r1 - r0)
        t0, r0, t1 = t1, r1, t2
        r1 = residual(t1)
        if abs(t1 - t0) < tol:
            return -t1.imag, t1.real / 2.0
    raise SolverError(f"whirl root of M = {mass:g} not found from whirl ratio {whirl_guess:g} "
                      f"(last tau {t1:.6g})")

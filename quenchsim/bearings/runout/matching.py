"""Kinematic identification of run-out lines.

Every line of the quasi-static models is an integer combination

    f = p f_r + q f_c + s f_b

of the rotating-ring speed f_r, the cage speed f_c and the ball spin f_b (relative to the cage),
from :mod:`quenchsim.bearings.kinematics`. A waviness of order l seen by the balls contributes
+-l (f_c - f_ring) (rotating ring: p = -+l, q = +-l; fixed ring: q = +-l) or +-l f_b (ball:
s = +-l), and the ball pattern turning with the cage adds m f_c (m = +-1 radial, 0 axial for
identical, equally spaced balls; any m once balls differ). So

    p = sum of rotating-ring orders,  s = sum of ball orders,  q = -p + a + m,

a = sum of fixed-ring orders, each sum taken over up to ``MAX_COMBINED_TERMS`` signed orders
present in the case (nonlinear terms combine several). A line is matched to the combination
within ``tolerance_bins`` of its frequency with the least complexity (number of combined orders
+ |m|), then the least error.

Labels use the reference's notation (sec. 2): f_i = f_r - f_c (inner ring relative to the cage,
inner rotating) or f_o = f_r - f_c (outer rotating), written in whichever of the forms
p f_r + q f_c, a f_rel + b f_r, a f_rel + b f_c is shortest, e.g. "8 f_i + f_r", "8 f_c",
"2 f_b - f_c". The 3-D reference (sec. 3) writes ball-pass frequencies instead: its
n f_i, n f_o are nZ f_c and nZ f_o in these labels (outer rotating, inner fixed).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

# Nonlinear terms of up to this many waviness harmonics are considered (the 3-D reference shows
# lines from orders nZ/j with j up to 3 carrying visible amplitude).
MAX_COMBINED_TERMS = 3
DEFAULT_TOLERANCE_BINS = 0.3


@dataclass(frozen=True)
class KinematicBasis:
    """The basic frequencies (Hz) and the name of the rotating ring's cage-relative frequency."""

    rotating_hz: float
    cage_hz: float
    spin_hz: float
    relative_name: str  # "f_i" (inner rotating) or "f_o" (outer rotating)


@dataclass(frozen=True)
class Match:
    """Integer combination f = p f_r + q f_c + s f_b, its label and its complexity (terms + |m|)."""

    p: int
    q: int
    s: int
    label: str
    complexity: int

    def frequency_hz(self, basis: KinematicBasis) -> float:
        return self.p * basis.rotating_hz + self.q * basis.cage_hz + self.s * basis.spin_hz


def _combinations(orders: list[int]) -> dict[int, int]:
    """{sum of up to MAX_COMBINED_TERMS signed orders: fewest terms needed} (0 -> 0 terms)."""
    best = {0: 0}
    signed = sorted(set(orders) | {-o for o in orders})
    for n in range(1, MAX_COMBINED_TERMS + 1):
        for combo in itertools.combinations_with_replacement(signed, n):
            value = sum(combo)
            best[value] = min(best.get(value, n), n)
    return best


def _format(terms: list[tuple[int, str]]) -> str:
    terms = [(c, n) for c, n in terms if c != 0]
    terms.sort(key=lambda t: t[0] < 0)
    out = ""
    for i, (c, name) in enumerate(terms):
        mag = abs(c)
        body = name if mag == 1 else f"{mag} {name}"
        if i == 0:
            out = ("-" if c < 0 else "") + body
        else:
            out += (" - " if c < 0 else " + ") + body
    return out or "0"


def label(p: int, q: int, s: int, relative_name: str) -> str:
    """Shortest of p f_r + q f_c, (-q) f_rel + (p+q) f_r, p f_rel + (p+q) f_c (f_rel = f_r - f_c), plus s f_b.

    Fewest terms first, then the smallest sum of |coefficients| (the third form pays 2 extra)."""
    forms = [[(p, "f_r"), (q, "f_c")], [(-q, relative_name), (p + q, "f_r")], [(p, relative_name), (p + q, "f_c")]]

    def cost(i: int) -> tuple[int, int]:
        # the reference writes rotating-ring lines as "nZ f_i +- f_r": prefer that form over
        # "a f_i + b f_c" unless the latter is shorter by more than one f_r
        form = forms[i]
        return (sum(1 for c, _ in form if c), sum(abs(c) for c, _ in form) + (2 if i == 2 else 0))

    form = forms[min(range(3), key=cost)]
    rel = [t for t in form if t[1] == relative_name]
    rest = [t for t in form if t[1] != relative_name]
    return _format(rel + [(s, "f_b")] + rest)


class Matcher:
    """Identifies line frequencies as kinematic combinations for one case (module docstring)."""

    def __init__(self, basis: KinematicBasis, rotating_orders: list[int], fixed_orders: list[int],
                 ball_orders: list[int], balls: int, bin_hz: float,
                 tolerance_bins: float = DEFAULT_TOLERANCE_BINS) -> None:
        self.basis = basis
        self.tolerance_hz = tolerance_bins * bin_hz
        self.max_m = balls + MAX_COMBINED_TERMS
        combos = [_combinations(o) for o in (rotating_orders, fixed_orders, ball_orders)]
        self.triples = [(p, a, s, tp + ta + ts) for (p, tp), (a, ta), (s, ts) in itertools.product(
            *(c.items() for c in combos)) if tp + ta + ts <= MAX_COMBINED_TERMS]

    def match(self, frequency_hz: float, signed: bool) -> Match | None:
        """Best combination for a line at frequency_hz; signed=False also accepts -f (real spectra)."""
        b = self.basis
        best: tuple[tuple[int, float], Match] | None = None
        for target in ((frequency_hz,) if signed else (frequency_hz, -frequency_hz)):
            for p, a, s, terms in self.triples:
                q = int(round((target - p * b.rotating_hz - s * b.spin_hz) / b.cage_hz))
                m = q + p - a
                err = abs(p * b.rotating_hz + q * b.cage_hz + s * b.spin_hz - target)
                if err > self.tolerance_hz or abs(m) > self.max_m:
                    continue
                sign = 1 if (target > 0 or signed) else -1
                match = Match(sign * p, sign * q, sign * s, label(sign * p, sign * q, sign * s, b.relative_name),
                              terms + abs(m))
                key = (terms + abs(m), err)
                if best is None or key < best[0]:
                    best = (key, match)
        return None if best is None else best[1]


def matcher_for(rotating_hz: float, cage_hz: float, spin_hz: float, rotating: str, rotating_orders: list[int],
                fixed_orders: list[int], ball_orders: list[int], balls: int, bin_hz: float) -> Matcher:
    """A :class:`Matcher` for a case's kinematics and the waviness orders on the rings and balls."""
    basis = KinematicBasis(rotating_hz, cage_hz, spin_hz, "f_i" if rotating == "inner" else "f_o")
    return Matcher(basis, rotating_orders, fixed_orders, ball_orders, balls, bin_hz)

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

import numpy as np

# Nonlinear terms of up to this many waviness harmonics are considered: third-order lines are
# ~1e-5 of the waviness at 0.1 um p-p on the 3-D standard model (reports/bearing_runout.md sec. 4),
# higher orders fall below the default peak threshold.
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


def _combinations(orders: list[int]) -> dict[int, list[int]]:
    """{number of terms: sums of exactly that many signed orders not reachable with fewer} for
    0 .. MAX_COMBINED_TERMS terms."""
    signed = sorted(set(orders) | {-o for o in orders})
    seen = {0}
    out = {0: [0]}
    for n in range(1, MAX_COMBINED_TERMS + 1):
        values = {sum(c) for c in itertools.combinations_with_replacement(signed, n)} - seen
        out[n] = sorted(values)
        seen |= values
    return out


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
        cp, ca, cs = (_combinations(o) for o in (rotating_orders, fixed_orders, ball_orders))
        rows = [(p, a, s, tp + ta + ts)
                for tp, ta, ts in itertools.product(range(MAX_COMBINED_TERMS + 1), repeat=3)
                if tp + ta + ts <= MAX_COMBINED_TERMS
                for p in cp.get(tp, []) for a in ca.get(ta, []) for s in cs.get(ts, [])]
        self.p, self.a, self.s, self.terms = (np.array(c, dtype=np.int64) for c in zip(*rows))

    def match(self, frequency_hz: float, signed: bool) -> Match | None:
        """Best combination for a line at frequency_hz; signed=False also accepts -f (real spectra)."""
        b = self.basis
        best: tuple[tuple[int, float], Match] | None = None
        for sign in ((1,) if signed else (1, -1)):
            target = sign * frequency_hz
            q = np.rint((target - self.p * b.rotating_hz - self.s * b.spin_hz) / b.cage_hz).astype(np.int64)
            err = np.abs(self.p * b.rotating_hz + q * b.cage_hz + self.s * b.spin_hz - target)
            m = q + self.p - self.a
            ok = (err <= self.tolerance_hz) & (np.abs(m) <= self.max_m)
            if not ok.any():
                continue
            complexity = self.terms + np.abs(m)
            i = min(np.flatnonzero(ok), key=lambda k: (complexity[k], err[k]))
            key = (int(complexity[i]), float(err[i]))
            if best is None or key < best[0]:
                pp, qq, ss = (sign * int(v) for v in (self.p[i], q[i], self.s[i]))
                best = (key, Match(pp, qq, ss, label(pp, qq, ss, b.relative_name), key[0]))
        return None if best is None else best[1]


def matcher_for(rotating_hz: float, cage_hz: float, spin_hz: float, rotating: str, rotating_orders: list[int],
                fixed_orders: list[int], ball_orders: list[int], balls: int, bin_hz: float) -> Matcher:
    """A :class:`Matcher` for a case's kinematics and the waviness orders on the rings and balls."""
    basis = KinematicBasis(rotating_hz, cage_hz, spin_hz, "f_i" if rotating == "inner" else "f_o")
    return Matcher(basis, rotating_orders, fixed_orders, ball_orders, balls, bin_hz)

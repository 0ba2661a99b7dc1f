"""The time-step controller of every thermal march (the quench, the Jominy bar, the ISO 9950 probe).

A step's *ratio* is its largest change over the change allowed per step (``max(dT / max_dT_K, dX / max_dX)``).
After a committed step the next one is

    dt_next = clip(dt * min(growth, target / ratio), dt_min_s, dt_max_s)          (``hold_over_limit`` False)
    dt_next = clip(dt * (growth if ratio < 1 else 1), dt_min_s, dt_max_s)        (``hold_over_limit`` True)

so a step well within its limits grows by ``growth``, one near them is aimed at ``target`` of them (the quench), or
held (the Jominy bar). A step whose ratio exceeds ``reject_above`` is retried at half its length while that stays
at or above ``dt_min_s``; a step the solver cannot converge is likewise halved. A march on a schedule fixed in
advance (the probe fit, whose steps must not depend on the fitted parameters) uses :meth:`StepController.ahead`:
the next step grows by ``growth`` up to ``dt_max_s`` and to the length its expected change allows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

TARGET = 0.9
"""Share of the per-step limits the quench aims the next step at (a step near them is not rejected next time)."""
REJECT_ABOVE = 2.0
"""A quench step beyond this multiple of its limits is retried at half its length."""


@dataclass(frozen=True)
class StepController:
    """The step rule (module docstring). ``max_dT_K`` and ``max_dX`` are the changes allowed per step (inf: no
    limit)."""

    growth: float
    dt_min_s: float = 0.0
    dt_max_s: float = math.inf
    max_dT_K: float = math.inf
    max_dX: float = math.inf
    target: float = TARGET
    reject_above: float = math.inf
    hold_over_limit: bool = False

    def ratio(self, dT_K: float, dX: float = 0.0) -> float:
        """The step's change over its limits: the larger of ``dT_K / max_dT_K`` and ``dX / max_dX``."""
        return max(dT_K / self.max_dT_K, dX / self.max_dX)

    def can_halve(self, dt_s: float) -> bool:
        """Whether half of ``dt_s`` is still a step (at or above ``dt_min_s``)."""
        return dt_s / 2 >= self.dt_min_s

    def rejects(self, dt_s: float, ratio: float) -> bool:
        """Whether a step of ``dt_s`` with ``ratio`` is to be retried at half its length."""
        return ratio > self.reject_above and self.can_halve(dt_s)

    def next_dt(self, dt_s: float, ratio: float) -> float:
        """The step after a committed step of ``dt_s`` with ``ratio``."""
        if self.hold_over_limit:
            grow = self.growth if ratio < 1.0 else 1.0
        else:
            grow = self.growth if ratio < 1e-12 else min(self.growth, self.target / ratio)
        return float(np.clip(dt_s * grow, self.dt_min_s, self.dt_max_s))

    def ahead(self, dt_s: float, allowed_s: float) -> float:
        """The next step of a schedule fixed in advance: ``dt_s`` grown, at most ``dt_max_s`` and ``allowed_s`` (the
        length over which the expected change stays within its limit)."""
        return min(dt_s * self.growth, self.dt_max_s, allowed_s)

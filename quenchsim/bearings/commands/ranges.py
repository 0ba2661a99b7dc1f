"""Physical ranges of the bearing verbs' numeric options, checked before a verb does any work.

Each verb module may define ``RANGES = {dest: Range(...)}`` (``dest``: the argparse attribute, e.g.
``"speed"`` for ``--speed``); :func:`check_ranges` raises one :class:`~quenchsim.errors.InputError` naming the
option, its value and the allowed range. The limits are the widest values the models can mean physically
(a speed no rolling bearing reaches, a temperature no grease survives), not the models' validity ranges,
which the verbs report as warnings where they have them.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Mapping
from dataclasses import dataclass

from quenchsim.errors import InputError


@dataclass(frozen=True)
class Range:
    """``low <= value <= high`` (``low_open``/``high_open``: the end itself excluded), finite, with its unit."""

    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False
    unit: str = ""
    integer: bool = False
    nonzero: bool = False

    def contains(self, value: float) -> bool:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            return False
        if (self.integer and value != int(value)) or (self.nonzero and value == 0):
            return False
        above = value > self.low if self.low_open else value >= self.low
        below = value < self.high if self.high_open else value <= self.high
        return above and below

    def describe(self) -> str:
        kind = ("an integer" if self.integer else "a finite number") + (" other than 0" if self.nonzero else "")
        unit = f" {self.unit}" if self.unit else ""
        if math.isinf(self.low) and math.isinf(self.high):
            return f"must be {kind}{unit}"
        if math.isinf(self.high):
            return f"must be {kind} {'>' if self.low_open else '>='} {self.low:g}{unit}"
        if math.isinf(self.low):
            return f"must be {kind} {'<' if self.high_open else '<='} {self.high:g}{unit}"
        left, right = "(" if self.low_open else "[", ")" if self.high_open else "]"
        return f"must be {kind} in {left}{self.low:g}, {self.high:g}{right}{unit}"


def check_ranges(args: argparse.Namespace, ranges: Mapping[str, Range]) -> None:
    """Raise :class:`InputError` for the first option of ``args`` outside its range (lists: every value)."""
    for dest, allowed in ranges.items():
        value = getattr(args, dest, None)
        for v in value if isinstance(value, (list, tuple)) else [value]:
            if v is not None and not allowed.contains(v):
                raise InputError("--" + dest.replace("_", "-"), v, allowed.describe())


SPEED_RPM = Range(-1e6, 1e6, unit="rpm")
"""A ring speed: +-1e6 rpm is beyond any rolling bearing (dental turbines run at ~4e5 rpm)."""
DIAMETER_MM = Range(0.0, 1e4, low_open=True, unit="mm")
"""A bearing diameter: positive, below 10 m (the largest slewing bearings are ~8 m)."""
CONTACT_ANGLE_DEG = Range(0.0, 90.0, high_open=True, unit="deg")
BALLS = Range(1, 1000, integer=True)
GEOMETRY: dict[str, Range] = {"pitch_diameter_mm": DIAMETER_MM, "ball_diameter_mm": DIAMETER_MM, "balls": BALLS,
                              "contact_angle_deg": CONTACT_ANGLE_DEG}
"""The shared geometry options (``--pitch-diameter-mm``, ``--ball-diameter-mm``, ``--balls``,
``--contact-angle-deg``)."""

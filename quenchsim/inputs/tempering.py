"""A steel's tempering data file (``materials/data/tempering_1C_Cr.toml``, named by the steel file's ``tempering``
key): the Hollomon-Jaffe clock, the tempering reactions, the tempered martensite's hardness and the relaxation of the
residual stress, declared once; what they mean: :mod:`quenchsim.metallurgy.tempering`, which builds the model."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from quenchsim.errors import require
from quenchsim.inputs.declare import REQUIRED, Table, quantity
from quenchsim.inputs.properties import check_formula

PHASE = Literal["austenite", "pearlite", "bainite", "martensite"]
PRODUCT = Literal["pearlite", "bainite", "martensite"]
HARDNESS_LAWS = ("linear_in_P", "quadratic_in_P")


@dataclass(frozen=True, kw_only=True)
class Clock(Table):
    """``[clock]``: the Hollomon-Jaffe parameter P = T (C + log10 t), C a linear formula of the carbon."""

    law: Literal["hollomon_jaffe"] = quantity(REQUIRED, doc="the clock", allowed="needs law = 'hollomon_jaffe'")
    carbon: Literal["bulk", "dissolved"] = quantity("dissolved", doc="the carbon the constant takes")
    constant_formula: Mapping[str, float | str] = quantity(REQUIRED, doc="C = const + C x carbon (wt %), with "
                                                            "its source")

    def check(self) -> None:
        terms = {k: v for k, v in self.constant_formula.items() if k != "source"}
        require(all(isinstance(v, float) for v in terms.values()), "constant_formula", dict(self.constant_formula),
                "its terms must be numbers")
        check_formula({k: float(v) for k, v in terms.items()}, "constant_formula")

    @property
    def formula(self) -> dict[str, float]:
        """The formula's terms (its source left out)."""
        return {k: float(v) for k, v in self.constant_formula.items() if k != "source"}


@dataclass(frozen=True, kw_only=True)
class ProgressPoint(Table):
    """A published point of a tempering reaction: its progress after ``time_h`` hours at ``T_C``."""

    T_C: float = quantity(REQUIRED, unit="C", doc="hold temperature")
    time_h: float = quantity(REQUIRED, unit="h", gt=0.0, doc="hold time")
    progress: float = quantity(REQUIRED, gt=0.0, lt=1.0, doc="share of the reaction done")


@dataclass(frozen=True, kw_only=True)
class StressPoint(Table):
    """A point of the relaxation: the stress left (a share of the start's) after ``time_h`` hours at ``T_C``."""

    T_C: float = quantity(REQUIRED, unit="C", doc="hold temperature")
    time_h: float = quantity(REQUIRED, unit="h", gt=0.0, doc="hold time")
    stress_ratio: float = quantity(REQUIRED, gt=0.0, lt=1.0, doc="stress left over stress at the start")


@dataclass(frozen=True, kw_only=True)
class TemperReaction(Table):
    """``[reactions.NAME]``: a tempering reaction of ``parent`` through two published points; a martensite reaction
    contracts it by ``volume_change_pct_per_C`` (per wt % dissolved carbon), the austenite's decomposition forms
    ``product``."""

    parent: PHASE = quantity(REQUIRED, doc="the phase that tempers")
    product: PRODUCT | None = quantity(None, doc="the austenite's product (the austenite's decomposition only)")
    points: tuple[ProgressPoint, ...] = quantity(REQUIRED, doc="two {T_C, time_h, progress} points, the later one "
                                                 "second", allowed="needs exactly two {T_C, time_h, progress} points")
    points_source: str = quantity("", doc="where the points come from")
    volume_change_pct_per_C: float | None = quantity(None, unit="%/wt%", sourced=True,
                                                     doc="a martensite reaction's volume change per wt % carbon")

    def check(self) -> None:
        require(len(self.points) == 2, "points", len(self.points), "needs exactly two {T_C, time_h, progress} points")
        if self.parent == "austenite":
            require(self.product is not None, "product", None, "the austenite's product must be one of "
                    "pearlite, bainite, martensite")
        else:
            require(self.volume_change_pct_per_C is not None, "volume_change_pct_per_C", None, "must be a finite "
                    "number")


@dataclass(frozen=True, kw_only=True)
class TemperHardness(Table):
    """``[hardness]``: published hardness after tempering of a specimen, to which HV_TM(P) is fitted."""

    law: str = quantity(REQUIRED, choices=HARDNESS_LAWS, doc="HV_TM(P): a line or a parabola in P")
    source: str = quantity("", doc="where the table comes from")
    austenitising_temperature_C: float = quantity(REQUIRED, unit="C", sourced=True, doc="the specimens' hardening")
    room_temperature_C: float = quantity(25.0, unit="C", sourced=True, doc="the specimens' quench end")
    time_h: float = quantity(REQUIRED, unit="h", gt=0.0, sourced=True, doc="the tempering time")
    T_C: tuple[float, ...] = quantity(REQUIRED, unit="C", doc="tempering temperatures")
    HRC: tuple[float, ...] = quantity(REQUIRED, unit="HRC", doc="hardness after tempering, one per T_C")

    def check(self) -> None:
        require(len(self.T_C) >= 2 and len(self.HRC) == len(self.T_C), "HRC", list(self.HRC),
                "needs at least two HRC values, one per T_C")


@dataclass(frozen=True, kw_only=True)
class Relaxation(Table):
    """``[relaxation]``: the residual stress's relaxation through two points."""

    points: tuple[StressPoint, ...] = quantity(REQUIRED, doc="two {T_C, time_h, stress_ratio} points")
    source: str = quantity("", doc="where the points come from")

    def check(self) -> None:
        require(len(self.points) == 2, "points", len(self.points),
                "needs exactly two {T_C, time_h, stress_ratio} points")


@dataclass(frozen=True, kw_only=True)
class TemperingData(Table):
    """A tempering data file."""

    source: str = quantity("", doc="where the data come from")
    clock: Clock = quantity(REQUIRED, doc="the Hollomon-Jaffe clock")
    hardness: TemperHardness = quantity(REQUIRED, doc="the tempered martensite's hardness")
    reactions: Mapping[str, TemperReaction] = quantity({}, doc="the tempering reactions")
    relaxation: Relaxation = quantity(REQUIRED, doc="the residual stress's relaxation")

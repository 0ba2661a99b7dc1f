"""Whether a kinetics fit can be believed: the quality check after every ``quenchsim material fit`` and the check of
its data for a unit slip.

**Quality.** Every compared quantity has a normalised residual, (model - data) / its stated uncertainty
(:class:`quenchsim.fitting.kinetics.Residual`). A fit whose worst one exceeds :data:`POOR_FIT_LIMIT` is poor:
``material fit`` prints a WARNING naming the point, and the written steel's fit record says ``fit_quality_flag = 1``
(0 when every point lies within the limit). 3 is the usual outlier rule: a Gaussian error exceeds it with
probability 0.27 %; the shipped fits stay within 2.6 (materials/SUJ2.toml, materials/SUJ3.toml).

**Unit slips.** The data file's numbers are compared as given and as they would be with

* the TTT times divided by 1000 (times in ms given as s), and
* the TTT hold temperatures minus 273.15 (temperatures in K given as C; a CCT line in K is refused by the data
  check, above its curve's start):

first against the kinetics of the file's base material (before the fit: does the data file describe a steel like it
in another unit?), then -- when the fit is poor or fails -- by fitting the changed data. A change is reported when it
brings the quantities it touches far closer: a cost (half the sum of squared normalised residuals) at most
:data:`SLIP_COST_RATIO` of the cost as given, and within :data:`POOR_FIT_LIMIT` where the data as given are not. It is
a hint (the data may describe a steel quite unlike the base material), never a change made to the data.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from quenchsim.errors import QuenchsimError
from quenchsim.fitting.diagram_data import DiagramData
from quenchsim.fitting.kinetics import FitResult, Residual, fit_kinetics, residuals
from quenchsim.materials import load_material
from quenchsim.metallurgy import Kinetics, load_kinetics

POOR_FIT_LIMIT = 3.0
"""Largest normalised residual (|model - data| / uncertainty) of a fit that is not flagged as poor."""
SLIP_COST_RATIO = 0.01
"""A unit change is reported when it cuts the cost of the quantities it touches to at most this share."""
KELVIN = 273.15


@dataclass(frozen=True)
class UnitSlip:
    """One way the data file's numbers may be in the wrong unit: its name, the hint shown, and the changed data."""

    what: str
    hint: str
    change: Callable[[DiagramData], DiagramData]
    touches: Callable[[Residual], bool]


def _times_in_ms(data: DiagramData) -> DiagramData:
    return dataclasses.replace(data, ttt=tuple(dataclasses.replace(p, t_start_s=p.t_start_s / 1000.0,
                                                                   t_finish_s=p.t_finish_s / 1000.0) for p in data.ttt))


def _holds_in_k(data: DiagramData) -> DiagramData:
    return dataclasses.replace(data, ttt=tuple(dataclasses.replace(p, T_C=p.T_C - KELVIN) for p in data.ttt))


def _ttt_time(r: Residual) -> bool:
    return r.quantity.endswith(" time")


UNIT_SLIPS = (
    UnitSlip("the TTT times / 1000", "were they given in ms?", _times_in_ms, _ttt_time),
    UnitSlip("the TTT hold temperatures - 273.15", "were they given in K?", _holds_in_k, _ttt_time),
)
"""The unit slips looked for. A CCT line in K lies above its curve's start (the austenitising temperature) and is
refused by the data check (:mod:`quenchsim.fitting.diagram_data`); a TTT hold in K may still lie below it."""


def worst_residual(res: Sequence[Residual]) -> Residual | None:
    """The compared quantity with the largest |normalised residual| (None without any)."""
    return max(res, key=lambda r: abs(r.residual), default=None)


def quality_warning(result: FitResult) -> str | None:
    """The WARNING of a poor fit (worst |normalised residual| above :data:`POOR_FIT_LIMIT`), else None."""
    worst = worst_residual(result.residuals)
    if worst is None or abs(worst.residual) <= POOR_FIT_LIMIT:
        return None
    over = sum(abs(r.residual) > POOR_FIT_LIMIT for r in result.residuals)
    return (f"poor fit: {over} of {len(result.residuals)} compared quantities lie beyond {POOR_FIT_LIMIT:g} times "
            f"their uncertainty, the worst {worst.where} {worst.quantity} at {worst.residual:+.1f} (data "
            f"{worst.data:.4g}, model {worst.model:.4g} {worst.unit}): the data contradict each other or the model "
            "(check the points named, their units and uncertainties) -- do not use this steel as it is")


def _cost(res: Sequence[Residual], touches: Callable[[Residual], bool]) -> tuple[float, float]:
    """Half the sum of squares and the worst |value| of the normalised residuals that ``touches`` selects."""
    values = np.array([r.residual for r in res if touches(r)])
    return (0.5 * float(values @ values), float(np.max(np.abs(values)))) if values.size else (0.0, 0.0)


def _far_better(given: tuple[float, float], changed: tuple[float, float]) -> bool:
    return given[1] > POOR_FIT_LIMIT and changed[1] <= POOR_FIT_LIMIT and changed[0] <= SLIP_COST_RATIO * given[0]


def base_kinetics_of(data: DiagramData) -> Kinetics:
    """The base material's own kinetics (every reaction, the fitted ones too) at the data's austenitising temperature."""
    return load_kinetics(load_material(data.material, field=f"{data.path.name}: material"), data.T_aust_C)


def _compared(kin: Kinetics, data: DiagramData) -> list[Residual]:
    """The residuals of the points whose product the kinetics model (CCT lines and TTT times; no Jominy bar)."""
    kept = dataclasses.replace(
        data, jominy=(), ttt=tuple(p for p in data.ttt if p.phase in kin.reactions),
        cct=tuple(dataclasses.replace(p, start_C={k: v for k, v in p.start_C.items() if k in kin.reactions or k == "martensite"},
                                      finish_C={k: v for k, v in p.finish_C.items() if k in kin.reactions},
                                      fractions={k: v for k, v in p.fractions.items() if k != "ferrite" or k in kin.reactions})
                  for p in data.cct))
    return residuals(kin, kept)


def slips_against_base(data: DiagramData) -> list[str]:
    """Unit slips the base material's own kinetics point to (cheap: no fit); each hint a sentence."""
    kin = base_kinetics_of(data)
    given = _compared(kin, data)
    hints = []
    for slip in UNIT_SLIPS:
        before, after = _cost(given, slip.touches), _cost(_compared(kin, slip.change(data)), slip.touches)
        if _far_better(before, after):
            hints.append(f"with {slip.what} the data match the base material {data.material}'s kinetics far better "
                         f"(worst {after[1]:.1f} against {before[1]:.1f} times the uncertainty as given): {slip.hint}")
    return hints


def slips_by_refit(data: DiagramData, jominy_histories: tuple[np.ndarray, np.ndarray] | None,
                   result: FitResult | None) -> list[str]:
    """Unit slips a fit of the changed data points to, when the fit as given is poor (``result``) or failed (None)."""
    hints = []
    for slip in UNIT_SLIPS:
        changed = slip.change(data)
        if changed == data:
            continue
        try:
            refit = fit_kinetics(changed, jominy_histories)
        except QuenchsimError:
            continue
        after = _cost(refit.residuals, slip.touches)
        before = _cost(result.residuals, slip.touches) if result is not None else (np.inf, np.inf)
        worst_after = abs(r.residual) if (r := worst_residual(refit.residuals)) else 0.0
        if _far_better(before, after) and worst_after <= POOR_FIT_LIMIT:
            hints.append(f"with {slip.what} the data fit far better (worst {worst_after:.1f} times the uncertainty"
                         + (f" against {before[1]:.1f} as given" if np.isfinite(before[1]) else "") + f"): {slip.hint}")
    return hints


def fit_record(result: FitResult, warnings: Sequence[str]) -> dict[str, object]:
    """The quality entries of the written fit record ([kinetics.fit]): ``fit_quality_flag`` 1 with any warning (a poor
    fit or a unit slip), else 0; the worst normalised residual, the limit, and the warnings."""
    worst = worst_residual(result.residuals)
    return {"fit_quality_flag": 1 if warnings else 0,
            "worst_normalised_residual": abs(worst.residual) if worst is not None else 0.0,
            "poor_fit_limit": POOR_FIT_LIMIT, "warnings": list(warnings)}

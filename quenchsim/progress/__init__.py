"""The progress bar of a run: one bar over all stages in simulated seconds, with a time-left estimate.

A run's simulated seconds pass at very different speeds (steps of milliseconds while the vapour film collapses,
of minutes in air), so a bar and an estimate in simulated seconds (tqdm's remaining seconds over their recent
rate) swing from hours to nothing. The bar here fills with a measure of the work that advances more evenly
(:class:`CoolingProgress`), shows the simulated seconds beside it, and its time-left estimate counts the steps
left from what limits the step (:meth:`CoolingProgress.steps_left`) and never rises (:class:`TimeLeft`).
"""

from __future__ import annotations

import logging
import math
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from tqdm import tqdm

from quenchsim.thermal.steps import TARGET

log = logging.getLogger("quenchsim")

BAR_FORMAT = "{desc}: {percentage:3.0f}%|{bar}| [{elapsed}{postfix}]"
"""The postfix carries the simulated seconds (one decimal) and the time left."""
STEPS = 1000
"""The bar counts thousandths of the run's work."""
UPDATE_EVERY_S = 0.5
"""Seconds of the bar's clock between two updates of the bar and its estimate (:meth:`RunProgress.due`); the steps in
between are only recorded for the price of a step (:meth:`TimeLeft.record`). An update costs ~0.5 ms (1.4 ms with
the forecast checks) and updating after every step took 2.5 % of ring A condition 1's CPU time (issue 48)."""
FORECAST_EVERY_STEPS = 16
"""Steps between two forecasts of the pearlite + bainite still to form (each costs about a step's metallurgy)."""
FORECAST_EVERY_S = 3.0
"""And seconds of the bar's clock between them, at least: a forecast costs 10-15 ms (ring A condition 1, 431 points
of 13,800), so at every 16 steps the forecasts alone took 1.4 % of the run's CPU time; every 3 s they take < 0.5 %."""
MARTENSITE_FORECAST_EVERY_STEPS = 8
"""Steps between two forecasts of the stress steps the martensite still needs (:meth:`CoolingProgress._martensite_steps`;
each costs a few milliseconds): where a front crosses the section, 16 steps are some 50 stress steps, over which the
forecast less what was taken since went stale."""
MARTENSITE_FORECAST_EVERY_S = 1.0
"""And seconds of the bar's clock between them, at least (a forecast costs 1-3 ms)."""
PACE_MIN_STEPS = 8
"""Steps of the phase-fraction limit before their pace (pearlite + bainite formed per step) is taken as known."""
FILM_PACE_SHARE = 0.1
"""The film's end is extrapolated from how fast its farthest point cooled over the last tenth of the film's time: its
cooling speeds up as the wetting front nears (over the last fifth, ring B condition 6's film was 2-3x late)."""
STEPS_PER_LIMIT_OF_MEAN = 3.5
"""Steps the pearlite/bainite limit holds per ``time.max_dX`` (at 90 %) of the mean pearlite + bainite still to form,
before the limit has held and its own pace is known: the limit holds at the fastest-transforming point, while the
mean forms at the rate of the front, a fraction of the section. Measured on ring A condition 1 (session 11, code of
6199ce5): 3.3-3.7 throughout its ~600 steps of the limit (docs/experiments/time_left_diffusional_forecast.md)."""
PRICE_WINDOW_SHARE = 0.3
"""The time per step is taken over the last 30 % of the steps so far (at least :data:`PRICE_WINDOW_MIN_STEPS`)."""
PRICE_WINDOW_MIN_STEPS = 10
PRICE_MEDIAN_MIN_STEPS = 50
"""The median step (:data:`PRICE_OUTLIER_FACTOR`) is taken over at least this many of the last steps, so that a short
window where most steps are one-offs (the film's first collapse) does not take them for the norm."""
PRICE_OUTLIER_FACTOR = 3.0
"""A step dearer than this many times the median step is a one-off, not priced (:meth:`TimeLeft._price`): where the
vapour film first collapses, tries are thrown away (the thermal iteration at its limit) and the steps cost 3-14x the
median on ring B condition 6, 7-25x on the solid cylinder. A step that refactorises the stress tangent stays in
(41 ms on ring A's default mesh, docs/experiments/bench.md, about 2x a stress step's 20-27 ms)."""


@dataclass(frozen=True)
class StepState:
    """What the run passes to :meth:`CoolingProgress.steps_left` after each step.

    ``stage_clock_left_s``: simulated seconds left on the current stage's clock; ``ends_on_temperature``: the
    current stage is the one that ends at the end temperature; ``later_stages``: per stage still to come, its
    clock and, for the stage that ends on the end temperature, its Newton cooling rate ``h A / C`` (1/s; None
    for a stage that runs its clock); ``surface_mean_C``: the mean temperature of the cooled surface;
    ``film_excess_K``: how far the surface point farthest above its film-collapse temperature
    (:func:`film_collapse_temperatures`) still is above it (<= 0: no vapour film anywhere); ``film_wetted_share``:
    the share of the surface points with a film-collapse temperature that have cooled below it (their film has
    collapsed; 0 while the film holds everywhere);
    ``austenite_fraction``: the mean fraction still to transform (0 for a steel that does not);
    ``limited_by_phase_change``: the phase-fraction limit ``time.max_dX`` held the last step rather than the
    temperature limit ``time.max_dT_K``; ``incubation_share``: the largest share of its incubation any point has
    run for a diffusional reaction (:func:`quenchsim.metallurgy.incubation_share`; 1 once one has started);
    ``diffusional_fraction``: the mean fraction of pearlite + bainite formed so far; ``diffusional_to_come``: asked
    only when the estimate needs it, the mean fraction of pearlite + bainite still to form
    (:func:`quenchsim.progress.forecasts.diffusional_fraction_to_come` at each point's cooling rate now; None: not known);
    ``stage_ambient_C``: the current stage's ambient (the bath; NaN: not known); ``martensite_fraction``: the mean
    martensite formed so far; ``martensite_limit_steps``: asked only when the estimate needs it, the steps a limit of
    ``time.mechanics_max_dX`` on the martensite still needs
    (:func:`quenchsim.progress.forecasts.martensite_limit_steps_to_come`; None: no martensite to form);
    ``stress_steps_done``: the stress steps taken so far; ``clock_s``: the bar's clock, for the forecasts' spacing
    (:data:`FORECAST_EVERY_S`; NaN: no clock, the steps alone space them); ``limited_by_phase_change`` holds if the limit held at any step since the last
    update."""

    steps_done: int
    time_s: float
    T_nodes_C: np.ndarray
    dt_next_s: float
    stage_clock_left_s: float
    ends_on_temperature: bool
    later_stages: Sequence[tuple[float, float | None]] = ()
    surface_mean_C: float = -math.inf
    film_excess_K: float = -math.inf
    film_wetted_share: float = 0.0
    austenite_fraction: float = 0.0
    limited_by_phase_change: bool = False
    incubation_share: float = 0.0
    diffusional_fraction: float = 0.0
    diffusional_to_come: Callable[[], float] | None = None
    stage_ambient_C: float = math.nan
    martensite_fraction: float = 0.0
    martensite_limit_steps: Callable[[], float] | None = None
    stress_steps_done: int = 0
    clock_s: float = math.nan


class CoolingProgress:
    """How far a run's cooling is and how many steps it still needs.

    The fraction done is the mean nodal temperature between the austenitising temperature and the run's end
    temperature (the bar's fill). Not simulated time, whose work per second falls by orders of magnitude from
    the quench to the air; and the nodes weigh equally, not by volume: the step limit is on nodal temperature
    changes, so the fine surface layer, where the nodes crowd, is where the steps go.

    The steps left (:meth:`steps_left`) come from the step limit that holds:

    * the fewest steps that cover the simulated time left, growing from the next step by ``time.growth`` up to
      ``time.dt_max_s`` (:meth:`_steps_to_cover`), the time left being the stages' clocks or, in a stage that ends
      on a temperature, when the mean's exponential decay towards the ambient reaches the end temperature
      (Newton's cooling: its rate over the last step in that stage, before it the stage's ``h A / C``, from the mean
      the current stage will leave, :meth:`_excess_at_stage_end`). Since no
      step is longer or grows faster, this is also a floor on every other estimate, so a long air stage of capped
      steps is counted while the quench still runs, and so are the growing steps of a short air stage (the small
      ring of the tests: its last ~10 steps, counted as 3-5 by the scaling before this floor).
    * until the phase-fraction limit ``time.max_dX`` first holds, a count of what each limit still needs: while a
      vapour film holds somewhere, the film's time left at the steps per simulated second since the first point's
      film collapsed (:meth:`_film_steps`; not known until :data:`PACE_MIN_STEPS` steps after it, and no estimate
      is shown meanwhile); then the surface's and the hottest node's drops to the end temperature over the
      temperature limit ``time.max_dT_K`` (the limit holds at the surface first, inside later; steps at 90 % of
      the limit, as the controller aims); the steps of the pearlite/bainite limit, :data:`STEPS_PER_LIMIT_OF_MEAN`
      times the mean pearlite + bainite still to form (:func:`quenchsim.progress.forecasts.diffusional_fraction_to_come`,
      each point cooling on at its own rate, asked every :data:`FORECAST_EVERY_STEPS` steps and :data:`FORECAST_EVERY_S`) over 0.9 ``max_dX``,
      counted as far as the incubation of pearlite or bainite has run somewhere (``incubation_share``: the limit
      holds only those, which form once incubated); and the steps the growth factor needs to reach
      ``time.dt_max_s``. Once no film holds, the least of that count and the steps so far scaled by the cooling
      still to do (the fraction above). Under a film the scaling is no guide: in an agitated bath the surface cools
      the mean by a tenth in the film's first ~16 steps of up to 1.4 s, and ~600 steps of 0.03-0.13 s follow while
      the wetting front runs over the surface (ring A condition 3); in still oil the film's slow steps would count
      for all the cooling after it.
    * once the phase-fraction limit has held: the least of the scaling and the forecast still to form over the
      fraction formed per step since the limit first held, plus the drops and growth steps. The scaling alone
      counts a pace that holds while the front runs through the part; near the end of the transformation most of
      the austenite left turns to martensite instead (2.3-2.6x high on ring A).

    The estimate shown never rises (:class:`TimeLeft`, which also prices the steps), so where the model must guess
    it errs high, never low. Measured on every shipped quench case at the BDF2 step limits (the share of the steps
    between 10 % and 90 % of the run whose estimate is within a factor 2 of the real time left, CPU clock, and the
    range of estimate / real; session 14, docs/experiments/martensite_front_time_left.md keeps the models before and
    how each was measured): ring A conditions 1, 2, 3 100 % (0.94..1.86, 0.79..1.76, 0.70..1.65), condition 1 with
    ``time.max_dX = 0.01`` 100 % (0.81..1.67); ring B conditions 4, 5 100 % (0.68..1.62, 0.89..1.81), 6 95 %
    (0.93..1.64: 9-10 steps without an estimate while the pace after the first wetting is measured); the peer race in
    water 100 % (0.80..1.34), with ``time.max_dX = 0.01`` 100 % (0.68..1.15), where its martensite front splits 214
    thermal steps into 642 stress steps (7 % and 15 % before the front's steps were forecast); the solid cylinder in
    still oil 98 % (0.53..0.96). Before the film's pace and the pearlite/bainite forecast the agitated baths missed:
    ring A condition 3 65 % (0.18..1.63), ring B 84 %, 85 %, 48 % (0.27..3.23)."""

    def __init__(self, T_start_C: float, T_end_C: float, T_sink_C: float, dt_max_s: float, max_dT_K: float,
                 max_dX: float, growth: float, mechanics_max_dT_K: float = 0.0, mechanics_max_dX: float = 0.0) -> None:
        self.T_start_C = T_start_C
        self.T_end_C = T_end_C
        self.span_K = max(T_start_C - T_end_C, 1e-9)
        self.end_excess_K = T_end_C - T_sink_C
        self.T_sink_C = T_sink_C
        self.dt_max_s, self.max_dT_K, self.max_dX, self.growth = dt_max_s, max_dT_K, max_dX, growth
        self.mechanics_max_dT_K, self.mechanics_max_dX = mechanics_max_dT_K, mechanics_max_dX
        self._last: tuple[float, float] | None = None      # (time_s, mean nodal temperature) of the last call
        self._film: list[tuple[float, int, float]] = []     # (time_s, steps, film excess) while a film holds
        self._wetting: tuple[float, int] | None = None     # (time_s, steps) when a point's film first collapsed
        self._phase_change_limited = False
        self._phase_change_start: tuple[int, float] | None = None   # (steps, diffusional fraction) when it first held
        self._forecast: tuple[int, float, float] | None = None      # (steps, diffusional fraction, to come) when asked
        self._martensite: tuple[int, int, float, float] | None = None  # (steps, stress steps, martensite, forecast)
        self._forecast_clock_s = self._martensite_clock_s = -math.inf   # the bar's clock when they were asked

    def fraction(self, T_nodes_C: np.ndarray) -> float:
        return float(min(max((self.T_start_C - float(np.mean(T_nodes_C))) / self.span_K, 0.0), 1.0))

    def steps_left(self, now: StepState) -> float:
        """The steps still to come after ``now.steps_done``; NaN while they cannot be told (a vapour film holds
        and the pace of the steps once it collapses is not known yet, :meth:`_film_steps`)."""
        fraction, mean = self.fraction(now.T_nodes_C), float(np.mean(now.T_nodes_C))
        last, self._last = self._last, (now.time_s, mean)
        excess = mean - self.T_sink_C
        left_s = now.stage_clock_left_s
        if now.ends_on_temperature and last is not None and now.time_s > last[0]:
            previous = last[1] - self.T_sink_C
            if previous > excess > self.end_excess_K > 0.0:
                left_s = min(left_s, self._newton_time_s(excess, math.log(previous / excess) / (now.time_s - last[0])))
        later_excess = self._excess_at_stage_end(now, last, mean) if now.later_stages else excess
        for clock_s, rate_per_s in now.later_stages:
            left_s += clock_s if rate_per_s is None else min(clock_s, self._newton_time_s(later_excess, rate_per_s))
        floor = self._steps_to_cover(max(left_s, 0.0), now.dt_next_s)
        if now.dt_next_s >= 0.999 * self.dt_max_s:
            return floor
        self._phase_change_limited |= now.limited_by_phase_change
        scaled = now.steps_done * (1.0 - fraction) / max(fraction, 1e-9)
        if self._phase_change_limited:
            counted = self._diffusional_steps(now)
        else:
            incubated = now.incubation_share * self._to_come(now) if now.incubation_share > 0.0 else 0.0
            counted = self._film_steps(now) + STEPS_PER_LIMIT_OF_MEAN * incubated / (TARGET * self.max_dX)
        counted += self._drop_steps(now, self.max_dT_K) + self._growth_steps(now)
        if math.isnan(counted):
            return math.nan
        if now.film_excess_K > 0.0 and not self._phase_change_limited:
            return max(counted, floor)      # the mean's cooling under a film foretells nothing after it
        return max(min(scaled, counted), floor)

    def _excess_at_stage_end(self, now: StepState, last: tuple[float, float] | None, mean_C: float) -> float:
        """The mean's excess over the end's ambient (``T_sink_C``) when the current stage's clock runs out, for the
        stages after it: the mean decaying towards the stage's own ambient (``now.stage_ambient_C``, the bath) at its
        Newton rate over the last step; the mean as it is now where that rate is not known or not positive (latent
        heat holding the part), so that the estimate errs high. From the mean as it is now, ring A condition 1's
        air stage, which starts from the oil's 60 C after 900 s in the bath, was counted from 150-400 C: 2.5x its
        length while the quench ran (a floor of ~150 steps where ~75 were left)."""
        ambient = now.stage_ambient_C
        if (not math.isfinite(ambient) or now.ends_on_temperature or last is None or not now.time_s > last[0]
                or not last[1] - ambient > mean_C - ambient > 0.0):
            return mean_C - self.T_sink_C
        rate = math.log((last[1] - ambient) / (mean_C - ambient)) / (now.time_s - last[0])
        end_C = ambient + (mean_C - ambient) * math.exp(-rate * max(now.stage_clock_left_s, 0.0))
        return min(end_C, mean_C) - self.T_sink_C

    def stress_steps_left(self, now: StepState, steps_left: float) -> float:
        """The stress steps among the ``steps_left`` thermal steps (:meth:`steps_left` of the same ``now``): the
        stress solver steps when the change since its last step exceeds ``mechanics_max_dT_K`` or
        ``mechanics_max_dX`` (the pipeline's multirate stepping), so it takes the film's steps (those are at the
        thermal temperature limit ``max_dT_K``: a stress step every ``mechanics_max_dT_K / max_dT_K`` of them where the
        stress limit is the larger; measured at a 60 K stress limit on ring A condition 2, its share within x2 rose
        from 0.87 to 0.99 with this ratio), then the larger of
        the temperature drops still to come over 90 % of its temperature limit and the austenite left over 90 % of
        its phase-fraction limit (martensite forms as the part cools, so one stress step serves both limits), then
        the growth steps -- never more than the thermal steps (limits of 0: all of them) -- or, where more, the
        steps the martensite forming faster than the limit splits the thermal steps into (:meth:`_martensite_steps`)
        and the growth steps."""
        if self.mechanics_max_dT_K <= 0.0 or self.mechanics_max_dX <= 0.0:
            return steps_left
        film = self._film_steps(now)
        if math.isnan(film):
            return steps_left
        cooling = max(self._drop_steps(now, self.mechanics_max_dT_K),
                      now.austenite_fraction / (TARGET * self.mechanics_max_dX))
        growth = self._growth_steps(now)
        film *= min(self.max_dT_K / self.mechanics_max_dT_K, 1.0)
        return max(min(steps_left, film + cooling + growth), self._martensite_steps(now) + growth)

    def _martensite_steps(self, now: StepState) -> float:
        """The stress steps the martensite still needs: a thermal step that forms more than ``mechanics_max_dX`` of
        martensite anywhere is split into as many stress steps, so where a martensite front crosses the section they
        outnumber the thermal steps (the water-quenched peer race: 642 for 214). The forecast
        (``now.martensite_limit_steps``, asked every :data:`MARTENSITE_FORECAST_EVERY_STEPS` steps and :data:`MARTENSITE_FORECAST_EVERY_S`, less the steps taken
        since: the stress steps taken or the mean martensite formed over 0.9 of the limit, whichever is more) counts
        all the austenite left; the share of it that pearlite and bainite will take first (:meth:`_to_come`) forms no
        martensite, so it is scaled by the rest."""
        if now.martensite_limit_steps is None or now.austenite_fraction <= 0.0:
            return 0.0
        if self._martensite is None or (now.steps_done - self._martensite[0] >= MARTENSITE_FORECAST_EVERY_STEPS
                                        and not now.clock_s - self._martensite_clock_s < MARTENSITE_FORECAST_EVERY_S):
            self._martensite_clock_s = now.clock_s
            steps = now.martensite_limit_steps()     # NaN while the section is not cooling: the last one holds
            if not math.isnan(steps):
                self._martensite = (now.steps_done, now.stress_steps_done, now.martensite_fraction, steps)
            elif self._martensite is None:
                return 0.0
            else:
                self._martensite = (now.steps_done, *self._martensite[1:])
        _, stress_then, formed_then, steps = self._martensite
        taken = max(now.stress_steps_done - stress_then,
                    (now.martensite_fraction - formed_then) / (TARGET * self.mechanics_max_dX))
        return max(steps - taken, 0.0) * max(now.austenite_fraction - self._to_come(now), 0.0) / now.austenite_fraction

    def record_film(self, time_s: float, steps_done: int, film_excess_K: float, film_wetted_share: float) -> None:
        """The film's state after a step (:class:`StepState`'s fields of that name), once per step: the steps between
        two updates of the bar are recorded too, since the film's pace is taken over the last
        :data:`FILM_PACE_SHARE` of its time (at an update every ~5-10 steps that window held no earlier record and
        no estimate was given for a third of ring A's run) and the first wetting is dated to its step."""
        if film_excess_K <= 0.0:
            self._film, self._wetting = [], None
            return
        if not self._film or self._film[-1][:2] != (time_s, steps_done):
            self._film.append((time_s, steps_done, film_excess_K))
        if self._wetting is None and film_wetted_share > 0.0:
            self._wetting = (time_s, steps_done)

    def _film_steps(self, now: StepState) -> float:
        """The steps until the vapour film collapses everywhere (0 with no film): the film's time left (the surface
        point farthest above its collapse temperature reaching it at the pace it cools over the last
        :data:`FILM_PACE_SHARE` of the film's time) at the steps per simulated second since the first point's film
        collapsed. Where a film collapses the surface cools fastest (the transition and nucleate boiling), so the
        temperature limit cuts the steps 10-30x below the film's (ring A condition 3: ~1 s steps for 16 steps, then
        0.03-0.13 s for the ~600 steps while the wetting front runs over the surface); the film's own pace said
        nothing of them. NaN (not known) until :data:`PACE_MIN_STEPS` steps have passed since a point first wetted,
        and while the farthest point has not cooled over the last :data:`FILM_PACE_SHARE` of the film's time.
        Records ``now`` in the film's history once (both :meth:`steps_left` and :meth:`stress_steps_left` ask)."""
        self.record_film(now.time_s, now.steps_done, now.film_excess_K, now.film_wetted_share)
        if now.film_excess_K <= 0.0:
            return 0.0
        if self._wetting is None or now.steps_done - self._wetting[1] < PACE_MIN_STEPS:
            return math.nan
        t0 = self._film[0][0]
        since = now.time_s - t0
        t1, _, excess1 = next(f for f in self._film if f[0] >= t0 + (1.0 - FILM_PACE_SHARE) * since)
        if now.time_s <= t1 or excess1 <= now.film_excess_K:
            return math.nan        # the farthest point has not cooled over that time: the film's end is not known
        film_left_s = now.film_excess_K * (now.time_s - t1) / (excess1 - now.film_excess_K)
        return film_left_s * (now.steps_done - self._wetting[1]) / (now.time_s - self._wetting[0])

    def _drop_steps(self, now: StepState, max_dT_K: float) -> float:
        """The steps a temperature limit ``max_dT_K`` needs: it holds at the surface first, then inside, so the
        surface's and the hottest node's drops to the end temperature one after the other, at 90 % of the limit."""
        drop_K = max(now.surface_mean_C - self.T_end_C, 0.0) + max(float(np.max(now.T_nodes_C)) - self.T_end_C, 0.0)
        return drop_K / (TARGET * max_dT_K)

    def _steps_to_cover(self, time_s: float, dt_s: float) -> float:
        """The fewest steps that cover ``time_s`` of simulated time from a step of ``dt_s``: each step at most
        ``growth`` times the one before and at most ``time.dt_max_s`` (the steps grow geometrically until they reach
        dt_max, in (dt_max - dt) / (growth - 1) seconds, then hold at it). A floor on every other count.

        >>> p = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=120.0, max_dT_K=30.0, max_dX=0.02, growth=1.5)
        >>> round(p._steps_to_cover(1.0 + 1.5 + 2.25, 1.0), 9)   # three steps growing by 1.5
        3.0
        >>> p._steps_to_cover(1200.0, 120.0)                    # ten steps at dt_max
        10.0
        """
        dt_s = min(max(dt_s, 1e-12), self.dt_max_s)
        growing_s = (self.dt_max_s - dt_s) / (self.growth - 1.0)
        if time_s <= growing_s:
            return math.log(1.0 + time_s * (self.growth - 1.0) / dt_s) / math.log(self.growth)
        return math.log(self.dt_max_s / dt_s) / math.log(self.growth) + (time_s - growing_s) / self.dt_max_s

    def _growth_steps(self, now: StepState) -> float:
        """The steps the growth factor needs from the next step to ``time.dt_max_s``."""
        return max(math.log(self.dt_max_s / now.dt_next_s) / math.log(self.growth), 0.0)

    def _diffusional_steps(self, now: StepState) -> float:
        """The steps the pearlite/bainite limit still holds, once it has held: the fraction still to form
        (``now.diffusional_to_come``, asked every :data:`FORECAST_EVERY_STEPS` steps and :data:`FORECAST_EVERY_S`, less what has formed since)
        over the fraction formed per step since the limit first held (inf until :data:`PACE_MIN_STEPS` such steps)."""
        if self._phase_change_start is None:
            self._phase_change_start = (now.steps_done, now.diffusional_fraction)
        steps0, formed0 = self._phase_change_start
        if now.diffusional_to_come is None or now.steps_done - steps0 < PACE_MIN_STEPS:
            return math.inf
        pace = (now.diffusional_fraction - formed0) / (now.steps_done - steps0)
        if not pace > 0.0:
            return math.inf
        return self._to_come(now) / pace

    def _to_come(self, now: StepState) -> float:
        """The mean pearlite + bainite still to form (0 for a steel that forms none): ``now.diffusional_to_come``,
        asked every :data:`FORECAST_EVERY_STEPS` steps and :data:`FORECAST_EVERY_S`, less what has formed since it was asked."""
        if now.diffusional_to_come is None:
            return 0.0
        if self._forecast is None or (now.steps_done - self._forecast[0] >= FORECAST_EVERY_STEPS
                                      and not now.clock_s - self._forecast_clock_s < FORECAST_EVERY_S):
            self._forecast_clock_s = now.clock_s
            self._forecast = (now.steps_done, now.diffusional_fraction, now.diffusional_to_come())
        _, formed_then, to_come = self._forecast
        return max(to_come - (now.diffusional_fraction - formed_then), 0.0)

    def _newton_time_s(self, excess_K: float, rate_per_s: float) -> float:
        """When the mean's excess over the ambient, decaying at ``rate_per_s``, reaches the end's excess."""
        if rate_per_s <= 0.0 or self.end_excess_K <= 0.0:
            return math.inf
        return math.log(max(excess_K, self.end_excess_K) / self.end_excess_K) / rate_per_s


def film_collapse_temperatures(T_grid_C: np.ndarray, htc_W_m2K: np.ndarray, peak_share: float = 0.25) -> np.ndarray:
    """Per surface point, the temperature above which a vapour film insulates it: the highest temperature of
    ``T_grid_C`` (ascending) at which its HTC (``htc_W_m2K``, shape (temperatures, points)) still reaches
    ``peak_share`` of its peak, where its HTC at the grid's top is below that (a boiling curve); +inf where the
    HTC does not fall that far above its peak (a convection or radiation boundary, or a film that hardly
    insulates: no film). Film-boiling HTCs lie 5-50x below the nucleate-boiling peak (the peer race's water
    table: 135-437 against 13492 W/m2K; the bath model's oils: 280-1600 against 4500-8000), and the transition
    climbs through a quarter of the peak within some 10-60 K of where the film ends."""
    threshold = peak_share * np.max(htc_W_m2K, axis=0)
    above = htc_W_m2K >= threshold
    highest = len(T_grid_C) - 1 - np.argmax(above[::-1], axis=0)
    return np.where(above[-1], np.inf, np.asarray(T_grid_C)[highest])


class TimeLeft:
    """A time-left estimate that never rises: the raw estimate (the steps left, :meth:`CoolingProgress.steps_left`,
    at the time per step over the recent steps) is followed while it falls and held while it rises; none is given
    before ``warmup_fraction`` of the cooling is done (the first steps' pace says little), nor while the steps left
    are not known (NaN or infinite). The time per step is taken over the last :data:`PRICE_WINDOW_SHARE` of the steps: a step
    while a wetting front runs over the surface costs 3-4x one of the pearlite/bainite limit that follows (ring A
    condition 3: 25 ms against 9 ms of thermal solve, and a stress step at every step against one in ten), and the
    steps where the vapour film first collapses are the dearest of all (the thermal iteration fails and the step is
    cut), so the average since the start priced the rest of the run at the quench's cost. ``history`` keeps every
    ``(elapsed_s, fraction, raw_estimate_s, estimate_s)`` from the warm-up on (NaN where none was given), elapsed
    from the first step, for checking the estimate after the run."""

    def __init__(self, clock: Callable[[], float] = time.perf_counter, warmup_fraction: float = 0.1) -> None:
        self.clock = clock
        self.warmup_fraction = warmup_fraction
        self._seen = np.empty((256, 5))     # per update: clock, steps, stress steps, stress_s, thermal_s
        self._count = 0
        self.shown_s: float | None = None
        self.history: list[tuple[float, float, float, float]] = []

    def record(self, steps_done: int, stress_steps_done: int = 0, stress_s: float = 0.0, thermal_s: float = 0.0
               ) -> float:
        """Record a step (the clock, the steps so far and the run's timers) for the price of the steps, without an
        estimate (the steps between two updates of the bar); returns the clock."""
        now = self.clock()
        if self._count == len(self._seen):
            self._seen = np.concatenate([self._seen, np.empty_like(self._seen)])
        self._seen[self._count] = (now, steps_done, stress_steps_done, stress_s, thermal_s)
        self._count += 1
        return now

    def update(self, fraction: float, steps_done: int, steps_left: float, stress_steps_done: int = 0,
               stress_steps_left: float = 0.0, stress_s: float = 0.0, thermal_s: float = 0.0) -> float | None:
        """Record a step (:meth:`record`) and estimate. ``stress_s`` and ``thermal_s``: the seconds so far in the stress
        steps and in the thermal steps, by the run's timers (a multirate run's stress steps are fewer than its thermal
        steps, and each costs more): the share of the stress steps in the clock's time over the window splits it into
        a time per thermal step and one per stress step, each multiplying its own count of steps left."""
        now = self.record(steps_done, stress_steps_done, stress_s, thermal_s)
        elapsed, steps = now - self._seen[0, 0], steps_done - self._seen[0, 1]
        if fraction < self.warmup_fraction or elapsed <= 0.0 or steps < 1:
            return None
        raw = self._price(steps_left, stress_steps_left) if math.isfinite(steps_left) else math.nan
        if not math.isfinite(raw):
            self.history.append((elapsed, fraction, math.nan, math.nan if self.shown_s is None else self.shown_s))
            return self.shown_s
        self.shown_s = raw if self.shown_s is None else min(self.shown_s, raw)
        self.history.append((elapsed, fraction, raw, self.shown_s))
        return self.shown_s

    def _price(self, steps_left: float, stress_steps_left: float) -> float:
        """The seconds ``steps_left`` thermal steps with ``stress_steps_left`` stress steps among them take at the
        prices of the window (of the whole run so far where the window has no stress step to price). Steps that
        cost more than :data:`PRICE_OUTLIER_FACTOR` times the median step are left out: they are the one-off
        steps where the vapour film first collapses, not a price of the steps to come."""
        seen = self._seen[:self._count]
        steps = seen[:, 1]
        taken = steps[-1] - steps[0]
        window = min(taken, max(PRICE_WINDOW_MIN_STEPS, int(PRICE_WINDOW_SHARE * taken)))
        first = int(np.searchsorted(steps, steps[-1] - window, side="right")) - 1
        if seen[-1, 2] == seen[first, 2] and stress_steps_left > 0.0:
            first = 0
        typical = int(np.searchsorted(steps, steps[-1] - max(window, PRICE_MEDIAN_MIN_STEPS), side="right")) - 1
        step_s = np.diff(seen[max(min(first, typical), 0):, 0])
        per_step = np.diff(seen[first:], axis=0)
        kept = per_step[per_step[:, 0] <= PRICE_OUTLIER_FACTOR * np.median(step_s)].sum(axis=0)
        clock_s, steps, stress_steps, stress_s, thermal_s = kept
        stress_time_s = clock_s * stress_s / (stress_s + thermal_s) if stress_s + thermal_s > 0.0 else 0.0
        return ((clock_s - stress_time_s) / max(steps, 1.0) * steps_left
                + stress_time_s / max(stress_steps, 1.0) * stress_steps_left)


class RunProgress:
    """One tqdm bar on stderr for a whole run: the simulated seconds over all stages, the current stage (or the
    meshing, bath and output phases) in the description, the bar filled by the fraction of the work done
    (:class:`CoolingProgress`, so it fills evenly) and the :class:`TimeLeft` estimate, updated every ``update_every_s``
    of ``clock`` (:meth:`due`; the steps in between are recorded, :meth:`record_step`)."""

    def __init__(self, label: str, total_s: float, enabled: bool = True,
                 clock: Callable[[], float] = time.perf_counter, update_every_s: float = UPDATE_EVERY_S) -> None:
        self.label = label
        self.total_s = total_s
        self.time_left = TimeLeft(clock)
        self.clock = clock
        self.update_every_s = update_every_s
        self._updated_at = -math.inf
        self.done = 0
        self.bar = tqdm(total=STEPS, desc=label, bar_format=BAR_FORMAT, file=sys.stderr, disable=not enabled,
                        leave=False, dynamic_ncols=True)

    def phase(self, name: str) -> None:
        """Name what the run is doing (``meshing``, ``quench``, ``air``, ``output``) in the bar and the log."""
        self.bar.set_description_str(f"{self.label} {name}", refresh=True)
        log.info("%s: %s", self.label, name)

    def due(self) -> bool:
        """Whether ``update_every_s`` of the clock have passed since the last :meth:`update` (or there was none)."""
        return self.clock() - self._updated_at >= self.update_every_s

    def record_step(self, steps_done: int, stress_steps_done: int = 0, stress_s: float = 0.0,
                    thermal_s: float = 0.0) -> None:
        """A step between two updates: recorded for the price of the steps (:meth:`TimeLeft.record`)."""
        self.time_left.record(steps_done, stress_steps_done, stress_s, thermal_s)

    def update(self, time_s: float, fraction: float, steps_done: int, steps_left: float, stress_steps_done: int = 0,
               stress_steps_left: float = 0.0, stress_s: float = 0.0, thermal_s: float = 0.0) -> None:
        left = self.time_left.update(fraction, steps_done, steps_left, stress_steps_done, stress_steps_left,
                                     stress_s, thermal_s)
        self._updated_at = self.clock()
        done = min(int(fraction * STEPS), STEPS - 1)      # full only when the stages are done
        text = f"{time_s:.1f} s simulated of up to {self.total_s:.0f} s"
        self.bar.set_postfix_str(text if left is None else f"{text}, ~{_clock(left)} left", refresh=False)
        self.bar.update(max(done - self.done, 0))
        self.done = max(done, self.done)

    def finish(self, time_s: float) -> None:
        """The stages are done: the bar ends full at the run's last simulated second."""
        self.bar.set_postfix_str(f"{time_s:.1f} s simulated", refresh=False)
        self.bar.update(STEPS - self.done)
        self.done = STEPS

    def close(self) -> None:
        self.bar.close()


def _clock(seconds: float) -> str:
    minutes, s = divmod(int(round(seconds)), 60)
    hours, m = divmod(minutes, 60)
    return f"{hours}:{m:02d}:{s:02d}" if hours else f"{m:02d}:{s:02d}"

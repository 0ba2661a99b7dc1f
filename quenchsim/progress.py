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

log = logging.getLogger("quenchsim")

BAR_FORMAT = "{desc}: {percentage:3.0f}%|{bar}| [{elapsed}{postfix}]"
"""The postfix carries the simulated seconds (one decimal) and the time left."""
STEPS = 1000
"""The bar counts thousandths of the run's work."""
FORECAST_EVERY_STEPS = 16
"""Steps between two forecasts of the pearlite + bainite still to form (each costs about a step's metallurgy)."""
PACE_MIN_STEPS = 8
"""Steps of the phase-fraction limit before their pace (pearlite + bainite formed per step) is taken as known."""


@dataclass(frozen=True)
class StepState:
    """What the run passes to :meth:`CoolingProgress.steps_left` after each step.

    ``stage_clock_left_s``: simulated seconds left on the current stage's clock; ``ends_on_temperature``: the
    current stage is the one that ends at the end temperature; ``later_stages``: per stage still to come, its
    clock and, for the stage that ends on the end temperature, its Newton cooling rate ``h A / C`` (1/s; None
    for a stage that runs its clock); ``surface_mean_C``: the mean temperature of the cooled surface;
    ``film_excess_K``: how far the surface point farthest above its film-collapse temperature
    (:func:`film_collapse_temperatures`) still is above it (<= 0: no vapour film anywhere);
    ``austenite_fraction``: the mean fraction still to transform (0 for a steel that does not);
    ``limited_by_phase_change``: the phase-fraction limit ``time.max_dX`` held the last step rather than the
    temperature limit ``time.max_dT_K``; ``incubation_share``: the largest share of its incubation any point has
    run for a diffusional reaction (:func:`quenchsim.metallurgy.incubation_share`; 1 once one has started);
    ``diffusional_fraction``: the mean fraction of pearlite + bainite formed so far; ``diffusional_to_come``: asked
    only when the estimate needs it, the mean fraction of pearlite + bainite still to form
    (:func:`quenchsim.metallurgy.diffusional_fraction_to_come` at each point's cooling rate now; None: not known)."""

    steps_done: int
    time_s: float
    T_nodes_C: np.ndarray
    dt_next_s: float
    stage_clock_left_s: float
    ends_on_temperature: bool
    later_stages: Sequence[tuple[float, float | None]] = ()
    surface_mean_C: float = -math.inf
    film_excess_K: float = -math.inf
    austenite_fraction: float = 0.0
    limited_by_phase_change: bool = False
    incubation_share: float = 0.0
    diffusional_fraction: float = 0.0
    diffusional_to_come: Callable[[], float] | None = None


class CoolingProgress:
    """How far a run's cooling is and how many steps it still needs.

    The fraction done is the mean nodal temperature between the austenitising temperature and the run's end
    temperature (the bar's fill). Not simulated time, whose work per second falls by orders of magnitude from
    the quench to the air; and the nodes weigh equally, not by volume: the step limit is on nodal temperature
    changes, so the fine surface layer, where the nodes crowd, is where the steps go.

    The steps left (:meth:`steps_left`) come from the step limit that holds:

    * the step at ``time.dt_max_s``: the simulated time left over that step, the time left being the stages'
      clocks or, in a stage that ends on a temperature, when the mean's exponential decay towards the ambient
      reaches the end temperature (Newton's cooling: its rate over the last step in that stage, before it the
      stage's ``h A / C``). Since no step is longer, this is also a floor on every other estimate, so a long air
      stage of capped steps is counted while the quench still runs.
    * the phase-fraction limit ``time.max_dX`` (once it has held): the least of the steps so far scaled by the
      cooling still to do (the fraction above) and a count: the pearlite + bainite still to form, forecast with the
      run's kinetics as each point goes on cooling at its own rate
      (:func:`quenchsim.metallurgy.diffusional_fraction_to_come`, every :data:`FORECAST_EVERY_STEPS` steps), over
      the fraction formed per step since the limit first held,
      plus the drops and growth steps below. The scaling alone counts a pace that holds while the front runs
      through the part; near the end of the transformation most of the austenite left turns to martensite
      instead, and the scaling was up to 2.3-2.6x high there on ring A.
    * the temperature limit ``time.max_dT_K``: the least of that scaling and a count of what each limit still
      needs -- while a vapour film holds somewhere, the steps at the film's mean step until the surface point
      farthest above its film-collapse temperature reaches it at the pace it cools (over the last fifth of the
      film's time); then the surface's and the hottest node's drops to the end temperature (the limit holds at
      the surface first, inside later) over the temperature limit (steps at 90 % of the limit, as the
      controller aims), the austenite left over the phase-fraction limit -- counted as far as the incubation of
      pearlite or bainite has run at some point (``incubation_share``: the limit holds only those, which form once
      incubated) -- and the steps the growth factor needs to reach ``time.dt_max_s``. The scaling alone counts
      the film's slow steps for all the cooling after it, which goes far faster once the film collapses.

    The estimate shown never rises (:class:`TimeLeft`), so where the model must guess it errs high (the film
    ends when its farthest point has cooled through its collapse temperature at its own pace, which a wetting
    front overtakes; a later stage's Newton time starts from the mean as it is now), never low. Measured
    (tests/test_progress.py, the estimate of :class:`TimeLeft` on the CPU clock; the share of the steps between
    10 % and 90 % of the run within a factor 2 of the real time left and the range of estimate / real, the model
    before in brackets): the small test ring 89 % counted in steps, 0.39..1.37 (the same: no film, the scaling
    holds); the small ring with ``time.dt_max_s = 0.05`` 100 % in steps, 0.65..1.04 (none, 0.01..0.11: the
    quench pace said nothing of a long air stage of capped steps); ring A condition 1 94 %, 0.66..2.70 (80 %, up to
    4.7x high: the film's slow steps counted for the cooling after it; what is still high is after the
    collapse, where the air stage's Newton time from the hot mean is long and the air steps cost half the CPU
    time of the film's) and with ``time.max_dX = 0.01`` 100 %, 0.53..1.63 (84-100 %, 0.54..2.2); the peer race
    in water 100 %, 0.63..1.30 (35 %, up to 5.5x high while the film held). Those numbers were taken with
    ``time.max_dX`` limiting every phase at 0.1 (the former default). At today's default (0.002, pearlite and
    bainite only) ~600 steps of the diffusional limit follow ring A's quench, and nothing during the quench foretells
    them: counting every step at the quench's cost, the estimate started 0.39x low (71-76 %). Since the stress
    solver steps only over the ``time.mechanics_*`` limits (multirate), those steps cost about half as much, and
    :meth:`stress_steps_left` with :class:`TimeLeft`'s split of the time per thermal and per stress step counts
    that: ring A 92-95 % (0.56..2.37), with ``time.max_dX = 0.01`` 84-90 % (0.65..2.65); the ratio passes 2 only in
    the last ~10 % of the run (the air stage's Newton time from the hot mean). Counted at full weight, the austenite
    left over 0.9 max_dX is what ring A needs and what the martensitic peer race never takes (29-39 %, 1.14..3.03);
    weighted by the share of the pearlite/bainite incubation run so far (1 in ring A from step ~226 of 1127, long
    before its ~600 steps of the diffusional limit; below 0.2 in the peer race until its film has collapsed), the
    peer race is 76-100 % (1.05..2.24), ring A 93 % (0.80..2.32), with ``time.max_dX = 0.01`` 89 % (0.68..2.59)
    (session 10, three peer-race runs, on a machine loaded by other work). With the forecast count once the
    phase-fraction limit holds, and a stress count that takes the larger of its temperature and transformation
    steps (before: their sum), all within a factor 2 over the window (session 11, idle machine): ring A 100 %
    (0.54..1.49), with ``time.max_dX = 0.01`` 100 % (0.65..1.91), the peer race 100 % (0.95..1.61), with
    ``time.max_dX = 0.01`` 100 % (0.75..1.52), the small ring 100 % (0.65..0.92); the small ring with
    ``time.dt_max_s = 0.05`` 96 % on the CPU clock (0.95..2.67; 97 %, 0.90..2.62 before: its first steps cost twice
    the later ones in a 2.5 s run). Low only early on ring A (nothing during the quench foretells the ~600 steps of
    the diffusional limit), high while a film holds (its end is estimated late). A forecast from the start -- the
    steel's CCT at a Newton-cooled core rate -- gave ring A's core 0.1-0.35 diffusional instead of 0.67
    (docs/experiments/time_left_diffusional_forecast.md); the forecast kept is made only once the limit holds, from
    each point's own state and rate, and on ring A it is within 0.03 of the pearlite + bainite still to form from
    ~200 steps into the limit's ~600 (0.15 against 0.33 at its first step, when the scaling is the lesser)."""

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
        self._phase_change_limited = False
        self._phase_change_start: tuple[int, float] | None = None   # (steps, diffusional fraction) when it first held
        self._forecast: tuple[int, float, float] | None = None      # (steps, diffusional fraction, to come) when asked

    def fraction(self, T_nodes_C: np.ndarray) -> float:
        return float(min(max((self.T_start_C - float(np.mean(T_nodes_C))) / self.span_K, 0.0), 1.0))

    def steps_left(self, now: StepState) -> float:
        """The steps still to come after ``now.steps_done``."""
        fraction, mean = self.fraction(now.T_nodes_C), float(np.mean(now.T_nodes_C))
        last, self._last = self._last, (now.time_s, mean)
        excess = mean - self.T_sink_C
        left_s = now.stage_clock_left_s
        if now.ends_on_temperature and last is not None and now.time_s > last[0]:
            previous = last[1] - self.T_sink_C
            if previous > excess > self.end_excess_K > 0.0:
                left_s = min(left_s, self._newton_time_s(excess, math.log(previous / excess) / (now.time_s - last[0])))
        for clock_s, rate_per_s in now.later_stages:      # from the mean as it is now: the part is no hotter then
            left_s += clock_s if rate_per_s is None else min(clock_s, self._newton_time_s(excess, rate_per_s))
        at_dt_max = max(left_s, 0.0) / self.dt_max_s
        if now.dt_next_s >= 0.999 * self.dt_max_s:
            return at_dt_max
        self._phase_change_limited |= now.limited_by_phase_change
        scaled = now.steps_done * (1.0 - fraction) / max(fraction, 1e-9)
        if self._phase_change_limited:
            counted = self._diffusional_steps(now)
        else:
            counted = self._film_steps(now) + now.incubation_share * now.austenite_fraction / (0.9 * self.max_dX)
        counted += self._drop_steps(now, self.max_dT_K) + self._growth_steps(now)
        return max(min(scaled, counted), at_dt_max)

    def stress_steps_left(self, now: StepState, steps_left: float) -> float:
        """The stress steps among the ``steps_left`` thermal steps (:meth:`steps_left` of the same ``now``): the
        stress solver steps when the change since its last step exceeds ``mechanics_max_dT_K`` or
        ``mechanics_max_dX`` (the pipeline's multirate stepping), so it takes the film's steps, then the larger of
        the temperature drops still to come over 90 % of its temperature limit and the austenite left over 90 % of
        its phase-fraction limit (martensite forms as the part cools, so one stress step serves both limits), then
        the growth steps -- never more than the thermal steps (limits of 0: all of them)."""
        if self.mechanics_max_dT_K <= 0.0 or self.mechanics_max_dX <= 0.0:
            return steps_left
        cooling = max(self._drop_steps(now, self.mechanics_max_dT_K),
                      now.austenite_fraction / (0.9 * self.mechanics_max_dX))
        return min(steps_left, self._film_steps(now) + cooling + self._growth_steps(now))

    def _film_steps(self, now: StepState) -> float:
        """The steps until the vapour film collapses everywhere (0 with no film); records ``now`` in the film's
        history once (both :meth:`steps_left` and :meth:`stress_steps_left` ask)."""
        if now.film_excess_K <= 0.0:
            self._film = []
            return 0.0
        if not self._film or self._film[-1][:2] != (now.time_s, now.steps_done):
            self._film.append((now.time_s, now.steps_done, now.film_excess_K))
        t0, steps0, _ = self._film[0]
        since = now.time_s - t0
        t1, _, excess1 = next(f for f in self._film if f[0] >= t0 + 0.8 * since)
        if now.time_s <= t1 or excess1 <= now.film_excess_K or now.steps_done <= steps0:
            return math.inf
        film_left_s = now.film_excess_K * (now.time_s - t1) / (excess1 - now.film_excess_K)
        return film_left_s * (now.steps_done - steps0) / since

    def _drop_steps(self, now: StepState, max_dT_K: float) -> float:
        """The steps a temperature limit ``max_dT_K`` needs: it holds at the surface first, then inside, so the
        surface's and the hottest node's drops to the end temperature one after the other, at 90 % of the limit."""
        drop_K = max(now.surface_mean_C - self.T_end_C, 0.0) + max(float(np.max(now.T_nodes_C)) - self.T_end_C, 0.0)
        return drop_K / (0.9 * max_dT_K)

    def _growth_steps(self, now: StepState) -> float:
        """The steps the growth factor needs from the next step to ``time.dt_max_s``."""
        return max(math.log(self.dt_max_s / now.dt_next_s) / math.log(self.growth), 0.0)

    def _diffusional_steps(self, now: StepState) -> float:
        """The steps the pearlite/bainite limit still holds, once it has held: the fraction still to form
        (``now.diffusional_to_come``, asked every :data:`FORECAST_EVERY_STEPS` steps and less what has formed since)
        over the fraction formed per step since the limit first held (inf until :data:`PACE_MIN_STEPS` such steps)."""
        if self._phase_change_start is None:
            self._phase_change_start = (now.steps_done, now.diffusional_fraction)
        steps0, formed0 = self._phase_change_start
        if now.diffusional_to_come is None or now.steps_done - steps0 < PACE_MIN_STEPS:
            return math.inf
        pace = (now.diffusional_fraction - formed0) / (now.steps_done - steps0)
        if not pace > 0.0:
            return math.inf
        if self._forecast is None or now.steps_done - self._forecast[0] >= FORECAST_EVERY_STEPS:
            self._forecast = (now.steps_done, now.diffusional_fraction, now.diffusional_to_come())
        _, formed_then, to_come = self._forecast
        return max(to_come - (now.diffusional_fraction - formed_then), 0.0) / pace

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
    at the average wall time per step so far) is followed while it falls and held while it rises; none is given
    before ``warmup_fraction`` of the cooling is done (the first steps' pace says little). ``history`` keeps every
    ``(elapsed_s, fraction, raw_estimate_s, estimate_s)``, elapsed from the first step, for checking the estimate
    after the run."""

    def __init__(self, clock: Callable[[], float] = time.perf_counter, warmup_fraction: float = 0.1) -> None:
        self.clock = clock
        self.warmup_fraction = warmup_fraction
        self.first: tuple[float, int, int] | None = None   # (clock, steps, stress steps) at the first step seen
        self.shown_s: float | None = None
        self.history: list[tuple[float, float, float, float]] = []

    def update(self, fraction: float, steps_done: int, steps_left: float, stress_steps_done: int = 0,
               stress_steps_left: float = 0.0, stress_share: float = 0.0) -> float | None:
        """``stress_share``: the share of the time so far that went to the stress steps (those of a multirate
        run are fewer than its thermal steps, and each costs more): the time per thermal step and per stress step
        are taken apart and each multiplies its own count of steps left."""
        now = self.clock()
        if self.first is None:
            self.first = (now, steps_done, stress_steps_done)
        elapsed, steps = now - self.first[0], steps_done - self.first[1]
        stress_steps = stress_steps_done - self.first[2]
        if fraction < self.warmup_fraction or elapsed <= 0.0 or steps < 1:
            return None
        stress_s = elapsed * stress_share if stress_steps >= 1 else 0.0
        raw = (elapsed - stress_s) / steps * steps_left + stress_s / max(stress_steps, 1) * stress_steps_left
        self.shown_s = raw if self.shown_s is None else min(self.shown_s, raw)
        self.history.append((elapsed, fraction, raw, self.shown_s))
        return self.shown_s


class RunProgress:
    """One tqdm bar on stderr for a whole run: the simulated seconds over all stages, the current stage (or the
    meshing, bath and output phases) in the description, the bar filled by the fraction of the work done
    (:class:`CoolingProgress`, so it fills evenly) and the :class:`TimeLeft` estimate."""

    def __init__(self, label: str, total_s: float, enabled: bool = True,
                 clock: Callable[[], float] = time.perf_counter) -> None:
        self.label = label
        self.total_s = total_s
        self.time_left = TimeLeft(clock)
        self.done = 0
        self.bar = tqdm(total=STEPS, desc=label, bar_format=BAR_FORMAT, file=sys.stderr, disable=not enabled,
                        leave=False, dynamic_ncols=True)

    def phase(self, name: str) -> None:
        """Name what the run is doing (``meshing``, ``quench``, ``air``, ``output``) in the bar and the log."""
        self.bar.set_description_str(f"{self.label} {name}", refresh=True)
        log.info("%s: %s", self.label, name)

    def update(self, time_s: float, fraction: float, steps_done: int, steps_left: float, stress_steps_done: int = 0,
               stress_steps_left: float = 0.0, stress_share: float = 0.0) -> None:
        left = self.time_left.update(fraction, steps_done, steps_left, stress_steps_done, stress_steps_left,
                                     stress_share)
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

"""The run's progress bar: one bar over all stages that ends full with no TqdmWarning, the meshing, stage and
output phases named, and a time-left estimate that never rises; its accuracy is checked after the fact on a
recorded run ((CPU time, estimate) pairs, not a timed test)."""

import logging
import math
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from test_run_resume import plastic_ring
from tqdm import TqdmWarning

from quenchsim.case import case_from_dict, load_case
from quenchsim.pipeline import QuenchRun
from quenchsim.progress import (FORECAST_EVERY_STEPS, MARTENSITE_FORECAST_EVERY_STEPS, PACE_MIN_STEPS, STEPS,
                                STEPS_PER_LIMIT_OF_MEAN, UPDATE_EVERY_S,
                                CoolingProgress, RunProgress, StepState,
                                TimeLeft, film_collapse_temperatures)

ROOT = Path(__file__).resolve().parents[1]


class ThermalStepProgress(RunProgress):
    """The bar on a clock that counts the thermal steps: the time per step is one, and the split of the time per
    thermal and per stress step (measured on the wall clock) does not apply."""

    def update(self, time_s, fraction, steps_done, steps_left, *stress_steps):
        super().update(time_s, fraction, steps_done, steps_left)


def recorded_run(case, out, clock=time.process_time, update_every_s=UPDATE_EVERY_S):
    """Run ``case`` with the estimate on ``clock`` (default the process's CPU time, which other processes' load
    does not move; ``"steps"``: the thermal steps taken, which checks the model of the steps left alone), updated
    every ``update_every_s`` of it."""
    run = QuenchRun(case, out, progress=False)
    if clock == "steps":
        run.bar = ThermalStepProgress(case.name, 1.0, enabled=False, clock=lambda: float(run.counts.steps))
    else:
        run.bar = RunProgress(case.name, 1.0, enabled=False, clock=clock, update_every_s=update_every_s)
    run.run()
    history = np.array(run.bar.time_left.history)     # (elapsed, fraction, raw estimate, estimate) per update
    return history[:, 0], history[:, 3], history[-1, 0]


def test_one_bar_names_its_phases_and_ends_full_without_warning(tmp_path, caplog):
    caplog.set_level(logging.INFO, logger="quenchsim")
    with warnings.catch_warnings():
        warnings.simplefilter("error", TqdmWarning)
        run = QuenchRun(case_from_dict(plastic_ring()), tmp_path, progress=True)
        run.run()
    assert run.bar.bar.n == STEPS == run.bar.done
    named = [r.getMessage().split(": ", 1)[1] for r in caplog.records if r.getMessage().startswith("warm_ring: ")]
    assert named[0] == "meshing" and named[-1] == "output"
    assert {"quench", "air", "quench: boundary HTC", "air: boundary HTC"} <= set(named)


def within_factor_2(elapsed, estimate, end):
    """The share of the updates (one per step with a steps clock) between 10 % and 90 % of the run whose estimate is
    within a factor 2 of the real time left (one without an estimate, NaN, is a miss), and the range of estimate /
    real."""
    window = (elapsed > 0.1 * end) & (elapsed < 0.9 * end)
    ratio = estimate[window] / (end - elapsed[window])
    return float(np.mean((ratio >= 0.5) & (ratio <= 2.0))), np.nanmin(ratio), np.nanmax(ratio)


def test_the_time_left_never_rises_and_is_within_a_factor_2_on_the_small_ring(tmp_path):
    """On the CPU clock the estimate never rises; counted in steps (a 0.4 s run is too short for its CPU time per
    step to be steady inside a test session) it is within a factor 2 of the steps left. (Updated after every step: at
    the run's cadence of :data:`UPDATE_EVERY_S` the 0.4 s run has one or two updates.)"""
    elapsed, estimate, end = recorded_run(case_from_dict(plastic_ring()), tmp_path / "cpu", update_every_s=0.0)
    assert len(estimate) > 20
    assert np.all(np.diff(estimate) <= 0.0)
    elapsed, estimate, end = recorded_run(case_from_dict(plastic_ring()), tmp_path / "steps", clock="steps")
    assert np.all(np.diff(estimate) <= 0.0)
    share, low, high = within_factor_2(elapsed, estimate, end)
    # measured 1.00 (0.67..1.35), deterministic; 0.81 (0.33..1.35) before the floor of the growing steps
    assert share >= 0.85, (share, low, high)


class CountingProgress(RunProgress):
    """The bar on a clock that advances 0.1 s per thermal step, noting the step of each update."""

    def __init__(self, run):
        super().__init__("ring", 1.0, enabled=False, clock=lambda: 0.1 * run.counts.steps)
        self.run, self.updated_at = run, []

    def update(self, *args):
        self.updated_at.append(self.run.counts.steps)
        super().update(*args)


def test_the_estimate_is_updated_on_the_clock_and_every_step_is_priced(tmp_path):
    """On a clock that advances 0.1 s per thermal step the bar is updated every UPDATE_EVERY_S / 0.1 = 5 steps from
    the first, while every step is recorded, once, for the price of a step; the estimate shown never rises."""
    run = QuenchRun(case_from_dict(plastic_ring()), tmp_path, progress=False)
    run.bar = CountingProgress(run)
    run.run()
    recorded = run.bar.time_left._seen[:run.bar.time_left._count]
    assert recorded[-1, 1] == run.counts.steps and np.all(np.diff(recorded[:, 1]) == 1)
    assert run.bar.updated_at[0] == 1 and set(np.diff(run.bar.updated_at)) == {round(UPDATE_EVERY_S / 0.1)}
    shown = np.array(run.bar.time_left.history)[:, 3]
    assert np.all(np.diff(shown[~np.isnan(shown)]) <= 0.0)


def test_a_long_air_stage_of_capped_steps_is_counted_while_the_quench_runs(tmp_path):
    """The small ring with ``time.dt_max_s = 0.05``: ~200 steps of quench, then ~1100 capped steps of air. The
    air stage's Newton time (its HTC over the part's heat capacity) counts from the quench on; before it, the
    quench pace alone put the estimate at a tenth of the real time left, and it could not rise again."""
    case = case_from_dict(plastic_ring(), overrides={"time.dt_max_s": 0.05})
    elapsed, estimate, end = recorded_run(case, tmp_path, clock="steps")
    assert np.all(np.diff(estimate) <= 0.0)
    share, low, high = within_factor_2(elapsed, estimate, end)
    assert share >= 0.85 and low > 0.5, (share, low, high)   # measured 1.00 (0.65..1.04); before 0.00 (0.01..0.11)


def test_a_later_stage_that_ends_on_temperature_counts_its_newton_time_at_dt_max():
    """Closed form: at dt_max, the steps left are the stage's clock plus the later stage's Newton time
    ln(excess / end excess) / rate, over dt_max."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=0.5, max_dT_K=20.0, max_dX=0.1, growth=1.5)
    T = np.full(10, 100.0)
    now = StepState(steps_done=50, time_s=5.0, T_nodes_C=T, dt_next_s=0.5, stage_clock_left_s=3.0,
                    ends_on_temperature=False, later_stages=[(1e5, 0.01)])
    assert progress.steps_left(now) == pytest.approx((3.0 + math.log(80.0 / 20.0) / 0.01) / 0.5)


def test_the_stress_steps_left_count_the_mechanics_limits_and_never_exceed_the_thermal_steps():
    """Closed form, no film: the larger of (surface drop + hottest drop) / (0.9 mechanics_max_dT_K) and austenite left
    / (0.9 mechanics_max_dX) (martensite forms as the part cools: a stress step serves both limits), plus the growth
    steps to dt_max; limits of 0 (a stress step per thermal step) give the thermal steps."""
    multirate = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=20.0, max_dX=0.002, growth=2.0,
                                mechanics_max_dT_K=20.0, mechanics_max_dX=0.02)
    for austenite, expected in ((0.5, (260.0 + 460.0) / 18.0 + 3.0), (0.9, 0.9 / 0.018 + 3.0)):
        now = StepState(steps_done=100, time_s=20.0, T_nodes_C=np.array([300.0, 500.0]), dt_next_s=1.0,
                        stage_clock_left_s=1e4, ends_on_temperature=False, surface_mean_C=300.0,
                        austenite_fraction=austenite)
        assert multirate.stress_steps_left(now, 1e4) == pytest.approx(expected)
    assert multirate.stress_steps_left(now, 50.0) == 50.0
    every_step = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=20.0, max_dX=0.002, growth=2.0)
    assert every_step.stress_steps_left(now, 1234.0) == 1234.0


def test_the_stress_steps_of_a_martensite_front_outnumber_the_thermal_steps():
    """Where the martensite forms faster than mechanics_max_dX per thermal step, the thermal steps are split: the count
    is the forecast (asked every MARTENSITE_FORECAST_EVERY_STEPS steps), less the stress steps taken since or the mean
    martensite formed since over 0.9 of the limit, whichever is more, times the share of the austenite that pearlite
    and bainite will not take, plus the growth steps; more than the thermal steps left."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=20.0, max_dX=0.02, growth=2.0,
                               mechanics_max_dT_K=30.0, mechanics_max_dX=0.02)
    asked = []

    def state(steps, stress, martensite, to_come):
        return StepState(steps_done=steps, time_s=10.0 + steps, T_nodes_C=np.array([300.0, 400.0]), dt_next_s=1.0,
                         stage_clock_left_s=1e4, ends_on_temperature=False, surface_mean_C=300.0,
                         austenite_fraction=1.0 - martensite, martensite_fraction=martensite,
                         diffusional_to_come=lambda: to_come, martensite_limit_steps=lambda: asked.append(1) or 500.0,
                         stress_steps_done=stress)

    growth = 3.0    # 1 s to 8 s at x2
    assert progress.stress_steps_left(state(100, 150, 0.0, 0.0), 60.0) == pytest.approx(500.0 + growth)
    # 4 steps later: 60 stress steps taken, 0.09 martensite formed (5 limits' worth): 60 are taken off
    assert progress.stress_steps_left(state(104, 210, 0.09, 0.0), 60.0) == pytest.approx(
        (500.0 - 60.0) + growth)
    assert len(asked) == 1
    # asked again after MARTENSITE_FORECAST_EVERY_STEPS; with the pearlite/bainite forecast refreshed too (every
    # FORECAST_EVERY_STEPS), 0.3 to come of the 0.8 austenite left takes 3/8 of the count
    fresh = progress.stress_steps_left(state(100 + FORECAST_EVERY_STEPS, 260, 0.2, 0.3), 60.0)
    assert MARTENSITE_FORECAST_EVERY_STEPS <= FORECAST_EVERY_STEPS
    assert len(asked) == 2 and fresh == pytest.approx(500.0 * 0.5 / 0.8 + growth)


def test_a_later_stage_starts_from_where_the_current_stage_leaves_the_part():
    """Closed form: the mean (300 C, 400 C a second before) decays towards the bath (60 C) at its rate over that
    second, ln(340 / 240) per second, for the 10 s left on the stage's clock; the later stage's Newton time counts
    from there (not from 300 C), at dt_max."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=0.5, max_dT_K=20.0, max_dX=0.1, growth=1.5)
    for time_s, T_C in ((4.0, 400.0), (5.0, 300.0)):
        now = StepState(steps_done=50, time_s=time_s, T_nodes_C=np.full(10, T_C), dt_next_s=0.5,
                        stage_clock_left_s=10.0, ends_on_temperature=False, later_stages=[(1e5, 0.01)],
                        stage_ambient_C=60.0)
        left = progress.steps_left(now)
    end_C = 60.0 + 240.0 * math.exp(-math.log(340.0 / 240.0) * 10.0)
    assert left == pytest.approx((10.0 + math.log((end_C - 20.0) / 20.0) / 0.01) / 0.5)


def test_before_the_pearlite_bainite_limit_holds_it_counts_the_forecast_as_far_as_the_incubation_has_run():
    """Closed form, no film: (surface drop + hottest drop) / (0.9 max_dT_K) + incubation share x 3.5 x the forecast
    of the pearlite + bainite still to form (0.2) / (0.9 max_dX) + the growth steps (the limit holds at the
    fastest-transforming point, the mean forms at the front's pace: 3.3-3.7x on ring A); the stress solver's count
    keeps all the austenite (its phase-fraction limit holds martensite too; here its drop steps are the larger)."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dX=0.002, max_dT_K=20.0, growth=2.0,
                               mechanics_max_dT_K=20.0, mechanics_max_dX=0.02)
    counts = {}
    for share in (0.0, 0.5, 1.0):
        now = StepState(steps_done=10000, time_s=20.0, T_nodes_C=np.array([300.0, 500.0]), dt_next_s=1.0,
                        stage_clock_left_s=100.0, ends_on_temperature=False, surface_mean_C=300.0,
                        austenite_fraction=0.5, incubation_share=share, diffusional_to_come=lambda: 0.2)
        counts[share] = progress.steps_left(now)
        assert progress.stress_steps_left(now, 1e4) == pytest.approx((260.0 + 460.0) / 18.0 + 3.0)
    assert counts[0.0] == pytest.approx((260.0 + 460.0) / 18.0 + 3.0)
    assert counts[0.5] == pytest.approx(counts[0.0] + 0.5 * STEPS_PER_LIMIT_OF_MEAN * 0.2 / 0.0018)
    assert counts[1.0] == pytest.approx(counts[0.0] + STEPS_PER_LIMIT_OF_MEAN * 0.2 / 0.0018)


def test_once_the_pearlite_bainite_limit_holds_its_steps_are_the_forecast_over_the_pace_seen():
    """Closed form: the limit first holds at step 100 with 0.10 pearlite + bainite; at step 120 with 0.11 the pace is
    0.0005 per step, and a forecast of 0.02 still to form counts 40 steps, plus the drops and growth steps. The
    forecast is asked once per FORECAST_EVERY_STEPS steps; in between, what formed since is taken off it. Before
    PACE_MIN_STEPS steps of the limit the count is the scaling of the steps so far (no forecast asked)."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=20.0, max_dX=0.002, growth=2.0)
    asked = []

    def to_come():
        asked.append(1)
        return 0.02

    def state(steps, formed):
        return StepState(steps_done=steps, time_s=20.0, T_nodes_C=np.array([300.0, 500.0]), dt_next_s=1.0,
                         stage_clock_left_s=100.0, ends_on_temperature=False, surface_mean_C=300.0,
                         austenite_fraction=0.5, limited_by_phase_change=True, diffusional_fraction=formed,
                         diffusional_to_come=to_come)

    others = (260.0 + 460.0) / 18.0 + 3.0
    fraction = progress.fraction(np.array([300.0, 500.0]))
    assert progress.steps_left(state(100, 0.10)) == pytest.approx(100 * (1 - fraction) / fraction)
    before_pace = 100 + PACE_MIN_STEPS - 1
    assert progress.steps_left(state(before_pace, 0.10)) == pytest.approx(before_pace * (1 - fraction) / fraction)
    assert not asked
    assert progress.steps_left(state(120, 0.11)) == pytest.approx(others + 0.02 / 0.0005)
    assert progress.steps_left(state(124, 0.112)) == pytest.approx(others + 0.018 / (0.012 / 24)) and len(asked) == 1
    progress.steps_left(state(120 + FORECAST_EVERY_STEPS, 0.118))
    assert len(asked) == 2


def test_while_a_film_holds_the_steps_left_count_the_film_time_at_the_pace_since_the_first_wetting():
    """Closed form: a film whose farthest point is 300 - 5 t K above its collapse temperature (so 60 - t s left),
    16 steps of a growing dt to t = 8 s with no point wetted, then a point wets at step 20 (t = 10 s) and steps of
    0.05 s follow. Until then, and for PACE_MIN_STEPS steps after, the steps left are not known (NaN, no estimate
    shown); at step 28 (t = 10.4 s) the film's 49.6 s left at the 20 steps per second since the wetting are 992
    steps, plus the surface's and the hottest node's drops over 0.9 max_dT_K and the growth steps to dt_max. The
    film's own pace (28 steps in 10.4 s) would have counted 134; the steps so far scaled by the cooling still to do
    (28 x 0.904 / 0.096 = 264) are no cap while the film holds (the mean cooled by the surface under the film)."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=20.0, max_dX=0.002, growth=2.0)
    ticks = iter(range(1000))
    time_left = TimeLeft(clock=lambda: float(next(ticks)), warmup_fraction=0.0)

    def state(steps: int, time_s: float, wetted: float) -> StepState:
        return StepState(steps_done=steps, time_s=time_s, T_nodes_C=np.array([700.0, 845.0]), dt_next_s=0.05,
                         stage_clock_left_s=100.0, ends_on_temperature=False, surface_mean_C=800.0,
                         film_excess_K=300.0 - 5.0 * time_s, film_wetted_share=wetted)

    film = [(k, 0.5 * k, 0.0) for k in range(1, 17)] + [(17 + k, 8.5 + 0.5 * k, 0.0) for k in range(3)]
    film += [(20 + k, 10.0 + 0.05 * k, 0.1) for k in range(PACE_MIN_STEPS)]
    for steps, time_s, wetted in film:
        left = progress.steps_left(state(steps, time_s, wetted))
        assert math.isnan(left) and progress.stress_steps_left(state(steps, time_s, wetted), left) is left
        assert time_left.update(0.5, steps, left) is None
    others = (760.0 + 805.0) / 18.0 + math.log2(8.0 / 0.05)
    assert progress.steps_left(state(28, 10.4, 0.1)) == pytest.approx(49.6 * 20.0 + others)
    history = np.array(time_left.history)
    assert len(history) == len(film) - 1 and np.isnan(history[:, 2:]).all()


def test_the_film_counts_a_stress_step_per_stress_temperature_limit_of_thermal_steps():
    """Closed form, the film of the test above: its 992 thermal steps are at the thermal temperature limit (20 K), so a
    stress limit of 60 K takes a stress step every third of them; the surface's and the hottest node's drops count at
    the stress limit, the growth steps as they are."""
    counts = {}
    for mechanics_max_dT_K in (20.0, 60.0):
        progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=20.0, max_dX=0.002, growth=2.0,
                                   mechanics_max_dT_K=mechanics_max_dT_K, mechanics_max_dX=0.02)
        film = [(k, 0.5 * k, 0.0) for k in range(1, 17)] + [(17 + k, 8.5 + 0.5 * k, 0.0) for k in range(3)]
        film += [(20 + k, 10.0 + 0.05 * k, 0.1) for k in range(PACE_MIN_STEPS + 1)]
        for steps, time_s, wetted in film:
            now = StepState(steps_done=steps, time_s=time_s, T_nodes_C=np.array([700.0, 845.0]), dt_next_s=0.05,
                            stage_clock_left_s=100.0, ends_on_temperature=False, surface_mean_C=800.0,
                            film_excess_K=300.0 - 5.0 * time_s, film_wetted_share=wetted)
            progress.steps_left(now)
        counts[mechanics_max_dT_K] = progress.stress_steps_left(now, 1e5)
    growth = math.log2(8.0 / 0.05)
    assert counts[20.0] == pytest.approx(49.6 * 20.0 + (760.0 + 805.0) / 18.0 + growth)
    assert counts[60.0] == pytest.approx(49.6 * 20.0 / 3.0 + (760.0 + 805.0) / 54.0 + growth)


def test_a_film_whose_farthest_point_has_not_cooled_gives_no_estimate():
    """Regression (a run resumed under a film, CI at c5cba6c): the film's history starts again at the resume, and
    while the farthest point has not cooled over the last tenth of it the film's end is not known. That was an
    infinite count, which the steps so far no longer cap under a film: the time left came out infinite or NaN and
    the bar's clock raised. Now the steps left are NaN, and the estimate shown stays as it was (none here)."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=20.0, max_dX=0.002, growth=2.0,
                               mechanics_max_dT_K=20.0, mechanics_max_dX=0.02)
    bar = RunProgress("held film", 1.0, enabled=False, clock=iter(np.arange(100.0)).__next__)
    bar.time_left.warmup_fraction = 0.0
    for steps in range(1, 30):
        now = StepState(steps_done=steps, time_s=0.05 * steps, T_nodes_C=np.array([700.0, 845.0]), dt_next_s=0.05,
                        stage_clock_left_s=100.0, ends_on_temperature=False, surface_mean_C=800.0,
                        film_excess_K=100.0, film_wetted_share=0.5)
        left = progress.steps_left(now)
        assert math.isnan(left)
        bar.update(now.time_s, 0.5, steps, left, steps, progress.stress_steps_left(now, left), 1.0, 1.0)
    assert bar.time_left.shown_s is None and np.isnan(np.array(bar.time_left.history)[:, 2:]).all()
    time_left = TimeLeft(clock=iter([0.0, 1.0]).__next__, warmup_fraction=0.0)
    assert time_left.update(0.5, 0, 10.0) is None and time_left.update(0.5, 1, math.inf) is None
    assert np.isnan(time_left.history[-1][2])


def test_the_stress_steps_left_while_a_film_holds_after_the_phase_change_limit_took_over():
    """Regression: once the phase-fraction limit has held, :meth:`CoolingProgress.steps_left` no longer looks at the
    film, so the film's history lacked the latest steps and the stress count raised StopIteration (ring A condition 3
    with parameters drawn by the calibration, the film still holding somewhere when pearlite began)."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=120.0, max_dT_K=20.0, max_dX=0.002, growth=1.5,
                               mechanics_max_dT_K=20.0, mechanics_max_dX=0.02)
    for steps, time_s, limited in ((10, 1.0, False), (20, 2.0, False), (300, 10.0, True), (400, 12.0, True)):
        now = StepState(steps_done=steps, time_s=time_s, T_nodes_C=np.array([600.0, 800.0]), dt_next_s=0.1,
                        stage_clock_left_s=100.0, ends_on_temperature=False, surface_mean_C=600.0,
                        film_excess_K=60.0 - time_s, film_wetted_share=0.5, austenite_fraction=0.9,
                        limited_by_phase_change=limited)
        left = progress.steps_left(now)      # NaN at the first step: the pace since the first wetting is not known
        assert math.isnan(left) or 0.0 < progress.stress_steps_left(now, left) <= left


def test_the_time_left_prices_thermal_and_stress_steps_apart():
    """10 s for 100 thermal steps of which 20 were stress steps taking 60 % of the time: 0.04 s per thermal step and
    0.3 s per stress step, so 50 thermal steps left with 5 stress steps cost 2 + 1.5 s."""
    clock = iter([0.0, 10.0])
    time_left = TimeLeft(clock=lambda: next(clock), warmup_fraction=0.0)
    assert time_left.update(0.5, 0, 1.0, 0, 0.0, 0.0, 0.0) is None          # the first call sets the origin
    assert time_left.update(0.6, 100, 50.0, 20, 5.0, 6.0, 4.0) == pytest.approx(0.04 * 50 + 0.3 * 5)


def test_the_time_left_prices_the_steps_over_the_last_30_percent_of_them():
    """100 steps of 1 s, then 100 of 0.1 s (none a stress step): the window is the last 60 steps, all at 0.1 s, so
    50 steps left cost 5 s (the average since the start, 0.55 s a step, would say 27.5 s); after 10 steps of the
    cheap ones the window is the last 33 steps, 23 of them dear: (23 x 1 + 10 x 0.1) / 33 s a step."""
    clock = iter([0.0] + [1.0 * k for k in range(1, 101)] + [100.0 + 0.1 * k for k in range(1, 101)])
    time_left = TimeLeft(clock=lambda: next(clock), warmup_fraction=0.0)
    estimates = [time_left.update(0.5, k, 50.0) for k in range(201)]
    assert estimates[110] == pytest.approx(50.0 * 24.0 / 33.0) and estimates[110] < estimates[109]
    assert time_left.history[-1][2] == pytest.approx(50.0 * 0.1)


def test_the_time_left_leaves_out_a_step_dearer_than_three_times_the_median():
    """40 steps of 0.1 s, the 36th 3 s (a try thrown away where the film collapses): the window is the last 12
    steps, and 20 steps left cost 2 s, not the 6.6 s of the window's mean; a step of 0.25 s (a refactorisation)
    is kept: (11 x 0.1 + 0.25) / 12 s a step. Eight dear steps of ten in the window are still one-offs: the median
    is taken over the last 50 steps (here all 40)."""
    for dear_s, expected_s, dear in ((3.0, 20 * 0.1, [35]), (0.25, 20 * 1.35 / 12, [35]),
                                     (3.0, 20 * 0.1, list(range(30, 38)))):
        ticks = np.concatenate([[0.0], np.cumsum(np.where(np.isin(np.arange(40), dear), dear_s, 0.1))])
        clock = iter(ticks)
        time_left = TimeLeft(clock=lambda: next(clock), warmup_fraction=0.0)
        estimates = [time_left.update(0.5, k, 20.0) for k in range(41)]
        assert time_left.history[-1][2] == pytest.approx(expected_s) and estimates[-1] <= expected_s + 1e-12


def test_a_boiling_curve_has_a_film_collapse_temperature_and_convection_has_none():
    """The peer's water table (h peaks at 430 C, falls to a thirtieth by 800 C): on a 10 K grid the highest
    temperature with h at a quarter of its peak or more is 680 C (linear between 2507 W/m2K at 700 C and 7793 at
    600 C: 3373 at 684 C); a constant HTC (or one rising with temperature) has no film."""
    T_grid = np.arange(0.0, 901.0, 10.0)
    water = np.interp(T_grid, [0, 200, 400, 430, 500, 560, 600, 700, 800, 900],
                      [4350, 8207, 11962, 13492, 12500, 10206, 7793, 2507, 437, 135])
    collapse = film_collapse_temperatures(T_grid, np.stack([water, np.full_like(T_grid, 200.0), 5.0 + T_grid], 1))
    assert collapse[0] == 680.0 and np.all(np.isinf(collapse[1:]))


@pytest.mark.slow
@pytest.mark.parametrize("case_file, condition, overrides, measured, required", [
    ("crb_outer_ring.toml", "1", {}, "1.00 (1.16..1.75) updated every 0.5 s; 1.00 (0.94..1.86) with the martensite forecast; 1.00 (0.85..1.87) at the BDF2 limits; 1.00 (0.69..1.44); 1.00 (0.54..1.49) before the film's pace since the first "
                                     "wetting, 0.93 (0.80..2.32) before the forecast of the pearlite/bainite steps",
     0.95),
    ("crb_outer_ring.toml", "1", {"time.max_dX": 0.01}, "1.00 (0.81..1.67) with the martensite forecast; 1.00 (0.85..1.51) at the BDF2 limits; 1.00 (0.79..1.80); 1.00 (0.65..1.91) before", 0.95),
    ("crb_outer_ring.toml", "2", {}, "1.00 (0.79..1.76) with the martensite forecast; 0.96 (0.79..2.64) at the BDF2 limits; 1.00 (0.77..1.64); 1.00 (0.62..1.75) before", 0.95),
    ("crb_outer_ring.toml", "3", {}, "1.00 (1.02..1.95) updated every 0.5 s; 1.00 (0.70..1.65) with the martensite forecast; 1.00 (0.70..1.44) at the BDF2 limits; 1.00 (0.63..1.91); 0.65 (0.18..1.63) before", 0.95),
    ("srb_outer_ring.toml", "4", {}, "0.93 (0.88..2.01) updated every 0.5 s, two runs; 1.00 (0.68..1.62) with the martensite forecast; 1.00 (0.78..1.55) at the BDF2 limits; 1.00 (0.88..1.80); 0.84 (0.55..3.23) before", 0.85),
    ("srb_outer_ring.toml", "5", {}, "0.89-0.91 (1.05..2.75 / 1.15..3.15) updated every 0.5 s, two runs; 1.00 (0.89..1.81) with the martensite forecast; 0.98 (0.91..2.06) at the BDF2 limits; 1.00 (0.85..1.86); 0.85 (0.56..2.83) before", 0.85),
    ("srb_outer_ring.toml", "6", {}, "0.90 (1.15..2.04) updated every 0.5 s; 0.95 (0.93..1.64) with the martensite forecast; 0.95 (0.92..1.85) at the BDF2 limits; 0.91-0.96 (0.95..2.06) in three runs, 9-10 steps without an estimate while "
                                     "the pace after the first wetting is measured; 0.48 (0.27..2.16) before", 0.85),
    ("peer_race_100Cr6.toml", None, {}, "1.00 (0.68..1.14) updated every 0.5 s; 1.00 (0.80..1.34) with the martensite forecast; 0.07 (0.24..0.65) at the BDF2 limits before it (the split stress steps, 3 per thermal step, not counted); 1.00 (0.64..1.55); 1.00 (0.95..1.61) before", 0.95),
    ("peer_race_100Cr6.toml", None, {"time.max_dX": 0.01}, "1.00 (0.68..1.15) with the martensite forecast; 0.15 (0.26..0.70) at the BDF2 limits before it; 1.00 (0.55..1.49); 1.00 (0.75..1.52) before", 0.95),
    ("solid_cylinder_still_oil.toml", None, {}, "0.98 (0.53..0.96) with the martensite forecast (none forms: the later stage counted from where the bath leaves the part); 0.98 (0.73..1.23) at the BDF2 limits; 1.00 (0.78..1.16); 1.00 (1.24..1.82) before", 0.95)],
    ids=["A1", "A1_max_dX_0.01", "A2", "A3", "B4", "B5", "B6", "peer", "peer_max_dX_0.01", "cylinder"])
def test_the_time_left_is_within_a_factor_2_for_most_of_every_shipped_quench(tmp_path, case_file, condition,
                                                                              overrides, measured, required):
    """Every shipped quench case (ring A in still oil, 1, and agitated, 2-3; ring B agitated, 4-6; the peer race
    in water; the solid cylinder in still oil): the estimate never rises and is within a factor 2 of the real time
    left for at least ``required`` of the updates between 10 % and 90 % of the run (CPU clock; updated every
    :data:`UPDATE_EVERY_S`, so each update stands for the same CPU time; before issue 48 every step was one; an update
    without an estimate counts as a miss; ring B condition 6, whose film's end is estimated late and whose misses sit near 2x,
    varies 0.91-0.96 from run to run; ring B conditions 4 and 5 fell from 1.00 to 0.89-0.93 when the updates became
time-based in issue 48: each update now stands for 0.5 s of CPU, so the film stage's overestimates (up to 2.75x, before
the wetting front's pace is measured) weigh by the time they last, not by their few steps). ``measured``: the share and the range of estimate / real (with the martensite front's stress
    steps forecast, session 14, updated every 0.5 s since issue 48; at the BDF2 limits without it, session 13; session 12; then the model before it: the
    film's steps at its own mean pace, the austenite left as the pearlite/bainite steps before the limit held, the
    steps priced at the run's mean cost; docs/experiments/martensite_front_time_left.md). The agitated baths missed: their film lets the step grow to
    ~1 s for 16 steps before the wetting front's ~0.05 s steps, and the steps of the front cost 3-4x the
    pearlite/bainite steps that follow (docs/experiments/time_left_diffusional_forecast.md)."""
    case = load_case(ROOT / "cases" / case_file, condition, overrides=overrides)
    elapsed, estimate, end = recorded_run(case, tmp_path)
    shown = estimate[~np.isnan(estimate)]
    assert len(shown) > 0.8 * len(estimate) and np.all(np.diff(shown) <= 0.0)
    share, low, high = within_factor_2(elapsed, estimate, end)
    print(f"{case_file} {condition} {overrides}: share {share:.2f} ({low:.2f}..{high:.2f}); measured {measured}")
    assert share >= required, (share, low, high, measured)


def test_the_floor_counts_steps_growing_by_the_growth_factor_up_to_dt_max():
    """Closed form: from a step dt growing by g per step, n steps cover dt (g^n - 1) / (g - 1) seconds until the
    step reaches dt_max; after that each step covers dt_max."""
    progress = CoolingProgress(850.0, 40.0, 20.0, dt_max_s=8.0, max_dT_K=30.0, max_dX=0.02, growth=2.0)
    assert progress._steps_to_cover(1.0 + 2.0 + 4.0, 1.0) == pytest.approx(3.0)
    assert progress._steps_to_cover(1.0 + 2.0 + 4.0 + 8.0 * 5, 1.0) == pytest.approx(3.0 + 5.0)
    assert progress._steps_to_cover(80.0, 8.0) == pytest.approx(10.0)
    T = np.full(10, 100.0)   # a stage of 7 s left from a 1 s step: 3 steps at least, whatever else counts fewer
    now = StepState(steps_done=50, time_s=5.0, T_nodes_C=T, dt_next_s=1.0, stage_clock_left_s=7.0,
                    ends_on_temperature=False, later_stages=[])
    assert progress.steps_left(now) >= 3.0 - 1e-9

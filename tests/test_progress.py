"""The run's progress bar: one bar over all stages that ends full with no TqdmWarning, the meshing, stage and
output phases named, and a time-left estimate that never rises; its accuracy is checked after the fact on a
recorded run ((CPU time, estimate) pairs, not a timed test)."""

import logging
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from test_run_resume import plastic_ring
from tqdm import TqdmWarning

from quenchsim.case import case_from_dict, load_case
from quenchsim.pipeline import QuenchRun
from quenchsim.progress import STEPS, RunProgress

ROOT = Path(__file__).resolve().parents[1]


def recorded_run(case, out, clock=time.process_time):
    """Run ``case`` with the estimate on ``clock`` (default the process's CPU time, which other processes' load
    does not move; ``"steps"``: the steps taken, which checks the model of the steps left alone)."""
    run = QuenchRun(case, out, progress=False)
    run.bar = RunProgress(case.name, 1.0, enabled=False,
                          clock=(lambda: float(run.counts["steps"])) if clock == "steps" else clock)
    run.run()
    history = np.array(run.bar.time_left.history)     # (elapsed, fraction, raw estimate, estimate) per step
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
    """The share of the steps between 10 % and 90 % of the run whose estimate is within a factor 2 of the real
    time left, and the range of estimate / real."""
    window = (elapsed > 0.1 * end) & (elapsed < 0.9 * end)
    ratio = estimate[window] / (end - elapsed[window])
    return float(np.mean((ratio >= 0.5) & (ratio <= 2.0))), ratio.min(), ratio.max()


def test_the_time_left_never_rises_and_is_within_a_factor_2_on_the_small_ring(tmp_path):
    """On the CPU clock the estimate never rises; counted in steps (a 0.4 s run is too short for its CPU time per
    step to be steady inside a test session) it is within a factor 2 of the steps left."""
    elapsed, estimate, end = recorded_run(case_from_dict(plastic_ring()), tmp_path / "cpu")
    assert len(estimate) > 20
    assert np.all(np.diff(estimate) <= 0.0)
    elapsed, estimate, end = recorded_run(case_from_dict(plastic_ring()), tmp_path / "steps", clock="steps")
    assert np.all(np.diff(estimate) <= 0.0)
    share, low, high = within_factor_2(elapsed, estimate, end)
    assert share >= 0.85, (share, low, high)                  # measured 0.89 (0.39..1.37), deterministic


@pytest.mark.slow
def test_the_time_left_on_ring_A_is_within_a_factor_2_for_most_of_the_run(tmp_path):
    """Ring A condition 1 (measured: 80 % of the steps between 10 % and 90 % of the run within a factor 2 of the
    real time left, 0.63..4.7x; see quenchsim.progress.CoolingProgress for where it fails)."""
    elapsed, estimate, end = recorded_run(load_case(ROOT / "cases" / "crb_outer_ring.toml", "1"), tmp_path)
    assert np.all(np.diff(estimate) <= 0.0)
    share, low, high = within_factor_2(elapsed, estimate, end)
    assert share >= 0.7 and 0.5 < low and high < 6.0, (share, low, high)

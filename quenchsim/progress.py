"""The progress bar of a run: one bar over all stages in simulated seconds, with a time-left estimate.

A run's simulated seconds pass at very different speeds (steps of milliseconds while the vapour film collapses,
of minutes in air), so a bar and an estimate in simulated seconds (tqdm's remaining seconds over their recent
rate) swing from hours to nothing. The bar here fills with a measure of the work that advances more evenly
(:class:`CoolingProgress`), shows the simulated seconds beside it, and its time-left estimate extrapolates that
measure and never rises (:class:`TimeLeft`).
"""

from __future__ import annotations

import logging
import sys
import time
from collections.abc import Callable

import numpy as np
from tqdm import tqdm

log = logging.getLogger("quenchsim")

BAR_FORMAT = "{desc}: {percentage:3.0f}%|{bar}| [{elapsed}{postfix}]"
"""The postfix carries the simulated seconds (one decimal) and the time left."""
STEPS = 1000
"""The bar counts thousandths of the run's work."""


class CoolingProgress:
    """Fraction of the cooling done: the mean nodal temperature between the austenitising temperature and the
    run's end temperature (the bar's fill and the base of the estimate).

    Not simulated time, whose work per second falls by orders of magnitude from the quench to the air, and the
    nodes weigh equally, not by volume: the step limit is on nodal temperature changes, so the fine surface
    layer, where the mesh's nodes crowd, is where the steps go. How evenly it follows the work depends on what
    limits the steps (measured, tests/test_progress.py): on ring A condition 1, whose steps the temperature
    change limits, the time-left estimate is within a factor 2 of the real time left for 9 in 10 of the steps
    after the first 10 % of the run; where most steps go to the vapour film while the mean hardly moves (the
    peer race) it overestimates up to ~8x until the film collapses, and where ``time.dt_max_s`` caps the steps
    of a long air stage it underestimates."""

    def __init__(self, T_start_C: float, T_end_C: float) -> None:
        self.T_start_C = T_start_C
        self.span_K = max(T_start_C - T_end_C, 1e-9)

    def fraction(self, T_nodes_C: np.ndarray) -> float:
        return float(min(max((self.T_start_C - float(np.mean(T_nodes_C))) / self.span_K, 0.0), 1.0))


class TimeLeft:
    """A time-left estimate that never rises: the raw estimate elapsed x (1 - f) / f (the work left at the average
    pace so far, f from :class:`CoolingProgress`) is followed while it falls and held while it rises; none is
    given before ``warmup_fraction`` of the heat is out (the first steps' pace says little). ``history`` keeps every ``(elapsed_s, fraction, estimate_s)`` for
    checking the estimate after the run."""

    def __init__(self, clock: Callable[[], float] = time.perf_counter, warmup_fraction: float = 0.1) -> None:
        self.clock = clock
        self.start = clock()
        self.warmup_fraction = warmup_fraction
        self.shown_s: float | None = None
        self.history: list[tuple[float, float, float]] = []

    def update(self, fraction: float) -> float | None:
        now = self.clock()
        elapsed = now - self.start
        if fraction < self.warmup_fraction or elapsed <= 0.0:
            return None
        raw = elapsed * (1.0 - fraction) / fraction
        self.shown_s = raw if self.shown_s is None else min(self.shown_s, raw)
        self.history.append((elapsed, fraction, self.shown_s))
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

    def update(self, time_s: float, fraction: float) -> None:
        left = self.time_left.update(fraction)
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

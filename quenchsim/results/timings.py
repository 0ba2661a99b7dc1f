"""Where a run's wall time goes: summary.json's ``solver.stage_time_s``."""

from __future__ import annotations

import contextlib
import time
from collections.abc import Iterator


class StageTimings(dict[str, float]):
    """Wall time in s per part of a run (``thermal_metallurgy_s``, ``mechanics_s``, ``output_s``, ...); a plain
    dict, so it goes into the checkpoint and the summary as it is. ``with timings("key"): ...`` adds the block's
    wall time to ``timings["key"]``."""

    @contextlib.contextmanager
    def __call__(self, key: str) -> Iterator[None]:
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self[key] = self.get(key, 0.0) + time.perf_counter() - t0

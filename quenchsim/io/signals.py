"""SIGTERM (a batch scheduler's time limit) and SIGINT (Ctrl-C) as a request to stop a run at its next whole step."""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator
from typing import Any

from quenchsim.errors import RunInterrupted


class StopRequest:
    """SIGTERM (a batch scheduler's time limit) or SIGINT (Ctrl-C) as a request to stop, honoured by the step
    loop after its last committed step (so the checkpoint it writes is whole); a second signal stops at once."""

    def __init__(self) -> None:
        self.signal_name: str | None = None

    @property
    def requested(self) -> bool:
        return self.signal_name is not None

    def __call__(self, signum: int, frame: Any) -> None:
        name = signal.Signals(signum).name
        if self.signal_name is not None:
            raise RunInterrupted(f"interrupted by a second signal {name}")
        self.signal_name = name

    def check(self) -> None:
        if self.signal_name is not None:
            raise RunInterrupted(f"interrupted by signal {self.signal_name}")


@contextlib.contextmanager
def signals_as_stop_request(stop: StopRequest) -> Iterator[None]:
    """Route SIGTERM and SIGINT to ``stop`` while the stages run (only in the main thread, where signals are
    delivered; elsewhere Ctrl-C stays a KeyboardInterrupt)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {sig: signal.signal(sig, stop) for sig in (signal.SIGTERM, signal.SIGINT)}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)

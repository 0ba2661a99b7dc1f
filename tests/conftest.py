"""Shared pytest configuration."""

import signal

import matplotlib

matplotlib.use("Agg")


def default_ctrl_c() -> None:
    """``preexec_fn`` of a child process that a test interrupts with SIGINT: Ctrl-C acts as from a terminal.
    A non-interactive shell starts background jobs with SIGINT ignored, a child inherits that, and Python then
    installs no KeyboardInterrupt handler, so a suite launched with ``... &`` saw the child ignore the signal."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)

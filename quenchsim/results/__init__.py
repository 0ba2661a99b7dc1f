"""The output contract of ``quenchsim run``: file names, the writer of a run folder and its reader.

    import quenchsim.results as results
    run = results.load("runs/crb_1")          # RunResults: summary, probes, traverses, outline, last frame
    run.summary["dimensions_mm"]["change"]

File names are the constants of :mod:`quenchsim.results.files`; :class:`RunWriter` writes them while a
run goes; :mod:`quenchsim.results.postprocess` turns the final state into the summary's numbers.
"""

from quenchsim.results import files
from quenchsim.results.reader import Frame, RunResults, last_frame, load, load_frame, read_summary
from quenchsim.results.writer import RunWriter

__all__ = ["files", "Frame", "RunResults", "RunWriter", "last_frame", "load", "load_frame", "read_summary"]

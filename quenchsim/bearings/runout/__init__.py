"""Ball-bearing vibration and run-out (NRRO) from waviness, ball diameter differences and ball
spacing: a 2-D linear-spring and a 3-D Hertz quasi-static model (reference sec. 2 and 3).

Library use::

    case = load_case("cases/runout_695_inner9.toml")
    result = run(case)            # trajectory, spectra, identified peaks, run-out, NRRO
"""

from quenchsim.bearings.runout.analysis import LinePeak, RunoutResult, analyse, run, simulate
from quenchsim.bearings.runout.case import RunoutCase, Waviness, load_case, parse_case

__all__ = ["LinePeak", "RunoutCase", "RunoutResult", "Waviness", "analyse", "load_case", "parse_case", "run",
           "simulate"]

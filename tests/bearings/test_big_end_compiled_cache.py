"""The compiled big-end right-hand side equals its Python source.

dynamics.py calls contact laws of ehl.py, contact.py and journal.py, and all of them are compiled with
numba's on-disk cache. That cache is invalidated only by edits to the caller's own file ("Notes on
caching" in the numba documentation: changes in functions defined in a different file are not
detected), so after an edit of a contact law a stale cache would silently run the old law. This test
evaluates the same loaded state once compiled (this process) and once as plain Python
(NUMBA_DISABLE_JIT=1 in a subprocess, which reads the current source of every file).
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from quenchsim.bearings.big_end.case import load_case
from quenchsim.bearings.big_end.dynamics import evaluate
from quenchsim.bearings.big_end.simulate import build_params, integrate

CASE = Path(__file__).resolve().parents[2] / "cases" / "big_end_two_stroke.toml"

PYTHON_EVALUATION = """
import sys
import numpy as np
from quenchsim.bearings.big_end.case import load_case
from quenchsim.bearings.big_end.dynamics import evaluate
from quenchsim.bearings.big_end.simulate import build_params
case_path, state_path, out_path = sys.argv[1:4]
p, _, _ = build_params(load_case(case_path), 2, "engine")
t, *y = np.load(state_path)
np.save(out_path, np.concatenate(evaluate(float(t), np.array(y), p)))
"""


def test_compiled_right_hand_side_matches_the_python_source(tmp_path):
    p, _, _ = build_params(load_case(CASE), 2, "engine")
    # a state inside a loaded engine revolution (not the contact-free start)
    t, y, _, _ = integrate(p, 0.3, 40)
    t_k, y_k = float(t[-1]), y[:, -1]
    compiled = np.concatenate(evaluate(t_k, y_k, p))
    state = tmp_path / "state.npy"
    np.save(state, np.concatenate([[t_k], y_k]))
    out = tmp_path / "python.npy"
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
    subprocess.run([sys.executable, "-c", PYTHON_EVALUATION, str(CASE), str(state), str(out)],
                   env=env, check=True, capture_output=True, text=True)
    python = np.load(out)
    n = p.n
    loads = compiled[-3 * n:]
    assert np.max(loads[n:]) > 10.0  # some roller carries a race load of the engine, not a contact-free state
    scale = np.maximum(np.abs(compiled), 1e-6 * np.max(np.abs(compiled)))
    assert np.max(np.abs(python - compiled) / scale) < 1e-8, (
        "compiled big-end kernels differ from their source: a stale numba cache? "
        "delete quenchsim/bearings/big_end/__pycache__/*.nbi and *.nbc")

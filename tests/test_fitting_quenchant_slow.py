"""Slow checks of the ISO 9950 probe model and fit (not in the default run)."""

from __future__ import annotations

import numpy as np
import pytest

from quenchsim.fitting.probe import ProbeMesh, ProbeModel

T_C = np.array([100.0, 300.0, 500.0, 600.0, 700.0, 850.0])
H = np.array([350.0, 800.0, 2600.0, 2800.0, 900.0, 450.0])


@pytest.mark.slow
def test_probe_centre_curve_is_mesh_converged_on_the_default_mesh():
    """The default 4 x 6 P2 half-probe mesh against 8 x 12 and 16 x 24: the centre curve changes by < 1 K, and the
    difference shrinks under refinement."""
    ends = np.concatenate([np.arange(0.01, 30.0, 0.01), np.arange(30.0, 40.0, 0.1)])
    curves = [ProbeModel(mesh=m).cool(T_C, H, ends).centre_C for m in (ProbeMesh(), ProbeMesh(8, 12, 0.3), ProbeMesh(16, 24, 0.2))]
    d_default = np.max(np.abs(curves[0] - curves[2]))
    d_mid = np.max(np.abs(curves[1] - curves[2]))
    assert d_default < 1.0
    assert d_mid < d_default

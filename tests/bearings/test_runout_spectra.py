"""Spectral analysis and kinematic identification of run-out lines."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from quenchsim.bearings.runout.matching import KinematicBasis, Matcher, label
from quenchsim.bearings.runout.spectra import find_peaks, spectrum, whirl_spectrum


@settings(max_examples=30, deadline=None)
@given(bins=st.floats(20.0, 200.0), amp=st.floats(1e-9, 1e-6), phase=st.floats(0.0, 6.28))
def test_hann_interpolation_recovers_an_off_bin_tone(bins, amp, phase):
    """A cosine of p-p amplitude 2a at an arbitrary (off-bin) frequency is found at its frequency
    (to 1e-3 bin) with its p-p amplitude (to 1e-3), as the reference reports amplitudes (p-p)."""
    n, T = 4096, 1.0
    t = np.arange(n) * T / n
    x = amp * np.cos(2 * np.pi * bins * t + phase)
    peaks = find_peaks(spectrum(x, T, "x"), 0.1 * amp)
    assert len(peaks) == 1
    assert peaks[0].frequency_hz == pytest.approx(bins, abs=1e-3)
    assert peaks[0].amplitude_pp_m == pytest.approx(2 * amp, rel=1e-3)


def test_whirl_spectrum_separates_forward_and_backward():
    n, T = 2048, 1.0
    t = np.arange(n) * T / n
    fwd, bwd = 1e-8, 3e-9
    z = fwd * np.exp(2j * np.pi * 50.3 * t) + bwd * np.exp(-2j * np.pi * 80.7 * t)
    peaks = sorted(find_peaks(whirl_spectrum(z.real, z.imag, T), 1e-10), key=lambda p: p.frequency_hz)
    assert [round(p.frequency_hz, 3) for p in peaks] == [-80.7, 50.3]
    assert peaks[0].amplitude_pp_m == pytest.approx(2 * bwd, rel=1e-3)
    assert peaks[1].amplitude_pp_m == pytest.approx(2 * fwd, rel=1e-3)


def test_labels_in_the_reference_notation():
    assert label(9, -8, 0, "f_i") == "8 f_i + f_r"
    assert label(7, -8, 0, "f_i") == "8 f_i - f_r"
    assert label(0, 16, 0, "f_i") == "16 f_c"
    assert label(0, -1, 2, "f_i") == "2 f_b - f_c"
    assert label(-8, 8, 0, "f_o") == "-8 f_o"
    assert label(9, -8, 0, "f_o") == "8 f_o + f_r"


def test_matcher_prefers_the_physical_combination():
    """16 f_i - f_r for a 15-lobe rotating inner ring, even though some multiple of f_c lies
    within the tolerance too."""
    fr, fc, fb = 30.0, 11.863730770152582, 64.54914459537369
    m = Matcher(KinematicBasis(fr, fc, fb, "f_i"), [15], [], [], 8, bin_hz=3.0)
    f = 16 * (fr - fc) - fr
    assert abs(f - 22 * fc) < 0.9  # a cheaper-looking but unphysical candidate exists
    assert m.match(f, signed=False).label == "16 f_i - f_r"
    assert m.match(f + 5.0, signed=False) is None

"""Run-out spectra (Hann window + FFT, peak-to-peak amplitudes) and their peaks.

As in the reference (sec. 3): the ring-centre signal is multiplied by a Hann window, transformed,
and a line's amplitude is reported as 2 x the single-sided spectral amplitude, i.e. peak-to-peak.
For a window w_n the single-sided amplitude of bin k is A_k = 2 |X_k| / sum(w); a pure tone
a cos(2 pi f t) on a bin gives A_k = a and is reported as 2a (p-p).

Radial motion is also analysed as a whirl: the complex signal x + i y has a two-sided spectrum in
which a circular orbit of radius r turning forward (the sense of the rotating ring) at f shows as
one line at +f of amplitude r (backward: at -f).

Peaks are refined by the two-bin interpolation of the Hann window: with the peak bin amplitude
A_k and its larger neighbour A_(k+-1), r = A_(k+-1) / A_k, the offset is d = (2r - 1)/(r + 1) bins
towards the neighbour and the amplitude A_k / W(d) with the Hann kernel
W(d) = sin(pi d) / (pi d (1 - d^2)), exact for an isolated tone (T. Grandke, "Interpolation
algorithms for discrete Fourier transforms of weighted signals", IEEE Trans. Instrum. Meas. 32(2),
1983, 350-355).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Spectrum:
    """Frequencies (Hz, signed for a whirl spectrum) and peak-to-peak amplitudes (m) of one direction."""

    direction: str
    frequency_hz: np.ndarray
    amplitude_pp_m: np.ndarray
    bin_hz: float


@dataclass(frozen=True)
class Peak:
    """A spectral line: refined frequency (Hz; signed for the whirl 'radial' direction) and p-p amplitude (m)."""

    direction: str
    frequency_hz: float
    amplitude_pp_m: float


def hann(n: int) -> np.ndarray:
    """Periodic Hann window w_k = (1 - cos(2 pi k / n)) / 2."""
    return 0.5 * (1.0 - np.cos(2.0 * np.pi * np.arange(n) / n))


def spectrum(signal_m: np.ndarray, duration_s: float, direction: str) -> Spectrum:
    """Single-sided p-p amplitude spectrum of a real signal (mean removed)."""
    x = np.asarray(signal_m, dtype=float)
    n = x.size
    w = hann(n)
    amp = 2.0 * np.abs(np.fft.rfft((x - x.mean()) * w)) / w.sum()
    return Spectrum(direction, np.fft.rfftfreq(n, duration_s / n), 2.0 * amp, 1.0 / duration_s)


def whirl_spectrum(x_m: np.ndarray, y_m: np.ndarray, duration_s: float) -> Spectrum:
    """Two-sided p-p whirl spectrum of x + i y (positive frequency = forward whirl), sorted by frequency."""
    c = np.asarray(x_m, dtype=float) + 1j * np.asarray(y_m, dtype=float)
    n = c.size
    w = hann(n)
    amp = np.abs(np.fft.fft((c - c.mean()) * w)) / w.sum()
    f = np.fft.fftfreq(n, duration_s / n)
    order = np.argsort(f)
    return Spectrum("radial", f[order], 2.0 * amp[order], 1.0 / duration_s)


def _hann_kernel(d: np.ndarray) -> np.ndarray:
    d = np.asarray(d, dtype=float)
    small = np.abs(d) < 1e-9
    safe = np.where(small, 0.5, d)
    return np.where(small, 1.0, np.sin(np.pi * safe) / (np.pi * safe * (1.0 - safe * safe)))


def find_peaks(s: Spectrum, threshold_m: float) -> list[Peak]:
    """Local maxima of the spectrum above threshold_m (p-p), refined by two-bin Hann interpolation.

    The zero-frequency bin and its neighbours (the removed mean's leakage) are skipped."""
    a = s.amplitude_pp_m
    f = s.frequency_hz
    k = np.arange(1, a.size - 1)
    is_max = (a[k] >= a[k - 1]) & (a[k] > a[k + 1]) & (a[k] > threshold_m) & (np.abs(f[k]) > 1.5 * s.bin_hz)
    peaks = []
    for i in k[is_max]:
        side = 1 if a[i + 1] >= a[i - 1] else -1
        r = a[i + side] / a[i]
        d = (2.0 * r - 1.0) / (r + 1.0)
        d = min(max(d, 0.0), 0.5)
        peaks.append(Peak(s.direction, float(f[i] + side * d * s.bin_hz), float(a[i] / _hann_kernel(d))))
    return peaks

"""Figures of the encoder module (quenchsim.figures, no pyplot state): pole-centre field against gap (closed form and
FE), and the sensor field with the two Hall outputs over a few poles."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from quenchsim.bearings.encoder import field, pulses
from quenchsim.figures import save, subplots


def field_vs_gap(curves: dict[str, tuple[field.Encoder, np.ndarray, np.ndarray]], measured: tuple[float, float],
                 path: pathlib.Path) -> pathlib.Path:
    """Closed-form pole-centre field (mT) against gap for each labelled encoder, its FE points (gaps, fields) and
    the ``measured`` (gap, field) point."""
    g = np.linspace(0.0, 3.0e-3, 121)
    fig, ax = subplots(figsize=(6, 4))
    for i, (label, (enc, fe_gaps, fe_T)) in enumerate(curves.items()):
        ax.semilogy(g * 1e3, np.asarray(field.pole_centre_field_T(enc, g)) * 1e3, color=f"C{i}", label=label)
        ax.semilogy(fe_gaps * 1e3, fe_T * 1e3, "o", color=f"C{i}", ms=4, mfc="none")
    ax.semilogy([measured[0] * 1e3], [measured[1] * 1e3], "k*", ms=10, label="review: 15 mT at 1 mm")
    ax.set_xlabel("air gap (mm)")
    ax.set_ylabel("pole-centre B_y (mT); circles: FE")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return save(fig, path)


def hall_outputs(ring: pulses.RingEncoder, path: pathlib.Path, pole_pairs: int = 3) -> pathlib.Path:
    """B_y at sensors A and B and the two switched outputs over ``pole_pairs`` pole pairs."""
    phi = np.linspace(0.0, pole_pairs * 4.0 * math.pi / ring.poles, 1200)
    fig, (ax, ax2) = subplots(2, 1, figsize=(6, 4.5), sharex=True)
    deg = np.degrees(phi)
    for name, angle, c in (("A", 0.0, "C0"), ("B", ring.b_offset_rad, "C1")):
        b = pulses.sensor_field_T(ring, phi, angle) * 1e3
        ax.plot(deg, b, color=c, label=f"sensor {name}")
        state, out = b[0] >= ring.operate_T * 1e3, []
        for v in b:
            state = True if v >= ring.operate_T * 1e3 else (False if v <= ring.release_T * 1e3 else state)
            out.append(state)
        ax2.plot(deg, np.array(out, dtype=float) + (1.5 if name == "A" else 0.0), color=c, label=f"output {name}")
    ax.axhline(ring.operate_T * 1e3, color="0.4", ls="--", lw=0.8, label="operate / release")
    ax.axhline(ring.release_T * 1e3, color="0.4", ls="--", lw=0.8)
    ax.set_ylabel("B_y at sensor (mT)")
    ax.legend(fontsize=7)
    ax2.set_xlabel("shaft angle (deg)")
    ax2.set_yticks([])
    ax2.legend(fontsize=7)
    fig.tight_layout()
    return save(fig, path)

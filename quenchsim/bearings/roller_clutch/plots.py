"""Figures of the roller-clutch module (quenchsim.figures, no pyplot state): load per unit torque against
torque, and the outer ring's hoop stress around one roller pitch."""

from __future__ import annotations

import math
import pathlib
from collections.abc import Sequence

import numpy as np

from quenchsim.bearings.roller_clutch import analysis, wedge
from quenchsim.figures import save, subplots


def load_per_torque(geometry: wedge.ClutchGeometry, torques_Nm: np.ndarray, printed: Sequence[tuple[float, float]],
                    path: pathlib.Path) -> pathlib.Path:
    """Roller load / torque of the compliant and the rigid wedge over ``torques_Nm``, with the ``printed``
    (torque, roller load) points."""
    comp = [wedge.engage(geometry, t).load_per_torque_N_per_Nm for t in torques_Nm]
    rigid = wedge.engage(geometry, float(torques_Nm[-1]), compliant=False).load_per_torque_N_per_Nm
    fig, ax = subplots(figsize=(6, 3.8))
    ax.plot(torques_Nm, comp, label="compliant wedge (contacts + ring)")
    ax.axhline(rigid, color="0.5", ls="--", label="rigid wedge (same free angle)")
    ax.plot([t for t, _ in printed], [q / t for t, q in printed], "ko", label="printed (Table 2)")
    ax.set_xlabel("transmitted torque (N m)")
    ax.set_ylabel("roller load / torque (N per N m)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, path)


def hoop_around_pitch(geometry: wedge.ClutchGeometry, state: analysis.ClutchState, path: pathlib.Path,
                      label: str = "") -> pathlib.Path:
    """Hoop stress on the bore and the outer surface over one roller pitch (discrete-load series) against the
    Lame bore and outer values."""
    g = geometry
    ring = analysis.discrete_ring(g, state.engagement)
    th = np.linspace(-math.pi / g.rollers, math.pi / g.rollers, 721)
    bore = ring.field(ring.a, th).s_tt / 1e6
    outer = ring.field(ring.b, th).s_tt / 1e6
    fig, ax = subplots(figsize=(6, 3.8))
    ax.plot(np.degrees(th), bore, label="bore (series)")
    ax.plot(np.degrees(th), outer, label="outer surface (series)")
    ax.axhline(state.lame.bore_hoop_Pa / 1e6, color="C0", ls="--", label="bore (Lame)")
    ax.axhline(state.lame.outer_hoop_Pa / 1e6, color="C1", ls="--", label="outer surface (Lame)")
    top = 1.6 * max(state.discrete.max_hoop_Pa, state.lame.bore_hoop_Pa) / 1e6
    ax.set_ylim(-0.5 * top, top)
    ax.set_xlabel("angle from a roller (deg)")
    ax.set_ylabel("hoop stress (MPa)")
    ax.set_title(label, fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, path)

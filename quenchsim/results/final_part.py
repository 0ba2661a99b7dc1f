"""The part after the run: the section moved by the stress solver's displacement, without the rigid axial
translation its fixed point sets, or the "before" section when the stress is not solved."""

from __future__ import annotations

from typing import Any

import numpy as np
import skfem

from quenchsim import mechanics
from quenchsim.results.summary import FinalSection


class FinalPart:
    """The final part of a run on ``mesh`` (the austenitised section the solvers use) from ``before_mesh`` (the
    room-temperature section before the quench), with the stress solver ``mech`` (None: not solved)."""

    def __init__(self, mesh: skfem.MeshTri, before_mesh: skfem.MeshTri, mech: Any) -> None:
        self.mesh, self.before_mesh, self.mech = mesh, before_mesh, mech

    def rigid_axial_shift_m(self, vertices_m: np.ndarray) -> float:
        """Axial shift of the section's volume centroid from the "before" section: a rigid translation set by
        the solver's fixed point, not a distortion (removed from every final-part output)."""
        def centroid_z(p: np.ndarray) -> float:
            tri = p[:, self.mesh.t]                                       # (2, 3, ne)
            area = 0.5 * np.abs((tri[0, 1] - tri[0, 0]) * (tri[1, 2] - tri[1, 0])
                                - (tri[0, 2] - tri[0, 0]) * (tri[1, 1] - tri[1, 0]))
            weight = area * tri[0].mean(axis=0)                          # r dA: the ring's volume
            return float(np.sum(weight * tri[1].mean(axis=0)) / np.sum(weight))
        return centroid_z(vertices_m) - centroid_z(self.before_mesh.p)

    def _deformed_vertices(self) -> tuple[np.ndarray, float]:
        """The mesh vertices moved by the solver's displacement and their rigid axial shift (stress solved)."""
        p = self.mesh.p + self.mech.vertex_displacement().T
        return p, self.rigid_axial_shift_m(p)

    def vertices(self) -> np.ndarray:
        """Mesh vertices (2, nv) of the part after the run, without rigid axial translation: the deformed
        section when the stress is solved; otherwise the "before" section (no distortion computed)."""
        if self.mech is None:
            return self.before_mesh.p.copy()
        p, shift = self._deformed_vertices()
        p[1] -= shift
        return p

    def section(self) -> FinalSection:
        """The final section with its outline."""
        if self.mech is None:
            return FinalSection.of(self.before_mesh.p.copy(), self.mesh.t, mechanics.section_outline(self.before_mesh))
        p, shift = self._deformed_vertices()
        p[1] -= shift
        outline = mechanics.section_outline(self.mesh, self.mech.displacement_m)
        outline[:, 1] -= shift
        return FinalSection.of(p, self.mesh.t, outline)

"""External surface loads of the axisymmetric problem (nodal force vectors per radian)."""

from __future__ import annotations

import numpy as np
from skfem import ElementTriP2, ElementVector, FacetBasis, LinearForm, MeshTri
from skfem.helpers import dot

from quenchsim.fem import INTORDER


def surface_load(mesh: MeshTri, facets: np.ndarray, pressure_Pa: float = 0.0,
                 traction_Pa: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """f = int_facets (t - p n) . v r ds for a pressure p (positive pushes on the surface, along -n)
    and a traction vector t = (t_r, t_z), both uniform; DOF numbering of the solver's vector P2 basis."""
    fb = FacetBasis(mesh, ElementVector(ElementTriP2()), facets=np.asarray(facets), intorder=INTORDER)
    t = np.asarray(traction_Pa, dtype=float)

    @LinearForm
    def load(v, w):
        r = w.x[0]
        return (t[0] * v[0] + t[1] * v[1] - pressure_Pa * dot(w.n, v)) * r

    return load.assemble(fb)

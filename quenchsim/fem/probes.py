"""Point values of the gradient of a finite-element field (scikit-fem), the companion of ``Basis.probes`` (which
gives the field's values): used by the bearing modules' FE checks to read stresses and flux densities at points."""

from __future__ import annotations

import numpy as np
from skfem import Basis


def gradient_at(basis: Basis, u: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Gradient of the FE field ``u`` at the points ``x`` (2, points): shape (2, points) for a scalar basis,
    (components, 2, points) for a vector one. A point on a mesh vertex takes the mean over the elements around
    it (the gradient jumps between elements); any other point, the element it lies in."""
    mesh = basis.mesh
    scale = np.abs(mesh.p).max()
    out = []
    for i in range(x.shape[1]):
        d = np.hypot(mesh.p[0] - x[0, i], mesh.p[1] - x[1, i])
        vertex = int(np.argmin(d))
        if d[vertex] <= 1e-9 * scale:
            cells = np.flatnonzero(np.any(mesh.t == vertex, axis=0))
        else:
            cells = mesh.element_finder(mapping=basis.mapping)(x[0, i:i + 1], x[1, i:i + 1])
        at = np.repeat(x[:, i:i + 1], cells.size, axis=1)
        local = basis.mapping.invF(at[:, :, np.newaxis], tind=cells)
        g = 0.0
        for k in range(basis.Nbfun):
            g = g + basis.elem.gbasis(basis.mapping, local, k, tind=cells)[0].grad[..., 0] * u[basis.element_dofs[k, cells]]
        out.append(np.mean(g, axis=-1))
    return np.stack(out, axis=-1)

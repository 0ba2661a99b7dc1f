"""Post-processing of a finished run: probe times, hardness traverses and the phase summary."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import skfem


def time_to_temperature(time_s: np.ndarray, T_C: np.ndarray, target_C: float) -> float | None:
    """First time the history falls to ``target_C`` (linear interpolation); None if it never does."""
    below = np.flatnonzero(T_C <= target_C)
    if below.size == 0:
        return None
    i = int(below[0])
    if i == 0:
        return float(time_s[0])
    t0, t1, T0, T1 = time_s[i - 1], time_s[i], T_C[i - 1], T_C[i]
    return float(t0 + (t1 - t0) * (T0 - target_C) / (T0 - T1))


class NodalProjection:
    """Lumped L2 projection of quadrature-point values onto the P1 vertices of the mesh:
    u_i = int u phi_i r dA / int phi_i r dA (r-weighted, so it is exact for constants)."""

    def __init__(self, mesh: skfem.MeshTri, intorder: int) -> None:
        b = skfem.Basis(mesh, skfem.ElementTriP1(), intorder=intorder)
        r_dx = np.asarray(b.global_coordinates())[0] * b.dx                  # (ne, nq)
        ne, nq = r_dx.shape
        rows, cols, vals = [], [], []
        for i in range(b.Nbfun):
            w = np.asarray(b.basis[i][0]) * r_dx
            rows.append(np.repeat(b.element_dofs[i], nq))
            cols.append(np.arange(ne * nq))
            vals.append(w.ravel())
        W = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(b.N, ne * nq))
        norm = np.asarray(W.sum(axis=1)).ravel()
        norm[norm == 0] = 1.0
        self.matrix = sp.diags(1.0 / norm) @ W
        self.p1 = b

    def __call__(self, values_qp: np.ndarray) -> np.ndarray:
        return self.matrix @ values_qp.reshape(-1)


def depth_below(depth_mm: np.ndarray, values: np.ndarray, threshold: float) -> float:
    """Depth where a traverse (from the surface inward) first falls below ``threshold``
    (linear interpolation); the full traverse length if it never does."""
    below = np.flatnonzero(values < threshold)
    if below.size == 0:
        return float(depth_mm[-1])
    i = int(below[0])
    if i == 0:
        return 0.0
    d0, d1, v0, v1 = depth_mm[i - 1], depth_mm[i], values[i - 1], values[i]
    return float(d0 + (d1 - d0) * (v0 - threshold) / (v0 - v1))


def phase_statistics(fractions: dict[str, np.ndarray], r_dx: np.ndarray) -> dict[str, dict[str, float]]:
    """min / volume-weighted mean / max of every phase fraction over the section."""
    vol = float(np.sum(r_dx))
    return {p: {"min": float(np.min(X)), "mean": float(np.sum(X * r_dx) / vol), "max": float(np.max(X))}
            for p, X in fractions.items()}

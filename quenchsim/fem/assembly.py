"""Fixed-pattern sparse assembly and axisymmetric integration weights.

In an axisymmetric problem (x = r, y = z) every integral over the section carries the factor r:
int f dV = 2 pi int f r dr dz. A basis' quadrature weights ``dx`` times the radius of each quadrature
point give these weights per radian; the 2 pi cancels between internal and external forces, and between
stored heat and boundary flux.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import skfem

INTORDER = 4
"""Quadrature order of every P2 volume and facet basis of a section: one order for the thermal, the
metallurgy and the mechanics, so temperature, phase state and stresses live at the same points."""


def r_weights(basis: skfem.AbstractBasis) -> tuple[np.ndarray, np.ndarray]:
    """(radius, r dA) at the quadrature points of ``basis``, each shaped (elements or facets, points)."""
    radius = np.asarray(basis.global_coordinates())[0]
    return radius, radius * basis.dx


class FixedPatternAssembler:
    """Sums element matrices (n_cells, n_loc, n_loc) into a CSR matrix with a pattern computed once.

    ``cell_dofs`` is (n_loc, n_cells), the layout of scikit-fem's ``basis.element_dofs``. Only the
    coefficients change in time, so an assembly is one ``np.bincount`` into the CSR data array.
    """

    def __init__(self, cell_dofs: np.ndarray, n_dofs: int) -> None:
        n_loc, n_cells = cell_dofs.shape
        rows = np.broadcast_to(cell_dofs.T[:, :, None], (n_cells, n_loc, n_loc)).ravel()
        cols = np.broadcast_to(cell_dofs.T[:, None, :], (n_cells, n_loc, n_loc)).ravel()
        keys = rows.astype(np.int64) * n_dofs + cols
        unique, self.scatter = np.unique(keys, return_inverse=True)
        self.indices = (unique % n_dofs).astype(np.int32)
        self.row_of = unique // n_dofs
        self.indptr = np.searchsorted(self.row_of, np.arange(n_dofs + 1)).astype(np.int32)
        self.n_dofs = n_dofs
        self.nnz = unique.size
        self.cell_dofs = cell_dofs

    def keys(self) -> np.ndarray:
        """row * n_dofs + column of every stored entry, in CSR order (sorted)."""
        return self.row_of.astype(np.int64) * self.n_dofs + self.indices

    def csr(self, data: np.ndarray) -> sp.csr_matrix:
        """A CSR matrix on this pattern from its data array (length nnz)."""
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n_dofs, self.n_dofs))

    def matrix(self, cell_matrices: np.ndarray) -> sp.csr_matrix:
        return self.csr(np.bincount(self.scatter, weights=cell_matrices.ravel(), minlength=self.nnz))

    def vector(self, cell_vectors: np.ndarray) -> np.ndarray:
        """Sum (n_cells, n_loc) local vectors into a global vector."""
        return np.bincount(self.cell_dofs.T.ravel(), weights=cell_vectors.ravel(), minlength=self.n_dofs)

    def constrained_pattern(self, fixed_dofs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Positions in the CSR data of entries in fixed rows/columns, and of their diagonals."""
        fixed = np.zeros(self.n_dofs, dtype=bool)
        fixed[fixed_dofs] = True
        touched = fixed[self.row_of] | fixed[self.indices]
        diagonal = touched & (self.row_of == self.indices) & fixed[self.row_of]
        return np.flatnonzero(touched), np.flatnonzero(diagonal)

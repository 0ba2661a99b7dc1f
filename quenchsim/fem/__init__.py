"""Finite-element helpers shared by the thermal and the mechanics solvers.

- :data:`INTORDER`: the one quadrature order of every volume and facet basis of a ring section, so that
  the temperature, the phase state and the stresses live at the same points;
- :class:`FixedPatternAssembler`: element matrices summed into a CSR matrix whose pattern is computed once;
- :func:`r_weights`: the axisymmetric integration weights r dA (r ds on facets);
- :mod:`quenchsim.fem.linalg`: BLAS-free dot, preconditioned CG and the symmetric-mode LU.
"""

from quenchsim.fem.assembly import INTORDER, FixedPatternAssembler, r_weights

__all__ = ["INTORDER", "FixedPatternAssembler", "r_weights"]

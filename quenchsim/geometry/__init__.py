"""Axisymmetric (r, z) ring sections built with gmsh, with a named physical group per boundary segment."""

"""Axisymmetric (r, z) ring sections built with gmsh, with a named physical group per boundary segment."""

from quenchsim.geometry.boundary import BoundaryPoints, SectionExtent, boundary_points
from quenchsim.geometry.mesher import SectionMesh, mesh_profile
from quenchsim.geometry.profile import Profile, Segment, general_profile, profile_from_case, rectangular_ring, spherical_outer_ring

__all__ = ["BoundaryPoints", "SectionExtent", "boundary_points", "SectionMesh", "mesh_profile", "Profile", "Segment", "general_profile",
           "profile_from_case", "rectangular_ring", "spherical_outer_ring"]

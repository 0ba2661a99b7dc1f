"""Double-offset constant-velocity joint (DOJ): quasi-static internal forces with Hertz contacts and clearances.

Reference: Y. Hayama, "Internal-force analysis of a DOJ with ADAMS", technical review No. 69 (2001) p. 97;
docs/reference/other_seed_systems.md section 1.
"""

from quenchsim.bearings.doj.contact import ContactStiffness, contact_stiffness, hayama_fit_stiffness
from quenchsim.bearings.doj.geometry import (Clearances, DOJGeometry, reference_case, reference_data,
                                             reference_geometry, scaled_reference_geometry)
from quenchsim.bearings.doj.model import DOJModel, PhaseResult, hayama_normal_load_N

__all__ = ["Clearances", "DOJGeometry", "reference_case", "reference_data", "reference_geometry", "scaled_reference_geometry", "ContactStiffness",
           "contact_stiffness", "hayama_fit_stiffness", "DOJModel", "PhaseResult", "hayama_normal_load_N"]

"""Gas journal bearings, plain and herringbone-grooved: compressible Reynolds equation in divergence
(finite-volume) form on a skewed grid, FAS multigrid, static characteristics, orbits and stability.

Reference: docs/reference/bearing_modules.md, section 1 (ASME J. Tribology 121 (1999) 148).
"""

from quenchsim.bearings.gas_journal.geometry import Bearing, Grid, Grooves, effective_ratios, grid_for_level
from quenchsim.bearings.gas_journal.orbit import OrbitResult, mass_from_parameter, orbit
from quenchsim.bearings.gas_journal.stability import StabilityResult, critical_mass_parameter
from quenchsim.bearings.gas_journal.static import StaticResult, equilibrium, static_characteristics

__all__ = ["Bearing", "Grooves", "Grid", "grid_for_level", "effective_ratios", "StaticResult", "equilibrium",
           "static_characteristics", "OrbitResult", "orbit", "mass_from_parameter", "StabilityResult",
           "critical_mass_parameter"]

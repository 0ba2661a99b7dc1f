"""Transient axisymmetric heat conduction with latent heat (scikit-fem, P2, r-weighted forms).

API (used by :mod:`quenchsim.pipeline` and by studies such as the ISO 9950 probe)::

    fe = AxisymmetricP2(mesh, robin_facets)            # mesh in metres, x = r, y = z
    solver = ThermalSolver(fe, thermal_properties(material), T_initial_C, phase_model, phase_state)
    step = solver.try_step(dt_s, htc)                  # htc(T_surface_C (n,), time_s) -> h (n,); htc.ambient_C (n,)
    solver.commit(step)

``htc`` is evaluated at the facet quadrature points ``fe.facet_r``, ``fe.facet_z`` (flattened);
:class:`TableHTC` builds it from case-file tables, the bath model from nozzles and boiling.
"""

from quenchsim.thermal.assembly import AxisymmetricP2
from quenchsim.thermal.boundary import (HeatingHTC, ImmersionHTC, SurfaceTemperatureHTC, TableHTC,
                                        parse_htc_table)
from quenchsim.thermal.solver import NoTransformation, PhaseModel, ThermalSolver, ThermalStep

__all__ = ["AxisymmetricP2", "HeatingHTC", "ImmersionHTC", "SurfaceTemperatureHTC", "TableHTC", "parse_htc_table", "NoTransformation",
           "PhaseModel", "ThermalSolver", "ThermalStep"]

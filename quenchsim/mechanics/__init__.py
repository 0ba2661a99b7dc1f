"""Axisymmetric thermo-elastic-plastic mechanics: stress, distortion, dimension change, residual stress.

Public API::

    model = load_mechanics(material, options)        # material["mechanics"] + case [mechanics] options
    solver = MechanicsSolver(mesh, model, fixed_point=None)
    info = solver.step(T_C, fractions, T_prev_C, fractions_prev)   # StepInfo(converged, ...)
    solver.displacement_m, solver.nodal_fields()
    free_strain(model, T_C, fractions); model.annealed_free_strain; austenitized_scale(model)
    ring_dimensions(mesh, displacement_m); dimension_change(before, after); section_outline(...)
    section_area_mm2(mesh, displacement_m); distortion_budget(solver, before_mesh, T_C, fractions, eps_ann)
"""

from quenchsim.mechanics.budget import distortion_budget
from quenchsim.mechanics.dimensions import dimension_change, ring_dimensions, section_area_mm2, section_outline
from quenchsim.mechanics.loads import surface_load
from quenchsim.mechanics.model import (MechanicsModel, austenitized_scale, free_strain, load_mechanics,
                                      solver_options)
from quenchsim.mechanics.solver import MechanicsSolver, StepInfo

__all__ = ["MechanicsModel", "MechanicsSolver", "StepInfo", "load_mechanics", "solver_options", "free_strain", "ring_dimensions",
           "dimension_change", "section_outline", "section_area_mm2", "distortion_budget", "surface_load", "austenitized_scale"]

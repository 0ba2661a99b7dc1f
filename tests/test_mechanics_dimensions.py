"""Ring dimensions from a (deformed) section, section outline and nodal output fields."""

import numpy as np
import pytest

from quenchsim.materials import load_material
from quenchsim.mechanics import (MechanicsSolver, dimension_change, load_mechanics, ring_dimensions,
                                 section_outline)
from quenchsim.mechanics import verification as v


def _model():
    return load_mechanics(load_material("SUJ3"), {"plasticity": False, "trip": False})


def test_undeformed_rectangle_dimensions():
    mesh = v.tube_mesh(0.1, 0.15, 0.08, 3)
    dims = ring_dimensions(mesh)
    assert dims == pytest.approx({"id": 200.0, "od": 300.0, "width": 80.0}, rel=1e-12)


def test_uniform_free_strain_scales_every_dimension():
    mesh = v.tube_mesh(0.1, 0.15, 0.08, 3)
    solver = MechanicsSolver(mesh, _model(), fixed_point=(0.1, 0.0))
    T0, X0 = v.uniform_fields(solver, 850.0, 0.0)
    T1, X1 = v.uniform_fields(solver, 20.0, 1.0)
    assert solver.step(T1, X1, T0, X0).converged
    eps = float(solver.quadrature_state["free_strain"].mean())
    before, after = ring_dimensions(mesh), ring_dimensions(mesh, solver.displacement_m)
    change = dimension_change(before, after)["change"]
    for key in ("id", "od", "width"):
        assert change[key] == pytest.approx(eps * before[key], rel=1e-9)


def test_section_outline_is_closed_and_follows_the_boundary():
    mesh = v.tube_mesh(0.1, 0.15, 0.08, 3)
    outline = section_outline(mesh)
    seg = np.diff(outline, axis=0)
    assert np.allclose(outline[0], outline[-1])
    assert np.sum(np.hypot(seg[:, 0], seg[:, 1])) == pytest.approx(2 * (0.05 + 0.08), rel=1e-12)


def test_nodal_fields_shapes_and_projection():
    mesh = v.tube_mesh(0.1, 0.15, 0.08, 3)
    solver = MechanicsSolver(mesh, _model())
    fields = solver.nodal_fields()
    assert fields["displacement_m"].shape == (mesh.p.shape[1], 3)
    for key in ("stress_rr_Pa", "stress_zz_Pa", "stress_tt_Pa", "stress_rz_Pa", "von_mises_Pa",
                "equivalent_plastic_strain"):
        assert fields[key].shape == (mesh.p.shape[1],)
    ne, nq = solver.asm.radius.shape
    assert np.allclose(solver.project_to_vertices(np.full((ne, nq), 3.5)), 3.5)


def test_sample_reproduces_the_lame_stresses_inside_the_wall():
    from quenchsim.mechanics.loads import surface_load
    a, b, h, p = 0.1, 0.2, 0.1, 100e6
    mesh = v.tube_mesh(a, b, h, 8)
    model = load_mechanics(v.uniform_material(2e11, 0.3), {"plasticity": False, "trip": False})
    solver = MechanicsSolver(mesh, model, fixed_point=(a, 0.0))
    T, X = v.uniform_fields(solver, v.T_REF_C)
    facets = mesh.facets_satisfying(lambda x: np.isclose(x[0], a))
    assert solver.step(T, X, T, X, external_force_N=surface_load(mesh, facets, pressure_Pa=p)).converged
    r = np.linspace(0.12, 0.18, 5)
    got = solver.sample(np.vstack([r, np.full_like(r, 0.05)]))
    exact = v.lame_exact(r, a, b, p, 2e11, 0.3)
    np.testing.assert_allclose(got["tt"], exact["tt"], rtol=0.01)
    np.testing.assert_allclose(got["rr"], exact["rr"], atol=0.01 * p)
    np.testing.assert_allclose(got["u_r"], exact["u_r"], rtol=1e-3)


def test_before_hot_after_bookkeeping_returns_the_annealed_dimensions():
    """'before' (annealed, RT) -> hot mesh scaled by austenitized_scale -> uniform cooling to 20 C with
    full transformation to ferrite + carbide (the annealed structure): after - before = 0; full
    martensite instead gives the martensite-vs-annealed free strain on every dimension."""
    from skfem import MeshTri

    from quenchsim.mechanics import austenitized_scale, free_strain
    model = load_mechanics(load_material("SUJ3"), {})
    before_mesh = v.tube_mesh(0.1092, 0.1505, 0.173, 3)
    hot = MeshTri(before_mesh.p * austenitized_scale(model), before_mesh.t)
    before = ring_dimensions(before_mesh)
    for phase in ("pearlite", "martensite"):
        solver = MechanicsSolver(hot, model)
        T0, X0 = v.uniform_fields(solver, model.austenitizing_T_C, 0.0)
        T1, _ = v.uniform_fields(solver, 20.0, 0.0)
        X1 = {"austenite": np.zeros_like(T1), phase: np.ones_like(T1)}
        assert solver.step(T1, X1, T0, X0).converged
        change = dimension_change(before, ring_dimensions(hot, solver.displacement_m))["change"]
        growth = (1 + float(free_strain(model, 20.0, {phase: 1.0}))) / (1 + model.annealed_free_strain) - 1
        for key in ("id", "od", "width"):
            assert change[key] == pytest.approx(growth * before[key], abs=1e-9)
        if phase == "pearlite":
            assert abs(change["od"]) < 1e-9

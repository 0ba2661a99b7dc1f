"""Distortion budget: the parts add up to the run's dimension change, and each part is what it says."""

import numpy as np
import pytest
from skfem import MeshTri

from quenchsim.materials import load_material
from quenchsim.mechanics import (MechanicsSolver, austenitized_scale, distortion_budget, free_strain,
                                 load_mechanics, section_area_mm2)
from quenchsim.mechanics import verification as v
from quenchsim.mechanics.budget import MEASURES, PARTS


def _quench_small_ring(model, n_steps: int = 30):
    """A 20 x 12 mm section (ID 160 mm) quenched from the outside in: the temperature falls linearly from
    T_aust to 20 C, twice as fast at the OD as at the bore, martensite forms by Koistinen-Marburger below 220 C
    (stress, plasticity and TRIP all active in the gradient)."""
    before = v.tube_mesh(0.08, 0.10, 0.012, 8)
    hot = MeshTri(before.p * austenitized_scale(model), before.t)
    solver = MechanicsSolver(hot, model)
    r = np.asarray(solver.basis.global_coordinates())[0] / austenitized_scale(model)
    s = (r - 0.08) / 0.02  # 0 at the bore, 1 at the OD
    T_aust = model.austenitizing_T_C
    T_prev, X_prev = v.uniform_fields(solver, T_aust, 0.0)
    for k in range(1, n_steps + 1):
        t = k / n_steps
        T = T_aust - (T_aust - 20.0) * np.minimum(1.0, t * (1.0 + s))  # the OD is cold at t = 1/2, the bore at 1
        m = np.maximum(1.0 - np.exp(-0.011 * np.maximum(220.0 - T, 0.0)), X_prev["martensite"])
        X = {"austenite": 1.0 - m, "martensite": m}
        assert solver.step(T, X, T_prev, X_prev).converged
        T_prev, X_prev = T, X
    return before, solver, T_prev, X_prev


@pytest.fixture(scope="module")
def quenched():
    model = load_mechanics(load_material("SUJ3"), {})
    return (model,) + _quench_small_ring(model)


def test_budget_parts_add_up_to_the_dimension_change(quenched):
    model, before, solver, T, X = quenched
    budget = distortion_budget(solver, before, T, X, model.annealed_free_strain)
    assert set(budget["parts"]) == set(PARTS)
    for key in MEASURES:
        total = budget["total"][key]
        parts = sum(budget["parts"][p][key] for p in PARTS)
        tol = 2e-3 if key != "area_mm2" else 2e-3 * 24.0  # 0.002 mm on lengths; on the area x the perimeter
        assert abs(parts - total) < tol, (key, parts, total)
        assert budget["sum_minus_total"][key] == pytest.approx(parts - total, abs=1e-12)
    # the gradient quench does yield and transform under stress: both plastic parts are real
    assert abs(budget["parts"]["thermal_plasticity"]["od"]) > 1e-3
    assert abs(budget["parts"]["transformation_plasticity"]["od"]) > 1e-3
    # a converged final state is in equilibrium: the elastic residue is round-off
    assert max(abs(budget["parts"]["elastic_residue"][k]) for k in ("id", "od", "width")) < 1e-6


def test_uniform_transformation_is_all_free_strain():
    """Uniform cooling to full martensite: no stress, so the free-strain part is the whole change,
    g = (1 + eps_M(20 C)) / (1 + eps_ann) - 1 times every length; the area grows by ((1 + g)^2 - 1) A, of which
    the (linearised) part holds 2 g A and the closure error is the second-order g^2 A."""
    model = load_mechanics(load_material("SUJ3"), {})
    before = v.tube_mesh(0.08, 0.10, 0.012, 3)
    hot = MeshTri(before.p * austenitized_scale(model), before.t)
    solver = MechanicsSolver(hot, model)
    T0, X0 = v.uniform_fields(solver, model.austenitizing_T_C, 0.0)
    T1, X1 = v.uniform_fields(solver, 20.0, 1.0)
    assert solver.step(T1, X1, T0, X0).converged
    budget = distortion_budget(solver, before, T1, X1, model.annealed_free_strain)
    growth = (1 + float(free_strain(model, 20.0, {"martensite": 1.0}))) / (1 + model.annealed_free_strain) - 1
    expected = {"id": 160.0 * growth, "od": 200.0 * growth, "width": 12.0 * growth,
                "area_mm2": 240.0 * ((1 + growth) ** 2 - 1)}
    for key, value in expected.items():
        linear = 240.0 * 2 * growth if key == "area_mm2" else value
        assert budget["parts"]["free_strain"][key] == pytest.approx(linear, rel=1e-5)
        assert budget["total"][key] == pytest.approx(value, rel=1e-9)
        for part in ("thermal_plasticity", "transformation_plasticity", "elastic_residue"):
            assert abs(budget["parts"][part][key]) < 1e-9 * 200.0
    assert budget["sum_minus_total"]["area_mm2"] == pytest.approx(-240.0 * growth**2, rel=1e-3)


def test_section_area_of_a_sheared_and_stretched_rectangle():
    """u = (a x + b y, c x + d y) maps the rectangle's area A to A det(I + grad u) exactly."""
    from skfem import Basis, ElementTriP2, ElementVector
    mesh = v.tube_mesh(0.1, 0.15, 0.08, 2)
    basis = Basis(mesh, ElementVector(ElementTriP2()), intorder=1)
    a, b, c, d = 0.01, -0.02, 0.03, 0.005
    x, y = basis.doflocs[0], basis.doflocs[1]
    u = np.where(np.arange(basis.N) % 2 == 0, a * x + b * y, c * x + d * y)
    area = 50.0 * 80.0
    assert section_area_mm2(mesh) == pytest.approx(area, rel=1e-12)
    assert section_area_mm2(mesh, u) == pytest.approx(area * ((1 + a) * (1 + d) - b * c), rel=1e-12)


@pytest.mark.slow
def test_budget_of_ring_a_condition_1_adds_up(tmp_path):
    """Issue 21: the budget of the reference ring A (condition 1) closes to 0.002 mm on ID, OD and width."""
    from quenchsim.case import load_case
    from quenchsim.pipeline import run
    from quenchsim.validation import ROOT
    summary = run(load_case(ROOT / "cases" / "crb_outer_ring.toml", "1"), tmp_path / "A1", progress=False).summary
    budget = summary["distortion_budget_mm"]
    for key in ("id", "od", "width"):
        assert budget["total"][key] == pytest.approx(summary["dimensions_mm"]["change"][key], abs=1e-9)
        assert abs(sum(budget["parts"][p][key] for p in PARTS) - budget["total"][key]) < 2e-3
        assert abs(budget["parts"]["elastic_residue"][key]) < 1e-4

"""Material model of the mechanics: loader errors, free strain bookkeeping, TRIP kinetics and the
fate of accumulated hardening when a phase transforms."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from quenchsim.errors import InputError
from quenchsim.materials import PHASES, load_material, parse_property
from quenchsim.mechanics import austenitized_scale, free_strain, load_mechanics
from quenchsim.mechanics import verification as v
from quenchsim.mechanics.model import (LEBLOND_CUTOFF, free_strain_increment, integrate_property,
                                       trip_saturation)
from quenchsim.mechanics.solver import MechanicsSolver


def _raw(name):
    return load_material(name)


SUJ3 = load_mechanics(_raw("SUJ3"), {})
FURLAN = load_mechanics(_raw("100Cr6_furlan"), {"plasticity": False, "trip": False})
RATIO = _raw("SUJ3")["mechanics"]["free_strain"]["steel_to_cementite_density_ratio"]["value"]


def test_specific_volume_free_strain_closed_form():
    # linear free strain of martensite at 20 C relative to austenite at 850 C, from the file's numbers
    aus = _raw("SUJ3")["austenitisation"]
    c_b, c_m = 1.0, float(np.interp(850.0, aus["T_aust_C"], aus["dissolved_wt"]["C"]))  # the metallurgy's value
    phi_c = (c_b - c_m) / (6.67 - c_m) * RATIO
    dv = (1 - phi_c) * (4.64 - 0.53 * c_m) / 100
    expected = (1 + dv) ** (1 / 3) * (1 + 11.7e-6 * 0.0) / (1 + 22.2e-6 * 830) - 1
    assert float(free_strain(SUJ3, 20.0, {"martensite": 1.0})) == pytest.approx(expected, rel=1e-12)
    # annealed (F + C at 20 C) before-state and the scale of the hot geometry
    dv_p = (1 - phi_c) * (4.64 - 2.21 * c_m) / 100
    ann = (1 + dv_p) ** (1 / 3) / (1 + 22.2e-6 * 830) - 1
    assert SUJ3.annealed_free_strain == pytest.approx(ann, rel=1e-12)
    assert austenitized_scale(SUJ3) == pytest.approx(1 / (1 + ann))
    assert float(free_strain(SUJ3, SUJ3.austenitizing_T_C, {"austenite": 1.0})) == 0.0


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.floats(20.0, 850.0), st.floats(0.0, 1.0), st.floats(0.0, 1.0)), min_size=1, max_size=6))
def test_free_strain_increments_sum_to_the_state_function(path):
    # specific-volume form: integrating the increments along any path gives free_strain(T, X)
    T0, X0 = 850.0, {p: 0.0 for p in PHASES} | {"austenite": 1.0}
    total = 0.0
    for T, m, b in path:
        X = {"austenite": (1 - m) * (1 - b), "martensite": m * (1 - b), "bainite": b * 0.5, "pearlite": b * 0.5}
        total += float(free_strain_increment(SUJ3, np.array(T0), np.array(T), X0, X))
        T0, X0 = T, X
    assert total == pytest.approx(float(free_strain(SUJ3, T0, X0)), abs=1e-14)


def test_expansion_form_is_the_published_rate_form():
    # Furlan: cool austenite 850 -> 229 C, transform fully to martensite at 229 C, cool to 20 C
    path = [(850.0, 0.0), (229.0, 0.0), (229.0, 1.0), (20.0, 1.0)]
    total = 0.0
    for (Ta, ma), (Tb, mb) in zip(path[:-1], path[1:]):
        Xa = {"austenite": 1 - ma, "martensite": ma}
        Xb = {"austenite": 1 - mb, "martensite": mb}
        total += float(free_strain_increment(FURLAN, np.array(Ta), np.array(Tb), Xa, Xb))
    expected = 22.2e-6 * (229 - 850) + 1.11e-2 + 11.7e-6 * (20 - 229)
    assert total == pytest.approx(expected, rel=1e-12)


def test_integrate_property_table_matches_quadrature():
    prop = parse_property({"T_C": [100.0, 300.0, 700.0], "value": [1.0, 3.0, 2.0]}, "x")
    for a, b in [(0.0, 800.0), (150.0, 650.0), (750.0, 50.0)]:
        exact = quad(lambda t: float(prop(t)), a, b, points=[100.0, 300.0, 700.0])[0]
        assert float(integrate_property(prop, a, b)) == pytest.approx(exact, rel=1e-10)
    poly = parse_property({"poly_T_C": [1.0, 2.0, 3.0]}, "y")
    assert float(integrate_property(poly, 0.0, 2.0)) == pytest.approx(2 + 4 + 8)


def test_trip_saturation_functions():
    f = np.linspace(0.0, 1.0, 101)
    assert trip_saturation("desalos", f)[-1] == pytest.approx(1.0)
    leb = trip_saturation("leblond", f)
    assert leb[-1] == pytest.approx(1.0 - LEBLOND_CUTOFF)
    assert np.all(np.diff(leb) > 0)
    eps = 1e-9  # continuous at the cut-off
    assert trip_saturation("leblond", np.array(LEBLOND_CUTOFF - eps)) == pytest.approx(
        trip_saturation("leblond", np.array(LEBLOND_CUTOFF + eps)), abs=1e-8)


@pytest.mark.parametrize("mutate, field", [
    (lambda m: m["free_strain"].update(form="volume"), "SUJ3.mechanics.free_strain.form"),
    (lambda m: m["elastic"].pop("E_Pa"), "SUJ3.mechanics.elastic.E_Pa"),
    (lambda m: m["free_strain"]["volume_change_pct"].update(martensite=[4.64]),
     "SUJ3.mechanics.free_strain.volume_change_pct.martensite"),
    (lambda m: m["trip"].update(law="fischer"), "SUJ3.mechanics.trip.law"),
    (lambda m: m["plastic"].update(hardening_memory=1.5), "SUJ3.mechanics.plastic.hardening_memory"),
])
def test_bad_material_fields_are_named(mutate, field):
    raw = _raw("SUJ3")
    mutate(raw["mechanics"])
    with pytest.raises(InputError) as err:
        load_mechanics(raw, {})
    assert err.value.field == field


def test_bad_options_are_named():
    with pytest.raises(InputError, match="mechanics.plastisity"):
        load_mechanics(_raw("SUJ3"), {"plastisity": False})
    with pytest.raises(InputError, match="mechanics.trip"):
        load_mechanics(_raw("SUJ3"), {"trip": "yes"})
    with pytest.raises(InputError, match="mechanics.plasticity"):  # elastic peer set has no [plastic]
        load_mechanics(_raw("100Cr6_furlan"), {"trip": False})
    assert load_mechanics(_raw("SUJ3"), {"austenitizing_T_C": 830.0}).austenitizing_T_C == 830.0


@pytest.mark.parametrize("memory", [0.0, 0.4, 1.0])
def test_hardening_after_transformation(memory):
    """Rule: a newly formed phase inherits the fraction ``memory`` of the accumulated equivalent plastic
    strain p (Leblond's theta); the mixture value becomes p' = p (1 - (1 - memory) dX), dX = austenite
    lost.  In the axially restrained bar the lowered yield stress then relaxes the axial stress by
    uniaxial plastic flow: dp = H (p - p') / (E + H), sigma = -(sigma_y + H (p' + dp))."""
    E, alpha, sy, H = 2.0e11, 1.2e-5, 200e6, 5e9
    material = v.uniform_material(E, 0.3, alpha, yield_Pa=sy, hardening_Pa=H, hardening_memory=memory)
    model = load_mechanics(material, {"trip": False})
    mesh = v.tube_mesh(0.0, 0.01, 0.02, 1)
    ends = {"z": np.concatenate([v.nodes_on_line(mesh, 1, 0.0), v.nodes_on_line(mesh, 1, 0.02)])}
    solver = MechanicsSolver(mesh, model, fixed_point=(0.0, 0.0), dirichlet=ends)
    T0, X0 = v.uniform_fields(solver, v.T_REF_C, 0.0)
    T1, _ = v.uniform_fields(solver, v.T_REF_C + 200.0, 0.0)
    assert solver.step(T1, X0, T0, X0).converged
    p_before = solver.quadrature_state["equivalent_plastic_strain"].copy()
    assert p_before.min() > 1e-4
    _, X1 = v.uniform_fields(solver, v.T_REF_C, 0.5)
    assert solver.step(T1, X1, T1, X0).converged  # isothermal, no volume change
    p_reset = p_before * (1 - (1 - memory) * 0.5)
    p_after = p_reset + H * (p_before - p_reset) / (E + H)
    np.testing.assert_allclose(solver.quadrature_state["equivalent_plastic_strain"], p_after, rtol=1e-9)
    np.testing.assert_allclose(solver.stress_Pa["zz"], -(sy + H * p_after), rtol=1e-9)


def test_matrix_carbon_follows_the_austenitising_temperature():
    # more carbon dissolved at 860 C than at 830 C: smaller A -> M and A -> F+C volume changes
    low = load_mechanics(_raw("SUJ3"), {"austenitizing_T_C": 830.0})
    high = load_mechanics(_raw("SUJ3"), {"austenitizing_T_C": 860.0})
    aus = _raw("SUJ3")["austenitisation"]
    for model, T in ((low, 830.0), (high, 860.0)):
        c_m = float(np.interp(T, aus["T_aust_C"], aus["dissolved_wt"]["C"]))
        phi_c = (1.0 - c_m) / (6.67 - c_m) * RATIO
        assert model.volume_change["martensite"] == pytest.approx((1 - phi_c) * (4.64 - 0.53 * c_m) / 100, rel=1e-12)
    raw = _raw("SUJ3")
    raw.pop("austenitisation")
    with pytest.raises(InputError) as err:
        load_mechanics(raw, {})
    assert err.value.field == "SUJ3.mechanics.free_strain.carbon_matrix_wt_pct"


@pytest.mark.parametrize("mutate, field", [
    (lambda m: m["plastic"]["hardening_Pa"]["per_phase"].update(martensite=-1e9),
     "SUJ3.mechanics.plastic.hardening_Pa.per_phase.martensite"),
    (lambda m: m["elastic"]["E_Pa"]["per_phase"].update(austenite={"poly_T_C": [2.0e11, -3.0e8]}),
     "SUJ3.mechanics.elastic.E_Pa.per_phase.austenite"),
    (lambda m: m["trip"]["K_1_Pa"]["per_phase"].update(bainite=5e-5), "SUJ3.mechanics.trip.K_1_Pa.per_phase.bainite"),
    (lambda m: m["free_strain"]["alpha_1_K"]["per_phase"].update(
        austenite={"T_C": [100.0, 600.0], "value": [22e-6, 23e-6]}),
     "SUJ3.mechanics.free_strain.alpha_1_K.per_phase.austenite.T_C"),
    (lambda m: m["trip"]["K_1_Pa"]["per_phase"].update(martensite={"value": 3e-10, "range": [5e-11, 2.1e-10]}),
     "SUJ3.mechanics.trip.K_1_Pa.per_phase.martensite.value"),
    (lambda m: m["elastic"]["nu"].update(range_factor=0.5), "SUJ3.mechanics.elastic.nu.range_factor"),
])
def test_bad_mechanical_data_gets_a_one_line_error_naming_file_and_field(mutate, field):
    """Issue 21: a flow curve falling with strain, a negative modulus, a TRIP constant outside 1e-12..1e-9 /Pa,
    an expansion table not covering the temperatures used, a value outside its prior range."""
    import copy
    raw = copy.deepcopy(_raw("SUJ3"))
    mutate(raw["mechanics"])
    with pytest.raises(InputError) as err:
        load_mechanics(raw, {})
    assert err.value.field == field
    assert "\n" not in str(err.value)

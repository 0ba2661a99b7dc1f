"""The compiled phase update (:func:`quenchsim.metallurgy.advance`, loops in metallurgy/kernels.py) gives the same
numbers as the NumPy reference (:func:`quenchsim.metallurgy.transform.advance_reference`) on random states, for every
kinetics model: the loops do the reference's arithmetic in its order and the laws are the same NumPy calls, so the
results are equal to the last bit, not merely close."""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from quenchsim.materials import load_material
from quenchsim.metallurgy import PhaseState, advance, initial_state, load_kinetics
from quenchsim.metallurgy.transform import Q_MAX, advance_reference


def _with_ttt_bainite_and_node_pearlite():
    """SUJ2 with a tabulated (ttt_table) bainite and a c_curve pearlite whose n(T) runs through nodes: the two
    table-driven laws no shipped steel uses."""
    material = copy.deepcopy(load_material("SUJ2"))
    material["kinetics"]["bainite"] = {
        "model": "ttt_table", "source": "test: a synthetic TTT table", "T_upper_C": 520.0, "X_start": 0.01,
        "X_finish": 0.99, "T_C": [250.0, 350.0, 450.0, 520.0], "t_start_s": [60.0, 8.0, 12.0, 200.0],
        "t_finish_s": [3000.0, 300.0, 500.0, 9000.0]}
    pearlite = material["kinetics"]["pearlite"]
    for key in ("n", "n_per_K"):
        pearlite.pop(key, None)
    pearlite["n_nodes_T_C"], pearlite["n_nodes"] = [550.0, 650.0, 700.0], [2.5, 3.5, 1.8]
    return load_kinetics(material, 850.0)


KINETICS = {"SUJ3 (c_curve, n linear)": load_kinetics(load_material("SUJ3"), 845.0),
            "SUJ2_li1998 (li1998)": load_kinetics(load_material("SUJ2_li1998"), 845.0),
            "100Cr6_furlan (jmak_polynomial)": load_kinetics(load_material("100Cr6_furlan"), 850.0),
            "ttt_table, n nodes": _with_ttt_bainite_and_node_pearlite()}
KINETICS["no diffusional reaction"] = dataclasses.replace(KINETICS["SUJ3 (c_curve, n linear)"], reactions={})


@st.composite
def steps(draw):
    """A random state of a few points (partly transformed, partly incubated, some reactions complete) and a step."""
    n = draw(st.integers(1, 40))
    seed = draw(st.integers(0, 2**32 - 1))
    kin = KINETICS[draw(st.sampled_from(sorted(KINETICS)))]
    rng = np.random.default_rng(seed)
    fractions = rng.dirichlet(np.ones(4), n).T * (rng.random(n) < 0.8) + np.eye(4)[0][:, None] * (rng.random(n) >= 0.8)
    additivity = {r: rng.choice([0.0, 1e-6, 0.05, 1.0, Q_MAX], n) * rng.uniform(0.5, 1.0, n) for r in kin.reactions}
    state = PhaseState(fractions=dict(zip(("austenite", "pearlite", "bainite", "martensite"), fractions)),
                       additivity=additivity, T_min_C=rng.uniform(20.0, kin.T_aust_C, n),
                       cooling_rate_700_C_s=np.where(rng.random(n) < 0.5, np.nan, rng.uniform(1.0, 100.0, n)))
    T_old = rng.uniform(20.0, kin.T_aust_C, n)
    T_new = np.clip(T_old + rng.uniform(-120.0, 40.0, n), 10.0, kin.T_aust_C)
    dt_s = draw(st.sampled_from([0.0, 1e-3, 0.2, 5.0, 300.0]))
    return kin, state, T_old, T_new, dt_s


@settings(max_examples=150, deadline=None)
@given(steps())
def test_compiled_update_equals_the_numpy_reference_to_the_last_bit(step):
    kin, state, T_old, T_new, dt_s = step
    compiled = advance(state, kin, T_old, T_new, dt_s)
    reference = advance_reference(state, kin, T_old, T_new, dt_s)
    for phase, X in reference.fractions.items():
        np.testing.assert_array_equal(compiled.fractions[phase], X, err_msg=phase)
    for reaction, q in reference.additivity.items():
        np.testing.assert_array_equal(compiled.additivity[reaction], q, err_msg=reaction)
    np.testing.assert_array_equal(compiled.T_min_C, reference.T_min_C)
    np.testing.assert_array_equal(compiled.cooling_rate_700_C_s, reference.cooling_rate_700_C_s)


def test_compiled_update_of_a_quench_path_equals_the_reference_and_leaves_the_input_alone():
    """A whole cooling path of a (2, 3) field, state fed forward: the two updates stay equal, fractions sum to one,
    and the state passed in is not changed (advance is pure)."""
    kin = KINETICS["SUJ3 (c_curve, n linear)"]
    compiled = reference = initial_state((2, 3), kin)
    T = np.full((2, 3), kin.T_aust_C)
    rates = np.array([[2.0, 5.0, 10.0], [20.0, 40.0, 80.0]])  # C/s: pearlite, bainite and martensite all form
    for _ in range(60):
        T_next = np.maximum(T - rates * 4.0, 20.0)
        before = {p: v.copy() for p, v in compiled.fractions.items()}
        compiled_next = advance(compiled, kin, T, T_next, 4.0)
        for p, v in compiled.fractions.items():
            np.testing.assert_array_equal(v, before[p])
        compiled, reference = compiled_next, advance_reference(reference, kin, T, T_next, 4.0)
        T = T_next
    for phase, X in reference.fractions.items():
        np.testing.assert_array_equal(compiled.fractions[phase], X)
    assert all(compiled.fractions[p].max() > 0.01 for p in ("pearlite", "bainite", "martensite"))
    np.testing.assert_allclose(sum(compiled.fractions.values()), 1.0, atol=1e-12)

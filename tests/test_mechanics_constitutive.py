"""Material-point update: the consistent tangent is the derivative of the return map (finite
differences), elastic-plastic-TRIP split of the closed-form radial return, and the assembled
stiffness is the derivative of the internal force."""

import numpy as np
import pytest

from quenchsim.mechanics import load_mechanics
from quenchsim.mechanics import verification as v
from quenchsim.mechanics.constitutive import lame_bulk_shear, return_map, von_mises
from quenchsim.mechanics.solver import MechanicsSolver

RNG = np.random.default_rng(7)
N = 40
K, MU = lame_bulk_shear(np.full(N, 2.0e11), np.full(N, 0.3))
EPS = RNG.normal(size=(N, 4)) * 2e-3
SY, H = np.full(N, 300e6), np.full(N, 5e9)


@pytest.mark.parametrize("trip", [None, np.full(N, 2e-12)])
def test_consistent_tangent_matches_finite_differences(trip):
    up = return_map(EPS, K, MU, SY, H, trip)
    assert 0 < np.count_nonzero(up.d_eq_plastic) < N  # a mix of elastic and plastic points
    h = 1e-9
    for j in range(4):
        d = np.zeros(4)
        d[j] = h
        num = (return_map(EPS + d, K, MU, SY, H, trip).stress - return_map(EPS - d, K, MU, SY, H, trip).stress) / (2 * h)
        np.testing.assert_allclose(num, up.tangent[:, :, j], rtol=0, atol=1e-6 * 2e11)


def test_return_map_lands_on_the_yield_surface_and_flow_is_deviatoric():
    up = return_map(EPS, K, MU, SY, H, None)
    plastic = up.d_eq_plastic > 0
    q = von_mises(up.stress)
    np.testing.assert_allclose(q[plastic], SY[plastic] + H[plastic] * up.d_eq_plastic[plastic], rtol=1e-12)
    assert np.all(q[~plastic] <= SY[~plastic] * (1 + 1e-9))
    np.testing.assert_allclose(up.d_plastic_strain[:, :3].sum(axis=1), 0.0, atol=1e-15)
    # equivalent plastic strain increment = sqrt(2/3 |d eps_p|^2)
    np.testing.assert_allclose(np.sqrt(2 / 3 * np.sum(up.d_plastic_strain**2, axis=1)), up.d_eq_plastic, rtol=1e-12)


def test_trip_only_relaxes_the_deviator():
    dphi = np.full(N, 3e-11)
    up = return_map(EPS, K, MU, None, None, dphi)
    ref = return_map(EPS, K, MU, None, None, None)
    a = 3 * MU * dphi
    dev = ref.stress - (ref.stress[:, :3].mean(axis=1))[:, None] * np.array([1, 1, 1, 0])
    np.testing.assert_allclose(up.stress, ref.stress - dev * (a / (1 + a))[:, None], rtol=1e-12, atol=1e-3)
    np.testing.assert_allclose(up.d_trip_strain, 1.5 * dphi[:, None] * (up.stress - (up.stress[:, :3].mean(axis=1))[:, None]
                                                                       * np.array([1, 1, 1, 0])), rtol=1e-12, atol=1e-20)


def test_assembled_stiffness_is_the_derivative_of_the_internal_force():
    mesh = v.tube_mesh(0.0, 0.01, 0.02, 1)
    model = load_mechanics(v.uniform_material(2e11, 0.3, yield_Pa=200e6, hardening_Pa=5e9), {"trip": False})
    asm = MechanicsSolver(mesh, model).asm
    u = RNG.normal(size=asm.n_dofs) * 2e-5
    shape = asm.radius.shape
    k, mu = lame_bulk_shear(np.full(shape, 2e11), np.full(shape, 0.3))
    args = (k, mu, np.full(shape, 2e8), np.full(shape, 5e9), np.full(shape, 1e-11))
    up = return_map(asm.strain(u), *args)
    assert np.count_nonzero(up.d_eq_plastic) > 0
    stiffness = asm.stiffness(up).toarray()
    h = 1e-10
    num = np.zeros_like(stiffness)
    for j in range(asm.n_dofs):
        d = np.zeros(asm.n_dofs)
        d[j] = h
        f_plus = asm.internal_force(return_map(asm.strain(u + d), *args).stress)[0]
        f_minus = asm.internal_force(return_map(asm.strain(u - d), *args).stress)[0]
        num[:, j] = (f_plus - f_minus) / (2 * h)
    assert np.abs(num - stiffness).max() < 1e-7 * np.abs(stiffness).max()


@pytest.mark.parametrize("plastic, trip", [(True, True), (True, False), (False, True), (False, False)])
def test_compiled_point_update_equals_the_numpy_return_map_and_force(plastic, trip):
    mesh = v.tube_mesh(0.0, 0.01, 0.02, 2)
    model = load_mechanics(v.uniform_material(2e11, 0.3, yield_Pa=200e6, hardening_Pa=5e9), {"trip": False})
    asm = MechanicsSolver(mesh, model).asm
    shape = asm.radius.shape
    u = RNG.normal(size=asm.n_dofs) * 1e-6
    base = RNG.normal(size=shape + (4,)) * 1.5e-3
    k, mu = lame_bulk_shear(RNG.uniform(1.5e11, 2.1e11, shape), np.full(shape, 0.3))
    args = (k, mu, np.full(shape, 2e8) if plastic else None, np.full(shape, 5e9) if plastic else None,
            np.full(shape, 1e-11) if trip else None)
    ref = return_map(asm.strain(u) - base, *args)
    update, f_int, f_abs = asm.evaluate(u, base, *args)
    assert not plastic or 0 < np.count_nonzero(ref.d_eq_plastic) < ref.d_eq_plastic.size
    for name in ("stress", "beta", "c", "normal", "d_plastic_strain", "d_trip_strain", "d_eq_plastic"):
        a, b = getattr(update, name), np.broadcast_to(getattr(ref, name), getattr(update, name).shape)
        np.testing.assert_allclose(a, b, rtol=1e-11, atol=1e-11 * max(np.abs(b).max(), 1e-30), err_msg=name)
    f_ref, f_abs_ref = asm.internal_force(ref.stress)
    np.testing.assert_allclose(f_int, f_ref, rtol=0, atol=1e-11 * np.abs(f_abs_ref).max())
    np.testing.assert_allclose(f_abs, f_abs_ref, rtol=1e-11)

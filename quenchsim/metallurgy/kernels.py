"""Compiled (numba) point loops of the phase update :func:`quenchsim.metallurgy.advance`: the sub-step temperatures,
the selection of the sub-steps a reaction runs in (and their Gauss points), the competition of the reactions and
Koistinen-Marburger, each one pass over the points of a sub-step level.

The laws themselves (1/tau, n, the additivity powers, exp/expm1) stay NumPy calls on compact arrays of the sub-steps
that need them: NumPy evaluates exp, log and power with AVX-512 SIMD code, 3-10x faster than the scalar C library
calls a compiled loop makes (measured on this project's machines: 0.8 / 0.8 / 2.6 ns per value against ~10 ns in a
per-point chain), so a kernel doing the whole update per point was 1.3-1.4x slower than the NumPy version on the
calls of ring A condition 1 (docs/experiments/point_kernels.md). What is compiled here is the bookkeeping around the
laws (selections, clipping, scatters, ~100 array temporaries per sub-step level); the arithmetic per point is that of
:func:`quenchsim.metallurgy.transform.advance_reference`, in the same order, and the laws are the same NumPy
functions on the same values, so the two give the same numbers (tests/test_metallurgy_kernels.py).

numba's on-disk cache notices edits to this file only: the loops call nothing outside it.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def substep_temperatures(T0, dT, m, k, points, dt_s, fA, Ta, Tb, h, f):  # pragma: no cover (compiled)
    """Sub-step ``k`` of every point in ``points`` (m sub-steps of the step from T0 to T0 + dT): its temperatures
    Ta -> Tb, its length h = dt_s / m, and the austenite f it starts from (the first len(points) entries)."""
    for j in range(points.size):
        i = points[j]
        Ta[j] = T0[i] + dT[i] * (k / m[i])
        Tb[j] = T0[i] + dT[i] * ((k + 1) / m[i])
        h[j] = dt_s / m[i]
        f[j] = fA[i]


@njit(cache=True)
def cold_substeps(Ta, Tb, h, count, T_upper_C, gauss0, gauss1, tasks, T_gauss, T_mid, hs):  # pragma: no cover
    """The first ``count`` sub-steps that reach below ``T_upper_C`` (where the reaction runs): returns their number
    c and writes their indices (``tasks[:c]``), the 2-point Gauss temperatures of the part below T_upper
    (``T_gauss[:c]`` and ``T_gauss[c:2c]``), its mid temperature (``T_mid[:c]``) and its length (``hs[:c]``)."""
    c = 0
    for j in range(count):
        if min(Ta[j], Tb[j]) < T_upper_C:
            c += 1
    i = 0
    for j in range(count):
        ta, tb, length = Ta[j], Tb[j], h[j]
        if not min(ta, tb) < T_upper_C:
            continue
        if max(ta, tb) > T_upper_C:   # integrate only below T_upper (1/tau may jump there, e.g. at Bs)
            share = (T_upper_C - min(ta, tb)) / abs(tb - ta)
            ta, tb = (T_upper_C if ta > tb else ta), (T_upper_C if tb > ta else tb)
            length = length * share
        tasks[i] = j
        T_gauss[i] = ta + (tb - ta) * gauss0
        T_gauss[c + i] = ta + (tb - ta) * gauss1
        T_mid[i] = 0.5 * (ta + tb)
        hs[i] = length
        i += 1
    return c


@njit(cache=True)
def scatter_increments(q, points, tasks, c, q_new, d):  # pragma: no cover (compiled)
    """d[tasks[j]] = q_new[j] - q[points[tasks[j]]] and q updated to q_new, for j < c (d: per sub-step, zero
    where the reaction did not run, set by the caller)."""
    for j in range(c):
        i = points[tasks[j]]
        d[tasks[j]] = q_new[j] - q[i]
        q[i] = q_new[j]


@njit(cache=True)
def total_increments(d, count, total):  # pragma: no cover (compiled)
    """total[j] = sum over the reactions of d[r, j] (from 0, in reaction order), for j < count."""
    for j in range(count):
        s = 0.0
        for r in range(d.shape[0]):
            s += d[r, j]
        total[j] = s


@njit(cache=True)
def share_out(products, rows, points, d, total, expm1_of_minus_total, f, count):  # pragma: no cover (compiled)
    """The competition: the austenite f turns f (1 - exp(-total)) into the products (``products[rows[r]]``) in
    proportion to their increments d[r], where total > 0; f is what is left."""
    for j in range(count):
        consumed = f[j] * -expm1_of_minus_total[j]
        t = total[j]
        if t > 0.0:
            i = points[j]
            for r in range(rows.size):
                products[rows[r], i] += consumed * d[r, j] / t
        f[j] = f[j] - consumed


@njit(cache=True)
def martensite_exponent(points, T_min, Ms_C, alpha_per_K, Tb, count, x):  # pragma: no cover (compiled)
    """x = -alpha max(min(T_min, Ms) - Tb, 0): Koistinen-Marburger below the lowest temperature reached."""
    minus_alpha = -alpha_per_K
    for j in range(count):
        T_ref = min(T_min[points[j]], Ms_C)
        x[j] = minus_alpha * max(T_ref - Tb[j], 0.0)


@njit(cache=True)
def form_martensite(points, f, expm1_of_x, Tb, count, martensite, fA, T_min):  # pragma: no cover (compiled)
    """f (1 - exp(x)) of the austenite left turns to martensite; the lowest temperature follows Tb."""
    for j in range(count):
        i = points[j]
        converted = f[j] * -expm1_of_x[j]
        martensite[i] += converted
        fA[i] = f[j] - converted
        T_min[i] = min(T_min[i], Tb[j])

"""Integrator choice by measurement: every SciPy method on the same short window of a settled run."""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import solve_ivp

from quenchsim.bearings.big_end.case import BigEndCase
from quenchsim.bearings.big_end.simulate import (INTEGRATORS, RTOL, build_params, integrate, rhs_function,
                                                 solver_options)


class _Budget(Exception):
    """Raised inside the right-hand side when a method exceeds its evaluation budget."""


def integrator_benchmark(case: BigEndCase, set_number: int, mode: str, settle_revolutions: float,
                         window_revolutions: float, max_evaluations: int = 200_000,
                         methods: tuple[str, ...] = INTEGRATORS) -> list[dict]:
    """Integrate ``window_revolutions`` from the state reached after ``settle_revolutions`` (RK45) with
    each method; returns evaluations, steps-free wall time and the extrapolated cost per revolution.
    A method that needs more than ``max_evaluations`` right-hand sides is stopped and reported so."""
    p, _, _ = build_params(case, set_number, mode)
    t, y, _, _ = integrate(p, settle_revolutions, 36, "RK45")
    t0, y0 = t[-1], np.ascontiguousarray(y[:, -1])
    rhs = rhs_function(p)
    t1 = t0 + window_revolutions * 2 * np.pi / p.omega
    rows = []
    for method in methods:
        count = [0]

        def fun(tt, yy, count=count):
            count[0] += 1
            if count[0] > max_evaluations:
                raise _Budget
            return rhs(tt, yy)

        options = solver_options(p, method)
        rhs(t0, y0)  # compiled specialisations loaded outside the timing
        if "jac" in options:
            options["jac"](t0, y0)
        start = time.perf_counter()
        try:
            sol = solve_ivp(fun, (t0, t1), y0, method=method, rtol=RTOL, **options)
            finished = bool(sol.success)
        except _Budget:
            finished = False
        wall = time.perf_counter() - start
        rows.append({
            "method": method, "finished": finished, "rhs_evaluations": count[0], "wall_time_s": wall,
            "wall_s_per_revolution": wall / window_revolutions if finished else float("nan"),
            "rhs_per_revolution": count[0] / window_revolutions if finished else float("nan"),
        })
    return rows

"""Bearing-analysis solvers; they share only :mod:`hertz` and :mod:`kinematics`."""

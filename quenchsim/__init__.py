"""quenchsim: oil-quench simulation of steel bearing rings and bearing-analysis solvers."""

__version__ = "0.1.0"

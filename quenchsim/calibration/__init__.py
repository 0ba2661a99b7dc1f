"""Calibration and uncertainty: fit the inputs no data sheet gives to measured parts, predict others with bands.

    spec = load_calibration("CAL.toml")         # free inputs (each with a prior in its data file), measurements, cases
    result = calibrate(spec, "runs/cal")         # design on Dask -> screening -> GP surrogate -> emcee posterior
    bands = propagate(case, "runs/c4", n=20, posterior="runs/cal")   # `quenchsim run ... --uncertainty 20`

Modules: :mod:`~quenchsim.calibration.inputs` (input paths, priors, derived data files),
:mod:`~quenchsim.calibration.spec` (the calibration file), :mod:`~quenchsim.calibration.data` (the measured data of
every kind -- values, bounds, probe orders, cooling curves, hardness traverses -- and their observables),
:mod:`~quenchsim.calibration.runs` (cached runs), :mod:`~quenchsim.calibration.design` (design and sensitivity),
:mod:`~quenchsim.calibration.surrogate`, :mod:`~quenchsim.calibration.likelihood` (measurement, surrogate error and
model discrepancy), :mod:`~quenchsim.calibration.posterior`, :mod:`~quenchsim.calibration.conflicts` (which data
pull which inputs, which conflict), :mod:`~quenchsim.calibration.calibrate` (the command's pipeline),
:mod:`~quenchsim.calibration.propagate` (bands on a run).
"""

from quenchsim.calibration.calibrate import calibrate, fit_design, infer, prediction_bands, run_design
from quenchsim.calibration.inputs import FreeInput, declared_priors, derived_files, free_input
from quenchsim.calibration.propagate import propagate
from quenchsim.calibration.spec import CalibrationSpec, load_calibration, parse_calibration

__all__ = ["CalibrationSpec", "FreeInput", "calibrate", "declared_priors", "derived_files", "fit_design",
           "free_input", "infer", "load_calibration", "parse_calibration", "prediction_bands", "propagate",
           "run_design"]

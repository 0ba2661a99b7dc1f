"""Process design: ``quenchsim optimise STUDY.toml`` -- the settings (any case field) that meet the constraints and
minimise (or maximise, or hit) summary quantities, with Optuna over the cached Dask runner: a cheap fidelity
explores, the full chain confirms. :mod:`~quenchsim.design.spec` reads a study file, :mod:`~quenchsim.design.optimise`
drives the sampler, :mod:`~quenchsim.design.study` runs a case study and :mod:`~quenchsim.design.page` writes what
a process engineer reads."""

"""The typed case: a case file read against its declaration and checked in one place, before any work starts.

    case = load_case("cases/crb_outer_ring.toml", condition="1", overrides={"quench.time_s": 600})
    case.quench.time_s, case.mesh.size_mm, case.probes[0].name, case.bath.oil_temperature_C
    longer = dataclasses.replace(case, quench=dataclasses.replace(case.quench, time_s=900.0))   # checked again
    finer = case.refined(mesh=0.5)              # a derived case, checked again

A case file holds one ring, one steel and a process; ``[conditions.NAME]`` tables are deep-merged over
the base case. Lengths in the file are in mm (``*_mm``), times in s, temperatures in degrees C. Every
error is an :class:`~quenchsim.errors.InputError` naming the file, the key (dotted path), the value and what is
allowed. The tables are declared in :mod:`quenchsim.inputs.case` (every key: docs/reference/case_keys.md);
``cases/crb_outer_ring.toml`` is a complete, commented example.
"""

from quenchsim.case.model import (AirStage, Case, MechanicsOptions, MeshSpec, OutputSpec, Probe, ProcessSpec,
                                  QuenchStage, TemperStage, TimeControl, TransferStage)
from quenchsim.case.parse import case_from_dict, deep_merge, load_case, set_dotted

__all__ = ["AirStage", "Case", "MechanicsOptions", "MeshSpec", "OutputSpec", "Probe", "ProcessSpec", "QuenchStage",
           "TemperStage", "TimeControl", "TransferStage", "case_from_dict", "deep_merge", "load_case", "set_dotted"]

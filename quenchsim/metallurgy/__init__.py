"""Phase transformations and hardness of quenched steel.

Public API (used by the time loop)::

    kin = load_kinetics(material, T_aust_C)            # material = quenchsim.materials.load_material("SUJ3")
    state = initial_state(shape, kin)                  # fully austenitic
    new = advance(state, kin, T_old_C, T_new_C, dt_s)  # pure; T linear in time over the step
    new.fractions["martensite"], new.cooling_rate_700_C_s
    hv = hardness_HV(new, kin); hrc = hv_to_hrc(hv)

Pearlite and bainite follow JMAK laws with Scheil additivity, martensite the Koistinen-Marburger law
below Ms; tempering (the ``[temper]`` stage, service stability) in :mod:`quenchsim.metallurgy.tempering`; see
:mod:`quenchsim.metallurgy.transform` for the algorithm and
:mod:`quenchsim.metallurgy.kinetics` for the material-file schema. CCT curves: :mod:`quenchsim.metallurgy.cct`.
"""

from quenchsim.metallurgy.adapter import PhaseModel
from quenchsim.metallurgy.hardness import hardness_HV, hrc_to_hv, hv_to_hrc, phase_hardness_HV
from quenchsim.metallurgy.kinetics import Kinetics, Reaction, load_kinetics
from quenchsim.metallurgy.transform import PhaseState, advance, incubation_share, initial_state
from quenchsim.metallurgy.tempering import Tempering, TemperingPhaseModel, TemperState, load_tempering

__all__ = ["Kinetics", "PhaseModel", "Reaction", "PhaseState", "load_kinetics", "initial_state", "advance", "incubation_share",
           "hardness_HV",
           "phase_hardness_HV", "hv_to_hrc", "hrc_to_hv", "Tempering", "TemperingPhaseModel", "TemperState",
           "load_tempering"]

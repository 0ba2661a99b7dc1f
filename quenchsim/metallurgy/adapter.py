"""The metallurgy as the thermal solver's phase model (:class:`quenchsim.thermal.PhaseModel`), with the state's
checkpoint form: one adapter for a steel that transforms (its :class:`Kinetics`) and for a material that does not
(``kin`` None: the phase it was heated to stays, no latent heat)."""

from __future__ import annotations

from typing import Any

import numpy as np

from quenchsim.metallurgy.kinetics import Kinetics
from quenchsim.metallurgy.transform import PhaseState, advance, initial_state

UNTRANSFORMED_PHASE = "austenite"
"""The phase of a material that does not transform (its state is that phase's fraction, 1 everywhere)."""


class PhaseModel:
    """``advance``, ``fractions`` and the checkpoint form of the phase state of ``kin`` (None: no transformation).

    ``time_dependent_phases``: the products of the diffusional reactions, whose fraction change per step
    ``time.max_dX`` limits; martensite is a function of the temperature alone (Koistinen-Marburger), so
    ``time.max_dT_K`` limits its steps."""

    def __init__(self, kin: Kinetics | None) -> None:
        self.kin = kin
        self.time_dependent_phases: tuple[str, ...] = () if kin is None else tuple(kin.reactions)

    def initial_state(self, shape: tuple[int, ...]) -> Any:
        """Fully austenitic at every point of ``shape``."""
        return np.ones(shape) if self.kin is None else initial_state(shape, self.kin)

    def advance(self, state: Any, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> Any:
        return state if self.kin is None else advance(state, self.kin, T_old_C, T_new_C, dt_s)

    def fractions(self, state: Any) -> dict[str, np.ndarray]:
        return {UNTRANSFORMED_PHASE: state} if self.kin is None else state.fractions

    def checkpoint_state(self, state: Any) -> dict[str, Any]:
        if self.kin is None:
            return {"fractions": self.fractions(state)}
        return {"fractions": state.fractions, "additivity": state.additivity, "T_min_C": state.T_min_C,
                "cooling_rate_700_C_s": state.cooling_rate_700_C_s}

    def restore_state(self, arrays: dict[str, Any]) -> Any:
        if self.kin is None:
            return np.array(arrays["fractions"][UNTRANSFORMED_PHASE])
        return PhaseState(fractions={p: np.array(v) for p, v in arrays["fractions"].items()},
                          additivity={r: np.array(v) for r, v in arrays.get("additivity", {}).items()},
                          T_min_C=np.array(arrays["T_min_C"]), cooling_rate_700_C_s=np.array(arrays["cooling_rate_700_C_s"]))

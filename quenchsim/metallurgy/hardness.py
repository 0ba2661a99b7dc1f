"""As-quenched hardness: per-phase values mixed by the phase fractions, and the HV -> HRC conversion.

HV = sum_i X_i HV_i (rule of mixtures, Li et al. 1998 eq. 26, here with retained austenite as a
phase of its own). Each HV_i is either a documented constant or the Maynier et al. (1978) form
A(w) + B(w) log10(V_r) with V_r the cooling rate at 700 C in degC/h, optionally capped at max_HV.
Points that have not crossed 700 C yet (V_r unknown) and rates below 1 degC/h use log10(V_r) = 0.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

from quenchsim.inputs.reader import read_toml
from quenchsim.metallurgy.kinetics import Kinetics
from quenchsim.metallurgy.laws import maynier_hv
from quenchsim.metallurgy.transform import PhaseState

CONVERSION_TABLE = Path(__file__).with_name("data") / "hv_hrc_astm_e140.toml"
SECONDS_PER_HOUR = 3600.0


def phase_hardness_HV(kin: Kinetics, phase: str, cooling_rate_700_C_s: np.ndarray) -> np.ndarray:
    """Hardness (HV) of one phase at the given cooling rates at 700 C (degC/s, NaN = unknown)."""
    spec = kin.hardness[phase]
    rate = np.asarray(cooling_rate_700_C_s, dtype=float) * SECONDS_PER_HOUR
    log_rate = np.where(np.isfinite(rate) & (rate > 1.0), np.log10(np.where(rate > 1.0, rate, 1.0)), 0.0)
    hv = maynier_hv({"base": spec.base, "rate": spec.rate}, spec.composition, log_rate)
    return np.minimum(np.broadcast_to(hv, log_rate.shape), spec.max_HV)


def hardness_HV(state: PhaseState, kin: Kinetics) -> np.ndarray:
    """Mixed Vickers hardness of each point: sum over the four phases of X_i HV_i."""
    return sum(state.fractions[p] * phase_hardness_HV(kin, p, state.cooling_rate_700_C_s) for p in kin.hardness)


@lru_cache(maxsize=1)
def _conversion_table() -> tuple[np.ndarray, np.ndarray]:
    data = read_toml(CONVERSION_TABLE, "hardness conversion table")
    return np.asarray(data["HV"], dtype=float), np.asarray(data["HRC"], dtype=float)


def hv_to_hrc(hv: np.ndarray) -> np.ndarray:
    """Rockwell C from Vickers by linear interpolation in ASTM E140 Table 1; NaN outside 238-940 HV (20-68 HRC)."""
    HV, HRC = _conversion_table()
    x = np.asarray(hv, dtype=float)
    return np.where((x >= HV[0]) & (x <= HV[-1]), np.interp(x, HV, HRC), np.nan)


def hrc_to_hv(hrc: np.ndarray) -> np.ndarray:
    """Vickers from Rockwell C (inverse of :func:`hv_to_hrc`, same table); NaN outside 20-68 HRC."""
    HV, HRC = _conversion_table()
    x = np.asarray(hrc, dtype=float)
    return np.where((x >= HRC[0]) & (x <= HRC[-1]), np.interp(x, HRC, HV), np.nan)

"""The [quench.bath] table of reference ring A, read from the shipped case file (one source for the tests)."""

import copy
from functools import lru_cache
from pathlib import Path

from quenchsim.case import load_case

CASE_A = Path(__file__).resolve().parents[1] / "cases" / "crb_outer_ring.toml"


@lru_cache(maxsize=None)
def _case_a_bath(condition: str) -> dict:
    return load_case(CASE_A, condition).data["quench"]["bath"]


def case_a_bath_spec(condition: str = "1") -> dict:
    """A fresh copy of case A's [quench.bath] under ``condition`` (jet speeds of Table 1)."""
    return copy.deepcopy(_case_a_bath(condition))

"""Design study, case A: the ID and OD jet speeds of the cylindrical-roller-bearing outer ring (cases/crb_outer_ring.toml)
that keep condition 1's HRC58 depth below the raceway and change the raceway's diameter and crown least
(ring_a.study.toml), with design/ring_b's helpers. Runs: ``runs/validation/design_ring_a/<code fingerprint>/``."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from quenchsim.validation import study_module

TITLE = "Design study, case A: ID/OD jet speeds for the least raceway diameter change and crown at condition 1's hardness"
SLOW = True
STUDY_FILE = Path(__file__).with_name("ring_a.study.toml")
NOTE_A = ("Ring A is not through-hardened: its HRC58 depth below the raceway depends on both jets, on a knife edge "
          "(either jet at the fast end of its range alone hardens the wall through, quench/process_response), so the "
          "hardness constraint bounds the search. Physics of issue 33 (see the ring_b page's note).")


def run(workdir: Path) -> dict[str, Any]:
    return study_module("design/ring_b").run_design(STUDY_FILE, Path(workdir), "ring_a")


def page(metrics: dict[str, Any]) -> str:
    return study_module("design/ring_b").design_page(metrics, NOTE_A)

"""How old_model_response.json was made: the response of the segment-mean h to the ID and OD jet speeds of the bath
model before issue 33 (commit bae6c38), rings A and B. Run it with the interpreter of a checkout of that commit
(e.g. `git worktree add /tmp/old bae6c38`, install it, `python old_model_response.py > old_model_response.json`);
the study reads the JSON only."""
import json
import subprocess
from pathlib import Path

import numpy as np
import quenchsim
from quenchsim.case import load_case
from quenchsim.bath.segments import outline_htc, segment_groups

T_LIST = (200.0, 400.0, 600.0, 800.0)
ID_SPEEDS = (400.0, 540.0, 1000.0, 1440.0, 2000.0)
OD_SPEEDS = (1470.0, 1780.0, 3280.0, 5340.0, 10680.0)
ROOT = Path(quenchsim.__file__).resolve().parents[1]
CASES = {"A": (ROOT / "cases" / "crb_outer_ring.toml", "1"), "B": (ROOT / "cases" / "srb_outer_ring.toml", "4")}
BASES = {"A": {"id": "1", "od": "1"}, "B": {"id": "4", "od": "5"}}
"""The condition each sweep starts from: ring A condition 1; ring B's ID sweep from condition 4 (OD 3280 mm/s, as 4 -> 5)
and its OD sweep from condition 5 (ID 1440 mm/s, as 5 -> 6)."""

def table(case, cond, overrides):
    c = load_case(case[0], cond, overrides)
    pts, htc = outline_htc(c.profile, c.bath)
    out = {}
    for seg, idx in segment_groups(htc).items():
        out[seg] = {str(int(T)): float(np.mean([np.interp(T, htc.T_grid_C, htc.h_W_m2K[i]) for i in idx])) for T in T_LIST}
        out[seg]["T_L"] = float(np.mean(htc.leidenfrost_C[idx]))
    return out

res = {"bases": BASES, "commit": subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()}
for label, case in CASES.items():
    base = load_case(*case)
    res[label] = {"id": {}, "od": {}}
    for v in ID_SPEEDS:
        res[label]["id"][str(int(v))] = table(case, BASES[label]["id"], {"quench.bath.id_jet_speed_mm_s": v})
    for v in OD_SPEEDS:
        res[label]["od"][str(int(v))] = table(case, BASES[label]["od"], {"quench.bath.od_jet_speed_mm_s": v})
print(json.dumps(res))

"""Validation (slow, minutes per run): case-A section centre P1 relative to condition 1, full thermal chain.

Report (shared/reference/quench_cases.md): condition 2 reaches 500 C in 0.75 +- 0.08 of condition 1's time;
condition 3 cools P1 to 500 C at 0.6 +- 0.1 of condition 1's rate.
"""

import pytest

from quenchsim.report.bath import case_a_study


@pytest.mark.slow
def test_case_a_centre_cooling_relative_to_condition_1(tmp_path):
    rel = case_a_study(tmp_path)["relative_to_condition_1"]
    assert rel["2"]["time_ratio"] == pytest.approx(0.75, abs=0.08)
    assert rel["3"]["rate_ratio"] == pytest.approx(0.6, abs=0.1)

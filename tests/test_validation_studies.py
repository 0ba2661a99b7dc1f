"""Every study of validation/ against its targets.toml: the fast ones (SLOW = False, seconds) in the default
suite, all of them under -m slow. A target with status "open" is a declared miss: it is reported, not asserted;
"reference" values carry no tolerance."""

from __future__ import annotations

import pytest

from quenchsim import validation as v

STUDIES = v.discover()
FAST_IN_DEFAULT_SUITE = ("bearings/hertz", "bearings/grease", "quench/thermal_verification")
"""Studies of a second or two; the others that run in seconds (free_run, runout, cct: ~5-10 s) are SLOW = False
for `quenchsim validate --fast` but kept out of the default suite, whose modules already test their functions."""


def test_every_targets_file_parses_and_every_study_declares_title_and_slow():
    assert len(STUDIES) >= 15
    for s in STUDIES:
        assert s.title() != s.key and isinstance(s._constant("SLOW", None), bool), s.key
        assert all(t.source for t in s.targets)


def _check(study: v.Study, tmp_path) -> None:
    result = v.run_study(study, tmp_path / "reports", tmp_path / "runs")
    assert result.status == "ran", result.error
    missed = [f"{x.target.metric} = {x.value} (target {x.target.describe()})" for x in result.verdicts
              if x.state in ("missed", "absent")]
    assert not missed, missed


@pytest.mark.parametrize("key", FAST_IN_DEFAULT_SUITE)
def test_fast_study_meets_its_targets(key, tmp_path):
    _check(next(s for s in STUDIES if s.key == key), tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("study", [s for s in STUDIES if s.key not in FAST_IN_DEFAULT_SUITE], ids=lambda s: s.key)
def test_study_meets_its_targets(study, tmp_path):
    _check(study, tmp_path)

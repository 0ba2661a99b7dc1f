"""The data file shown in docs/guide/bring_a_steel.md is complete: `material fit` takes it as written (issue 36:
the schema's required entries were undocumented and took a new user three tries)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from quenchsim.cli import main

GUIDE = Path(__file__).resolve().parents[1] / "docs" / "guide" / "bring_a_steel.md"


def _guide_data_file() -> str:
    text = GUIDE.read_text()
    start = text.index("```toml\n", text.index("## 1.")) + len("```toml\n")
    return text[start:text.index("```", start)]


def test_the_guides_data_file_fits_as_written(tmp_path, monkeypatch, capsys):
    (tmp_path / "MY_STEEL.toml").write_text(_guide_data_file())
    monkeypatch.chdir(tmp_path)
    assert main(["material", "fit", "MY_STEEL.toml"]) == 0
    written = tomllib.loads((tmp_path / "materials" / "MY_STEEL.toml").read_text())
    pearlite = written["kinetics"]["pearlite"]
    for key in ("T_upper_C", "tau_ref_s", "undercooling_exponent", "Q_J_mol", "n"):
        assert pearlite[key]["source"], key


def test_material_fit_help_says_where_the_schema_is(capsys):
    with pytest.raises(SystemExit):
        main(["material", "fit", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "docs/guide/bring_a_steel.md" in help_text
    assert "pydoc quenchsim.fitting.diagram_data" in help_text

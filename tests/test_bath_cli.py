"""`quenchsim bath CASE.toml --condition N [--png]`: prints the per-segment table, plots, errors exit 2."""

from pathlib import Path

from quenchsim.cli import main

CASE_A = Path(__file__).resolve().parents[1] / "cases" / "crb_outer_ring.toml"


def test_bath_command_prints_segments_and_writes_png(tmp_path, capsys):
    png = tmp_path / "htc.png"
    assert main(["bath", str(CASE_A), "--condition", "2", "--png", str(png), "--spacing-mm", "5"]) == 0
    out = capsys.readouterr().out
    assert "OD jets 10680.0 mm/s" in out
    for segment in ("bore", "od", "top", "bottom"):
        assert any(line.startswith(segment + " ") for line in out.splitlines())
    assert png.stat().st_size > 10_000 and (tmp_path / "htc_speed.png").stat().st_size > 10_000


def test_bath_command_bad_input_exits_2(capsys):
    assert main(["bath", str(CASE_A), "--condition", "1", "--spacing-mm", "0"]) == 2
    assert "--spacing-mm" in capsys.readouterr().err

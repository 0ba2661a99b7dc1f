"""`quenchsim cct`: table, JSON, PNG, and one-line errors naming the field."""

from __future__ import annotations

import json

from quenchsim.cli import main


def test_cct_json_matches_hardenability_order(capsys):
    """Below and above the ~12 C/s critical rate of the 100Cr6 data: pearlitic at 3 C/s, martensitic at 30 C/s; neither
    steel forms more bainite than Kawulok et al. (2020) could have missed ('absence of bainite', detection 0.02)."""
    assert main(["cct", "SUJ3", "--T-aust", "845", "--rates", "3", "30", "--json"]) == 0
    suj3 = json.loads(capsys.readouterr().out)
    assert main(["cct", "SUJ2", "--T-aust", "845", "--rates", "3", "30", "--json"]) == 0
    suj2 = json.loads(capsys.readouterr().out)
    assert suj3["rates_C_s"] == [3.0, 30.0]
    for d in (suj2, suj3):
        assert d["final_fractions"]["pearlite"][0] > 0.99 and d["final_fractions"]["martensite"][1] > 0.8
    for d in (suj2, suj3):
        assert max(d["final_fractions"]["bainite"]) <= 0.02
    for d in (suj2, suj3):
        total = [sum(d["final_fractions"][p][i] for p in d["final_fractions"]) for i in range(2)]
        assert all(abs(t - 1.0) < 1e-12 for t in total)


def test_cct_table_and_png(tmp_path, capsys):
    png = tmp_path / "cct.png"
    assert main(["cct", "100Cr6_furlan", "--T-aust", "850", "--rates", "1", "10", "--png", str(png)]) == 0
    out = capsys.readouterr().out
    assert "Ms 229 C" in out and "bainite below 385 C" in out
    assert png.stat().st_size > 10_000


def test_cct_bad_inputs_one_line(capsys):
    assert main(["cct", "NOSUCHSTEEL"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("quenchsim: error: material = 'NOSUCHSTEEL'") and "\n" not in err
    assert main(["cct", "SUJ3", "--T-aust", "1000"]) == 2
    assert "T_aust_C = 1000.0" in capsys.readouterr().err
    assert main(["cct", "SUJ3", "--rates", "-1"]) == 2
    assert "--rates" in capsys.readouterr().err

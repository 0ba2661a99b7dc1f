"""CalculiX peer: the deck writer and the result readers on a tiny problem (no ccx needed), and the
comparison itself where ccx is installed (slow)."""

import shutil
from pathlib import Path

import numpy as np
import pytest

from quenchsim.io import calculix
from quenchsim.materials import load_material
from quenchsim.mechanics import load_mechanics
from quenchsim.mechanics import verification as v
from quenchsim.mechanics.model import phase_free_strain


@pytest.fixture(scope="module")
def model():
    return load_mechanics(load_material("SUJ3"), {"trip": False})


def test_p2_nodes_are_the_scalar_p2_dofs_and_elements_are_counter_clockwise():
    mesh = v.tube_mesh(0.1, 0.12, 0.02, 2)
    nodes, conn = calculix.p2_nodes(mesh)
    assert len(nodes) == mesh.p.shape[1] + mesh.facets.shape[1]
    x, y = nodes[conn[:, :3], 0], nodes[conn[:, :3], 1]
    area = (x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0])
    assert np.all(area > 0)
    for a, b, m in ((0, 1, 3), (1, 2, 4), (2, 0, 5)):  # mid-side nodes halve their edges
        np.testing.assert_allclose(nodes[conn[:, m]], 0.5 * (nodes[conn[:, a]] + nodes[conn[:, b]]), atol=1e-15)


def test_material_tables_reproduce_the_free_strain_and_the_table_knots(model):
    grid = calculix.temperature_grid(model, "austenite", 20.0, model.austenitizing_T_C)
    yield_knots = model.yield_Pa.for_phase("austenite").T_C
    inside = yield_knots[(yield_knots > 20.0) & (yield_knots < model.austenitizing_T_C)]
    assert set(np.round(inside, 9)) <= set(grid)
    tab = calculix.material_tables(model, "austenite", grid)
    eps = tab["alpha_secant_1_K"] * (grid - model.austenitizing_T_C)
    np.testing.assert_allclose(eps, phase_free_strain(model, "austenite", grid), rtol=1e-12, atol=1e-15)
    assert np.all(tab["E_Pa"] > 0) and np.all(tab["yield_Pa"] > 0)


def test_deck_holds_every_node_element_step_and_temperature(tmp_path, model):
    mesh = v.tube_mesh(0.1, 0.12, 0.02, 2)
    nodes, conn = calculix.p2_nodes(mesh)
    temps = [np.full(len(nodes), 600.0), np.linspace(20.0, 300.0, len(nodes))]
    tables = calculix.material_tables(model, "austenite", np.array([20.0, 500.0, 850.0]))
    deck = calculix.write_inp(tmp_path / "t.inp", mesh, tables, 850.0, temps, [1.0, 3.0], fixed_node=4)
    text = deck.read_text()
    assert text.count("*STEP") == 2 and text.count("*TEMPERATURE") == 2
    assert "TYPE=CAX6" in text and "*EXPANSION, ZERO=850" in text
    body = text.split("*ELEMENT, TYPE=CAX6, ELSET=EALL\n")[1].split("*NSET")[0].strip().splitlines()
    assert len(body) == len(conn)
    assert [int(i) for i in body[0].split(",")[1:]] == [int(c) + 1 for c in conn[0]]
    assert "*NSET, NSET=NFIX\n5\n*BOUNDARY\nNFIX, 2, 2" in text
    steps = text.split("*STATIC\n")[1:]
    assert steps[0].startswith("1, 1\n") and steps[1].startswith("2, 2\n")
    last_temperatures = steps[1].split("*TEMPERATURE\n")[1].splitlines()[:len(nodes)]
    np.testing.assert_allclose([float(r.split(",")[1]) for r in last_temperatures], temps[1], rtol=1e-9)
    plastic = text.split("*PLASTIC\n")[1].split("*SOLID")[0].strip().splitlines()
    assert len(plastic) == 2 * 3  # two points per temperature
    sy, H = tables["yield_Pa"][0], tables["hardening_Pa"][0]
    assert [float(x) for x in plastic[1].split(",")] == pytest.approx([sy + H * calculix.PLASTIC_STRAIN_END,
                                                                        calculix.PLASTIC_STRAIN_END, 20.0])
    with pytest.raises(Exception, match="calculix.temperatures_C"):
        calculix.write_inp(tmp_path / "bad.inp", mesh, tables, 850.0, temps, [1.0], fixed_node=0)


def test_readers_take_the_last_blocks_of_dat_and_frd(tmp_path):
    dat = tmp_path / "r.dat"

    def block(time_s: float, scale: float) -> str:
        rows = "".join(f"{k:10d} {k * scale: .6E} {-k * scale: .6E}  0.000000E+00\n" for k in (1, 2, 3))
        return f" displacements (vx,vy,vz) for set NALL and time  {time_s:.7E}\n\n{rows}\n"

    dat.write_text(block(1.0, 1e-3) + block(2.0, 2e-3))
    u = calculix.read_dat_displacements(dat, 3)
    np.testing.assert_allclose(u, [[2e-3, -2e-3], [4e-3, -4e-3], [6e-3, -6e-3]])
    frd = tmp_path / "r.frd"
    rows = "".join(f" -1{k:10d}" + "".join(f"{(10 * k + j) * 1e6:12.5E}" for j in range(6)) + "\n" for k in (1, 2, 3, 4))
    frd.write_text(" -4  STRESS      6    1\n -5  SXX         1    4    1    1\n" + rows + " -3\n")
    s = calculix.read_frd_block(frd, "STRESS", 3)  # node 4 (an expansion node) is dropped
    assert s.shape == (3, 6)
    assert s[1, 2] == pytest.approx(22e6)
    with pytest.raises(Exception, match="DISP"):
        calculix.read_frd_block(frd, "DISP", 3)


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason="ccx not installed (apt-get install calculix-ccx)")
def test_quenchsim_agrees_with_calculix_on_the_thermal_only_ring(tmp_path):
    """Issue 21: uniform 3000 W/m2K on case A's section, all austenite, both codes on one history."""
    from quenchsim.validation import study_module
    study = study_module("mechanics/calculix")
    out = study.compare(study.HTC_CASES["uniform"], Path(tmp_path), shutil.which("ccx"))
    assert out["difference"]["max_dimension_mm"] < 0.005
    assert out["difference"]["max_hoop_MPa"] < 5.0


def test_the_study_skips_cleanly_without_ccx(monkeypatch, tmp_path):
    """No ccx: the study says so, its targets are 'skipped' (no miss), and nothing is installed."""
    from quenchsim.validation import evaluate, load_targets, study_module
    study = study_module("mechanics/calculix")
    monkeypatch.setattr(study.shutil, "which", lambda name: None)
    metrics = study.run(tmp_path)
    assert metrics == {"skipped": "skipped: ccx not found (install CalculiX, e.g. apt-get install calculix-ccx)"}
    targets = load_targets(Path(study.__file__).parent / "targets.toml", "mechanics/calculix")
    verdicts = evaluate(targets, metrics)
    assert len(verdicts) == 4 and all(v.state == "skipped" and not v.counts_as_miss for v in verdicts)
    assert "skipped: ccx not found" in study.page(metrics)

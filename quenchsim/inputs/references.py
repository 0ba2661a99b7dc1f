"""The key references of docs/reference/ generated from the declarations (:mod:`quenchsim.inputs.declare`): one
table of keys per declared table, with what each takes, its unit, default, limits and meaning.

``python dev/write_references.py`` writes them; tests/test_inputs.py checks that the committed files are current.
"""

from __future__ import annotations

from dataclasses import dataclass

from quenchsim.inputs.bath import BathTable, NozzleRowTable
from quenchsim.inputs.case import (Air, MechanicsOptions, Mesh, Output, Probe, ProfileGeometry,
                                   ProfileSegment, Process, Quench, RectangularGeometry, SphericalOuterGeometry, Temper,
                                   TimeControl, Transfer)
from quenchsim.inputs.declare import Table, key_rows
from quenchsim.inputs.htc import HtcTable


@dataclass(frozen=True)
class Section:
    """One section of a reference page: a heading, a paragraph and the declared table whose keys it lists."""

    heading: str
    text: str
    table: type[Table]
    skip: tuple[str, ...] = ()


def key_table(table: type[Table], skip: tuple[str, ...] = ()) -> list[str]:
    """The markdown table of ``table``'s declared keys."""
    lines = ["| key | takes | unit | default | limits | meaning |", "|---|---|---|---|---|---|"]
    for row in key_rows(table):
        if row.key in skip:
            continue
        cells = [f"`{row.key}`", row.takes, row.unit or "-", row.default, row.limits.replace("|", "/") or "-",
                 row.doc.replace("|", "/")]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def page(title: str, intro: str, sections: list[Section]) -> str:
    """A reference page: its title, introduction and one key table per section."""
    lines = [f"# {title}", "", intro.strip(), "",
             "Generated from the declarations in quenchsim/inputs/ by `python dev/write_references.py`; do not edit by "
             "hand (tests/test_inputs.py checks it is current).", ""]
    for section in sections:
        lines += [f"## {section.heading}", ""]
        if section.text:
            lines += [section.text.strip(), ""]
        lines += [*key_table(section.table, section.skip), ""]
    return "\n".join(lines).rstrip() + "\n"


CASE_INTRO = """
Every key a case file (`quenchsim run CASE.toml`) accepts, with what it takes, its unit, default and limits. A key not
listed is an error when the case loads (`unknown key; [table] takes ...`, with the closest known name), in every
condition's tables too; an error names the file, the key, the value and what is allowed. How to use them:
[../guide/run_a_ring.md](../guide/run_a_ring.md). Lengths in mm, times in s, temperatures in C. "required" means no
default; a `[conditions.NAME]` table holds any of the tables below (not `conditions`) and is merged over the case
with `--condition NAME`. Any key can be set from the command line with `--set TABLE.KEY=VALUE`.
"""


def case_keys() -> str:
    """docs/reference/case_keys.md."""
    from quenchsim.case.model import Case

    return page("Case file keys", CASE_INTRO, [
        Section("Top level", "", Case),
        Section("[geometry], type = \"rectangular\"", "Dimensions before the quench (the part as `reference_state` "
                "says), in mm.", RectangularGeometry),
        Section("[geometry], type = \"spherical_outer\"", "", SphericalOuterGeometry),
        Section("[geometry], type = \"profile\"", "Segment names label the surfaces for HTC tables and the mesh "
                "(`quenchsim mesh CASE --png mesh.png` shows them).", ProfileGeometry),
        Section("[[geometry.segments]]", "", ProfileSegment),
        Section("[mesh]", "`quenchsim run --mesh-size MM` sets the core size (the surface size in proportion). "
                "`run`, `mesh` and `sweep` refuse sizes whose mesh is estimated above 100,000 triangles unless "
                "`--force`.", Mesh),
        Section("[process]", "", Process),
        Section("[transfer]", "", Transfer),
        Section("[quench]", "", Quench),
        Section("[quench.bath]", "The bath model (quenchsim/bath/__init__.py explains what each key does).",
                BathTable),
        Section("[quench.bath.nozzles.NAME]", "A nozzle row of the case, or a row of a layout file "
                "(`materials/baths/NAME.toml`, `kind = \"nozzle_layout\"`); a number may be given as "
                "`{ value, range, source }`.", NozzleRowTable),
        Section("[quench.htc_table], [air.htc_table], [temper.htc_table]", "", HtcTable),
        Section("[air]", "", Air),
        Section("[temper]", "Optional: a temper after the air stage (docs/guide/temper.md). Without this table a "
                "case resolves and runs as before.", Temper),
        Section("[time]", "", TimeControl),
        Section("[output]", "", Output),
        Section("[mechanics]", "`austenitizing_T_C` is refused here: the stress-free temperature is "
                "`process.austenitising_temperature_C`, the case's one austenitising temperature.",
                MechanicsOptions),
        Section("[[probes]]", "", Probe),
    ])


DATA_INTRO = """
Every key of the data files a case reads: a steel (`materials/NAME.toml`), its mechanics file (`NAME.mechanics.toml`
beside it) and tempering data, a quenchant (`materials/quenchants/NAME.toml`, by its `kind`), a bath layout or
constants file (`materials/baths/NAME.toml`). A number of a data file may be given as `{ value = ..., source = "..." }`
and, when it is uncertain, with its prior for the calibration: `range = [lo, hi]` or `range_factor = f`. A key not
listed is an error naming the file and the key; how to bring your own steel or oil:
[../guide/bring_a_steel.md](../guide/bring_a_steel.md), [../guide/bring_an_oil.md](../guide/bring_an_oil.md).
"""


def data_file_keys() -> str:
    """docs/reference/data_file_keys.md."""
    from quenchsim.inputs import quenchant, steel, steel_mechanics, tempering
    from quenchsim.inputs.bath import ConstantsFile, FlowConstants, LayoutFile

    return page("Data file keys", DATA_INTRO, [
        Section("Steel: top level", "", steel.Steel),
        Section("Steel: [composition]", "", steel.Composition),
        Section("Steel: [thermal]", "", steel.Thermal),
        Section("Steel: [latent_heat]", "", steel.LatentHeat),
        Section("Steel: [austenitisation]", "", steel.Austenitisation),
        Section("Steel: [kinetics]", "", steel.KineticsTable),
        Section("Steel: [kinetics.pearlite] / [kinetics.bainite], model = \"c_curve\"", "Every reaction also takes "
                "`source` and `T_upper_C` or `T_upper_formula`.", steel.CCurveReaction),
        Section("model = \"li1998\"", "", steel.LiReaction),
        Section("model = \"jmak_polynomial\"", "", steel.JmakPolynomialReaction),
        Section("model = \"ttt_table\"", "", steel.TttTableReaction),
        Section("Steel: [kinetics.martensite]", "", steel.Martensite),
        Section("Steel: [hardness.PHASE]", "One table per phase: austenite, pearlite, bainite, martensite.",
                steel.PhaseHardness),
        Section("Mechanics file: top level", "", steel_mechanics.SteelMechanics),
        Section("Mechanics: [reference]", "", steel_mechanics.Reference),
        Section("Mechanics: [elastic]", "", steel_mechanics.Elastic),
        Section("Mechanics: [free_strain], form = \"specific_volume\"", "", steel_mechanics.SpecificVolumeStrain),
        Section("Mechanics: [free_strain.volume_change_pct]", "", steel_mechanics.VolumeChanges),
        Section("Mechanics: [free_strain], form = \"expansion\"", "", steel_mechanics.ExpansionStrain),
        Section("Mechanics: [annealed]", "", steel_mechanics.Annealed),
        Section("Mechanics: [plastic]", "", steel_mechanics.Plastic),
        Section("Mechanics: [trip]", "", steel_mechanics.Trip),
        Section("Tempering data: top level", "", tempering.TemperingData),
        Section("Tempering: [clock]", "", tempering.Clock),
        Section("Tempering: [hardness]", "", tempering.TemperHardness),
        Section("Tempering: [reactions.NAME]", "", tempering.TemperReaction),
        Section("Quenchant, kind = \"liquid\"", "", quenchant.LiquidQuenchant),
        Section("Liquid: [liquid]", "", quenchant.LiquidProperties),
        Section("Liquid: [boiling]", "", quenchant.BoilingProperties),
        Section("Quenchant, kind = \"still_bath_curve\"", "", quenchant.StillBathCurve),
        Section("Still-bath curve: [test]", "", quenchant.ProbeTest),
        Section("Still-bath curve: [htc]", "", quenchant.CurveTable),
        Section("Quenchant, kind = \"gas\"", "", quenchant.GasQuenchant),
        Section("Gas: [gas]", "", quenchant.GasTable),
        Section("Bath layout, kind = \"nozzle_layout\"", "Its rows take the keys of a case's "
                "[quench.bath.nozzles.NAME] (case_keys.md).", LayoutFile),
        Section("Bath constants, kind = \"bath_constants\"", "", ConstantsFile),
        Section("Bath constants: [flow]", "", FlowConstants),
    ])


REFERENCES = {"docs/reference/case_keys.md": case_keys, "docs/reference/data_file_keys.md": data_file_keys}
"""Each generated reference file (relative to the repository) and the function that writes it."""

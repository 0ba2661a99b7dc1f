"""File names of a run folder (the output contract of ``quenchsim run``, see README "What a run writes")."""

CASE_TOML = "case.toml"
"""The fully resolved inputs (defaults, condition and overrides merged)."""
MESH_MSH = "mesh.msh"
"""The gmsh mesh of the section (named physical groups per surface segment)."""
SERIES_NAME = "results"
"""Stem of the VTK time series: ``results.pvd`` indexing ``results_NNNN.vtu``."""
SERIES_PVD = f"{SERIES_NAME}.pvd"
FINAL_3D_VTU = "final_3d.vtu"
"""A 270-degree revolved sector of the final state, for ParaView."""
PROBES_CSV = "probes.csv"
"""``time_s`` and one temperature column ``<probe>_C`` per probe, one row per time step."""
HARDNESS_TRAVERSE_CSV = "hardness_traverse.csv"
"""HRC from the bore and from the OD at mid-width: ``depth_mm,HRC_from_bore,HRC_from_od``."""
RESIDUAL_TRAVERSE_CSV = "residual_hoop_traverse.csv"
"""Hoop and axial residual stress across the wall at mid-width: ``r_mm,hoop_MPa,axial_MPa``."""
OUTLINE_CSV = "outline.csv"
"""The section outline before and after: ``r_before_mm,z_before_mm,r_after_mm,z_after_mm``."""
TEMPERED_PREFIX = "tempered_"
"""A run with a ``[temper]`` writes the hardness, residual-stress and outline files twice: as quenched (the names
above) and after the temper (this prefix before each name)."""
SUMMARY_JSON = "summary.json"
"""Machine-readable results and the run's status (``ok`` / ``hot`` / ``failed`` / ``interrupted``)."""
FINISHED_STATUSES = ("ok", "hot")
"""The statuses of a run that went through all its stages: ``ok``, the part cooled to ``air.until_max_C`` and was
closed at room temperature; ``hot``, the stages ended with the part hotter than that (every result is that of the
hot part). ``failed`` and ``interrupted`` runs stopped before the end."""
CHECKPOINT_NPZ = "checkpoint.npz"
"""The whole state of an unfinished run (stage ends, every ``output.checkpoint_minutes``, on SIGTERM/Ctrl-C), from
which ``quenchsim run ... --resume`` continues; removed when the run completes."""

RUN_OUTPUTS = (SERIES_PVD, f"{SERIES_NAME}_*.vtu", FINAL_3D_VTU, PROBES_CSV, HARDNESS_TRAVERSE_CSV,
               RESIDUAL_TRAVERSE_CSV, OUTLINE_CSV, SUMMARY_JSON, SUMMARY_JSON + ".tmp", MESH_MSH,
               f"{TEMPERED_PREFIX}*.csv")
"""What a run writes (glob patterns) that a new run into the same folder replaces: cleared when it starts, so no
frame or summary of an earlier run is left beside its own (case.toml is rewritten; ``uncertainty/`` is a cache)."""
RUN_MARKERS = (CASE_TOML, SUMMARY_JSON, CHECKPOINT_NPZ, SERIES_PVD)
"""A folder holding one of these is a quenchsim run folder (case.toml is the first file a run writes)."""


def run_status(summary: dict | None) -> str:
    """The status of a run from its summary, told as it is: ``hot`` for a summary written before that status existed
    whose part was still hot at the end (status ``ok`` with ``end_state.at_room_temperature`` false)."""
    if not summary:
        return "no summary.json"
    status = str(summary.get("status", "unknown"))
    if status == "ok" and summary.get("end_state", {}).get("at_room_temperature") is False:
        return "hot"
    return status


def status_warning(summary: dict | None) -> str | None:
    """One sentence saying why a run's results are not those of the finished, cooled part (None when they are)."""
    status = run_status(summary)
    if status == "ok" or summary is None:
        return None
    end = summary.get("end_state", {})
    if status == "hot":
        hottest, at = end.get("max_temperature_C", float("nan")), end.get("time_s", float("nan"))
        return (f"the part is still hot at the end of the run (up to {hottest:.0f} C at t = {at:.0f} s): "
                "temperatures, phases, hardness, dimensions and stresses are those of the hot part, not of the "
                "cooled one (lengthen air.time_s)")
    at = summary.get("stopped_at_s")
    when = f" at t = {at:.4g} s" if isinstance(at, (int, float)) else ""
    return (f"the run did not finish (status {status}{when}): every result is the state where it stopped, not that "
            "of the quenched and cooled part")

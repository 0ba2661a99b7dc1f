"""CLI verbs of the bearing modules (`quenchsim bearings VERB`).

Each module here defines ``configure(parser)`` (adds its arguments) and ``run(args) -> dict``
(returns one JSON-serialisable object). The physics lives in the bearing packages; these files
only parse arguments and call them.
"""

VERBS: dict[str, str] = {
    "gas-journal": "quenchsim.bearings.commands.gas_journal",
    "runout": "quenchsim.bearings.commands.runout",
    "grease-life": "quenchsim.bearings.commands.grease_life",
    "kinematics": "quenchsim.bearings.commands.kinematics",
    "hertz": "quenchsim.bearings.commands.hertz",
    "roller-clutch": "quenchsim.bearings.commands.roller_clutch",
    "mode2": "quenchsim.bearings.commands.mode2",
    "encoder": "quenchsim.bearings.commands.encoder",
    "free-run": "quenchsim.bearings.commands.free_run",
    "big-end": "quenchsim.bearings.commands.big_end",
    "doj": "quenchsim.bearings.commands.doj",
}

"""Fitters that turn the data heat treaters have into quenchsim material and quenchant files.

They sit above the physics packages (they drive the metallurgy and thermal solvers the simulation
uses) and below the CLI: ``quenchsim material fit`` (CCT / TTT / Jominy data -> steel kinetics) and
``quenchsim quenchant fit`` (ISO 9950 probe curve -> HTC of the surface temperature). Import the
submodules directly.
"""

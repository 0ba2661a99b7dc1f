"""Writers of run outputs: VTK/PVD time series (meshio), probe CSV, checkpoints."""

from quenchsim.io.series import ProbeWriter, VtkSeries

__all__ = ["ProbeWriter", "VtkSeries"]

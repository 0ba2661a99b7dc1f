"""`quenchsim view RUN_DIR --field hardness_HRC --png out.png [--3d]`: off-screen render of the final state.

For people without ParaView: the last frame of ``results.pvd`` drawn with pyvista, either as the r-z
section (default) or revolved into a 3-D sector (``--3d``; ``quenchsim.io.revolve``). Rendering needs
an OpenGL implementation: VTK's wheels find Mesa's EGL (Debian: libegl1 libegl-mesa0 libgl1-mesa-dri)
or an X server.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("run_dir", type=Path, help="a run directory (quenchsim run)")
    parser.add_argument("--field", default="hardness_HRC", help="point-data field to colour by (default hardness_HRC)")
    parser.add_argument("--png", type=Path, help="image to write (default RUN_DIR/<field>.png or <field>_3d.png)")
    parser.add_argument("--3d", dest="three_d", action="store_true", help="revolve the section into a 3-D sector")
    parser.add_argument("--angle", type=float, default=270.0, help="sector angle of --3d in degrees (default 270)")
    parser.add_argument("--warp", type=float, default=0.0,
                        help="draw the shape displaced by displacement_m times this factor (e.g. 10)")
    parser.add_argument("--size", type=int, nargs=2, default=[1000, 800], metavar=("W", "H"), help="image size, px")


def prefer_egl_without_display() -> None:
    """Without an X display, ask VTK for its EGL render window first: it tried X first, printed a 'bad X server
    connection' warning, then rendered through EGL anyway (VTK >= 9.4 reads VTK_DEFAULT_OPENGL_WINDOW; a user's own
    setting is kept, and nothing is set where no EGL library is found)."""
    import ctypes.util

    if (sys.platform.startswith("linux") and not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY")
            and ctypes.util.find_library("EGL")):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def run(args: argparse.Namespace) -> int:
    prefer_egl_without_display()
    import numpy as np
    import pyvista

    from quenchsim.errors import InputError
    from quenchsim.io.revolve import revolve_mesh
    from quenchsim.results import last_frame, load_frame

    pyvista.OFF_SCREEN = True
    frame_path = last_frame(args.run_dir) if args.run_dir.is_dir() else None
    if frame_path is None:
        raise InputError("RUN_DIR", str(args.run_dir), "has no results.pvd / results_*.vtu frame")
    frame = load_frame(frame_path)
    if args.field not in frame.point_data:
        raise InputError("--field", args.field, f"not in {frame_path.name}; available: {', '.join(frame.point_data)}")
    if args.warp and "displacement_m" not in frame.point_data:
        raise InputError("--warp", args.warp, f"{frame_path.name} has no displacement_m (a run without mechanics)")
    if args.three_d:
        mesh = pyvista.from_meshio(revolve_mesh(frame.points, frame.triangles, frame.point_data, args.angle,
                                                max(8, int(round(args.angle / 5.0)))))
    else:
        cells = np.hstack([np.full((len(frame.triangles), 1), 3), frame.triangles]).ravel()
        mesh = pyvista.UnstructuredGrid(cells, np.full(len(frame.triangles), pyvista.CellType.TRIANGLE),
                                        frame.points)
        for name, values in frame.point_data.items():
            mesh.point_data[name] = values
    if args.warp:
        mesh = mesh.warp_by_vector("displacement_m", factor=args.warp)
    png = args.png or args.run_dir / f"{args.field}{'_3d' if args.three_d else ''}.png"
    png.parent.mkdir(parents=True, exist_ok=True)
    plotter = pyvista.Plotter(off_screen=True, window_size=list(args.size))
    plotter.set_background("white")  # type: ignore[arg-type]  # pyvista's decorator stub drops self
    title = f"{args.field}, {frame_path.name}" + (f", displacement x{args.warp:g}" if args.warp else "")
    plotter.add_mesh(mesh, scalars=args.field, cmap="inferno" if "hardness" in args.field else "viridis",
                     scalar_bar_args={"title": args.field, "color": "black"})
    plotter.add_text(title, font_size=10, color="black")
    if args.three_d:
        plotter.view_isometric()  # type: ignore[call-arg]  # pyvista's decorator stub drops self
    else:
        plotter.view_xy()  # type: ignore[call-arg]  # pyvista's decorator stub drops self
    plotter.screenshot(str(png))
    plotter.close()
    print(png)
    return 0

"""The element-count check of the commands that mesh a case (``run``, ``mesh``, ``sweep``): a case whose element sizes
would make an absurd mesh (``--mesh-size 0.05``, ``--set mesh.surface_size_mm=0.01``) is refused before any work, in
one line with the estimated count, unless ``--force``. The count is estimated without meshing
(:func:`quenchsim.geometry.mesher.estimated_triangles`); meshing it would itself take minutes."""

from __future__ import annotations

import sys
from typing import Any

from quenchsim.errors import InputError

MAX_TRIANGLES = 100_000
"""Largest estimated triangle count meshed without ``--force``: about 40 times ring A's reference mesh (2,300
triangles, ~20 s of CPU, a 40-60 s run on two cores). Measured on ring A condition 1 with ``--mesh-size 2`` (12,480
triangles): 145 s of CPU, so the CPU time grows a little faster than the count and a run at the limit takes half an
hour of CPU or more -- a size typed in the wrong unit, or a convergence check that asks for ``--force``."""


def refuse_large_mesh(case: Any, force: bool) -> int:
    """The estimated triangle count of ``case``'s mesh (a :class:`quenchsim.case.Case`); above
    :data:`MAX_TRIANGLES` an :class:`InputError` unless ``force`` (then a note on stderr)."""
    from quenchsim.geometry.mesher import estimated_triangles
    from quenchsim.geometry.profile import MM

    m = case.mesh
    count = estimated_triangles(case.profile, m.size_mm * MM, m.surface_size_mm * MM, m.surface_layer_mm * MM)
    if count > MAX_TRIANGLES:
        sizes = f"size_mm {m.size_mm:g}, surface_size_mm {m.surface_size_mm:g}"
        if not force:
            raise InputError("mesh", sizes, f"about {count:,} triangles, above the {MAX_TRIANGLES:,} meshed without "
                                            "--force (ring A's reference mesh has 2,300, a run of about a minute): "
                                            "coarser sizes, or --force to go ahead")
        print(f"quenchsim: note: mesh ({sizes}): about {count:,} triangles (--force)", file=sys.stderr)
    return count

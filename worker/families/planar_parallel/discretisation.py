"""The fixed discretisation of the planar2dof jobs, reported in each result's
``discretisation`` and priced by :mod:`worker.families.planar_parallel.costs`.

Plain constants: importing this module loads nothing heavy.
"""

from __future__ import annotations

__all__ = [
    "BOUNDARY_COLUMNS",
    "BOUNDARY_ROWS",
    "FIG9_MESH",
    "MAP_POINTS_PER_AXIS",
    "MAX_CHUNK_MESH_POINTS",
    "RECTANGLE_BOUNDARY_SAMPLES",
    "RECTANGLE_COLUMNS",
    "RECTANGLE_ROWS",
    "S_MAX_MESH",
]

#: W_kappa0's boundary: columns over its x span, scan rows per column (then refined).
BOUNDARY_COLUMNS = 801
BOUNDARY_ROWS = 321
#: The rectangle search of one delta: columns over [0, X], scan rows, check points per edge.
RECTANGLE_COLUMNS = 257
RECTANGLE_ROWS = 160
RECTANGLE_BOUNDARY_SAMPLES = 256
#: Nodes per side of the mesh used for S_max alone (its means are not used).
S_MAX_MESH = 2
#: Mesh points evaluated at once in a sweep (deltas per chunk = this / mean_mesh²).
MAX_CHUNK_MESH_POINTS = 4_000_000
#: Nodes per side of the Fig. 9 mesh over W_lambda.
FIG9_MESH = 201
#: Grid nodes per axis of the 1/kappa map behind the rectangle (Fig. 6).
MAP_POINTS_PER_AXIS = 301

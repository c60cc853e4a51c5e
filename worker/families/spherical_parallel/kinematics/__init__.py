"""Spherical parallel manipulators (3-RRR / coaxial 3-RRS): kinematics, conditioning,
design space and optimum design for a prescribed workspace.

S. Bai, "Optimum design of spherical parallel manipulators for a prescribed workspace",
Mech. Mach. Theory 45 (2010) 200-211, restated in docs/methods/spherical-parallel.md, which wins
where the two disagree (the paper's formulas are garbled by text extraction; its printed "C_n" is
mean(1/kappa^2), eq 28, not the root mean square of eq 25).

Conventions: every angle is in RADIANS (degrees belong to the job layer); legs
i = 1, 2, 3 at eta_i = 2 (i - 1) pi / 3; orientations psi = (psi1, psi2, psi3) with
Q = rot(e_psi, psi2) rot(e3, psi3) (eq 2); ``branch`` is the sign kept by
(u_i x w_i) . v_i (eq 29: -1). Functions are batched on leading axes and return arrays
for them, never scalars; a pose without a real inverse kinematics solution, or a start
that did not converge, is data, not an exception. Bad arguments raise ValueError
("The 'x' parameter of f must be ... Got ... instead.").

This module is the one to import; the work is done in:

* :mod:`~.model` — :class:`SpmDesign`, :class:`Workspace`;
* :mod:`~.sampling` — default and dense samples;
* :mod:`~.legs` — axes, inverse kinematics (eqs 11-12),
  Jacobian (eq 9), kappa (eqs 21-22);
* :mod:`~.indices` — indices over samples (eqs 24, 25, 28),
  vectorised, and the least 1/kappa on the closed workspace;
* :mod:`~.design_space` — design space (eqs 14-19) on the continuous
  workspace, numerically for limited torsion in :mod:`~.axis_reach`;
* :mod:`~.optimisation` — least squares (eqs 28-30) over
  :mod:`~.parametrisation` (variables <-> feasible designs),
  with its argument checks in :mod:`~.optimisation_inputs`;
* :mod:`~.twins` — designs scoring exactly the same;
* :mod:`~.reference` — the per-orientation loop (tests, bench).
"""

from __future__ import annotations

from worker.families.spherical_parallel.kinematics.design_space import (
    EDGE_TOLERANCE as EDGE_TOLERANCE,
)
from worker.families.spherical_parallel.kinematics.design_space import DesignSpace as DesignSpace
from worker.families.spherical_parallel.kinematics.design_space import (
    design_margins as design_margins,
)
from worker.families.spherical_parallel.kinematics.design_space import design_space as design_space
from worker.families.spherical_parallel.kinematics.design_space import (
    design_widths as design_widths,
)
from worker.families.spherical_parallel.kinematics.design_space import is_feasible as is_feasible
from worker.families.spherical_parallel.kinematics.design_space import link_angles as link_angles
from worker.families.spherical_parallel.kinematics.indices import Indices as Indices
from worker.families.spherical_parallel.kinematics.indices import SampleSet as SampleSet
from worker.families.spherical_parallel.kinematics.indices import (
    WorkspaceMinimum as WorkspaceMinimum,
)
from worker.families.spherical_parallel.kinematics.indices import (
    workspace_indices as workspace_indices,
)
from worker.families.spherical_parallel.kinematics.indices import (
    workspace_minimum as workspace_minimum,
)
from worker.families.spherical_parallel.kinematics.legs import condition_number as condition_number
from worker.families.spherical_parallel.kinematics.legs import (
    inverse_condition_number as inverse_condition_number,
)
from worker.families.spherical_parallel.kinematics.legs import (
    inverse_kinematics as inverse_kinematics,
)
from worker.families.spherical_parallel.kinematics.legs import jacobian as jacobian
from worker.families.spherical_parallel.kinematics.legs import rotation as rotation
from worker.families.spherical_parallel.kinematics.legs import unit_vectors as unit_vectors
from worker.families.spherical_parallel.kinematics.model import SpmDesign as SpmDesign
from worker.families.spherical_parallel.kinematics.model import Workspace as Workspace
from worker.families.spherical_parallel.kinematics.optimisation import (
    OptimisationResult as OptimisationResult,
)
from worker.families.spherical_parallel.kinematics.optimisation import StartOutcome as StartOutcome
from worker.families.spherical_parallel.kinematics.optimisation import optimise as optimise
from worker.families.spherical_parallel.kinematics.optimisation_inputs import (
    DEFAULT_BOUNDS as DEFAULT_BOUNDS,
)
from worker.families.spherical_parallel.kinematics.optimisation_inputs import (
    PARAMETERS as PARAMETERS,
)
from worker.families.spherical_parallel.kinematics.reference import (
    per_orientation_reference as per_orientation_reference,
)
from worker.families.spherical_parallel.kinematics.sampling import DEFAULT_COUNTS as DEFAULT_COUNTS
from worker.families.spherical_parallel.kinematics.sampling import SampleLayout as SampleLayout
from worker.families.spherical_parallel.kinematics.sampling import boundary_grid as boundary_grid
from worker.families.spherical_parallel.kinematics.sampling import (
    orientation_samples as orientation_samples,
)
from worker.families.spherical_parallel.kinematics.twins import TwinDesign as TwinDesign
from worker.families.spherical_parallel.kinematics.twins import twin_designs as twin_designs

__all__ = [
    "DEFAULT_BOUNDS",
    "DEFAULT_COUNTS",
    "EDGE_TOLERANCE",
    "PARAMETERS",
    "DesignSpace",
    "Indices",
    "OptimisationResult",
    "SampleLayout",
    "SampleSet",
    "SpmDesign",
    "StartOutcome",
    "TwinDesign",
    "Workspace",
    "WorkspaceMinimum",
    "boundary_grid",
    "condition_number",
    "design_margins",
    "design_space",
    "design_widths",
    "inverse_condition_number",
    "inverse_kinematics",
    "is_feasible",
    "jacobian",
    "link_angles",
    "optimise",
    "orientation_samples",
    "per_orientation_reference",
    "rotation",
    "twin_designs",
    "unit_vectors",
    "workspace_indices",
    "workspace_minimum",
]

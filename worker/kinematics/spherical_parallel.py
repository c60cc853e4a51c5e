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

* :mod:`~worker.kinematics.spherical_model` — :class:`SpmDesign`, :class:`Workspace`;
* :mod:`~worker.kinematics.spherical_workspace` — default and dense samples;
* :mod:`~worker.kinematics.spherical_kinematics` — axes, inverse kinematics (eqs 11-12),
  Jacobian (eq 9), kappa (eqs 21-22);
* :mod:`~worker.kinematics.spherical_indices` — indices over samples (eqs 24, 25, 28),
  vectorised, and the least 1/kappa on the closed workspace;
* :mod:`~worker.kinematics.spherical_design` — design space (eqs 14-19) on the continuous
  workspace, numerically for limited torsion in :mod:`~worker.kinematics.spherical_axis_reach`;
* :mod:`~worker.kinematics.spherical_optimisation` — least squares (eqs 28-30) over
  :mod:`~worker.kinematics.spherical_parametrisation` (variables <-> feasible designs),
  with its argument checks in :mod:`~worker.kinematics.spherical_optimisation_inputs`;
* :mod:`~worker.kinematics.spherical_twins` — designs scoring exactly the same;
* :mod:`~worker.kinematics.spherical_reference` — the per-orientation loop (tests, bench).
"""

from __future__ import annotations

from worker.kinematics.spherical_design import EDGE_TOLERANCE as EDGE_TOLERANCE
from worker.kinematics.spherical_design import DesignSpace as DesignSpace
from worker.kinematics.spherical_design import design_margins as design_margins
from worker.kinematics.spherical_design import design_space as design_space
from worker.kinematics.spherical_design import design_widths as design_widths
from worker.kinematics.spherical_design import is_feasible as is_feasible
from worker.kinematics.spherical_design import link_angles as link_angles
from worker.kinematics.spherical_indices import Indices as Indices
from worker.kinematics.spherical_indices import SampleSet as SampleSet
from worker.kinematics.spherical_indices import WorkspaceMinimum as WorkspaceMinimum
from worker.kinematics.spherical_indices import workspace_indices as workspace_indices
from worker.kinematics.spherical_indices import workspace_minimum as workspace_minimum
from worker.kinematics.spherical_kinematics import condition_number as condition_number
from worker.kinematics.spherical_kinematics import (
    inverse_condition_number as inverse_condition_number,
)
from worker.kinematics.spherical_kinematics import inverse_kinematics as inverse_kinematics
from worker.kinematics.spherical_kinematics import jacobian as jacobian
from worker.kinematics.spherical_kinematics import rotation as rotation
from worker.kinematics.spherical_kinematics import unit_vectors as unit_vectors
from worker.kinematics.spherical_model import SpmDesign as SpmDesign
from worker.kinematics.spherical_model import Workspace as Workspace
from worker.kinematics.spherical_optimisation import OptimisationResult as OptimisationResult
from worker.kinematics.spherical_optimisation import StartOutcome as StartOutcome
from worker.kinematics.spherical_optimisation import optimise as optimise
from worker.kinematics.spherical_optimisation_inputs import DEFAULT_BOUNDS as DEFAULT_BOUNDS
from worker.kinematics.spherical_optimisation_inputs import PARAMETERS as PARAMETERS
from worker.kinematics.spherical_reference import (
    per_orientation_reference as per_orientation_reference,
)
from worker.kinematics.spherical_twins import TwinDesign as TwinDesign
from worker.kinematics.spherical_twins import twin_designs as twin_designs
from worker.kinematics.spherical_workspace import DEFAULT_COUNTS as DEFAULT_COUNTS
from worker.kinematics.spherical_workspace import SampleLayout as SampleLayout
from worker.kinematics.spherical_workspace import boundary_grid as boundary_grid
from worker.kinematics.spherical_workspace import orientation_samples as orientation_samples

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

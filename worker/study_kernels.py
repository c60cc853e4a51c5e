"""Study kernels: how a family evaluates one of its processes over many designs at once.

A design study (:mod:`worker.studies`) can run the whole single-design process once per
design (the per-design engine, the reference), or hand blocks of designs to the
process's **study kernel** (the batched engine): pure numpy arithmetic over arrays with
one row per design, for the few numbers a study reads.  A family declares the kernel
on its process (``ProcessDefinition(study_kernel=StudyKernel(...))``); the study uses it
when every objective is a path the kernel covers and every varied input one it can
vary, and the per-design engine otherwise.  Both engines agree: a design is feasible in
one exactly when it is in the other, and its objectives are equal to 1e-12 relative.

**What a family writes** (a kernel for ``planar3r-dexterity-map`` follows the same
steps as ``worker/families/spherical_parallel/study.py``):

1. ``covers``: the declared result paths (as in the process's ``result_paths``:
   ``indices.gci``, ``task_points[].d_z``, ``links[]``) whose numbers the kernel
   computes; a reduction (``|min``, ``|max``, ``|mean``, ``|sum``) or an index of a
   covered list path is covered with it, and ``describe()`` publishes
   ``"kernel": true`` on these entries.
2. ``varies``: the input paths it can vary per design, as patterns (``[]`` any list
   index, ``*`` any key: ``alpha1_deg``, ``links[]``, ``chains[].lengths[]``), each with
   a **reference value** inside the input's own range (``90.0`` for an angle).  Varying
   anything else (a sample count, a ``method``) makes the study per-design.
3. **The template.**  The study validates the fixed inputs once, with the reference
   values at the varied paths, by the process's own model and schema, with the
   validation context ``{STUDY_TEMPLATE: True}`` (:func:`in_study_template`): every
   validator whose outcome depends on a vectorisable input skips then (a reach check,
   a closure check, a ratio of lengths), because the kernel makes that check per
   design.  Vectorisable inputs must not change the process's cost (the template's
   cost is every design's).
4. ``prepare(request)`` turns the validated template, the varied paths and the wanted
   declared paths into a :class:`KernelPlan`: ``cost`` (one design's work in the
   process's own cost unit, for the study's price and its chunking) and
   ``evaluate(values)``.
5. ``evaluate(values)`` takes designs ``(m, d)`` (columns in the order of
   ``request.varied``) and returns a :class:`KernelBlock`: per wanted path an array
   ``(m, *L)``, one axis per ``[]`` of the path (a list has the same length in every
   design; NaN where the process reports null or nothing), and per design the refusal
   the process's validation would make (``refused`` indexes ``refusals``: where the
   process locates its first error, and a message), -1 for a design it accepts.  Only
   refusals that depend on the varied values are the kernel's: the study refuses
   nothing else per design (the template validated the rest; a cost above the
   process's limit is the study's).  A kernel may skip a refusal check whose outcome
   cannot change feasibility (a design that closes at no sample is infeasible whether
   refused or not): its tests must prove each such shortcut.  It tiles its work so that
   temporaries stay bounded, and never raises for a design.
6. ``seconds_per_cost``: measured seconds per unit of ``plan.cost`` for one design (on
   the reference machine), so a study cuts its designs into chunks of about a second
   from its inputs alone: a re-run splits the same way.

Where the process finds a quantity by iteration (a root, a minimum), its single-design
job should call the kernel's own code, so that the two agree to the last bit.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "STUDY_TEMPLATE",
    "KernelBlock",
    "KernelPlan",
    "KernelRequest",
    "Refusal",
    "StudyKernel",
    "in_study_template",
]

#: The validation context key under which a study validates a kernel's template.
STUDY_TEMPLATE = "dexlab_study_template"


def in_study_template(context: Any) -> bool:
    """Whether a validator runs on a study kernel's template (``info.context``): then a
    check that depends on a vectorisable input is the kernel's, per design."""
    return isinstance(context, Mapping) and bool(context.get(STUDY_TEMPLATE))


@dataclass(frozen=True)
class Refusal:
    """Why the process refuses a design: where its validation locates the first error
    (pydantic's location in the inputs, tags of tagged unions included:
    ``("alpha1_deg",)``, ``("chains", 3, "loops", 0)``; a 422 shows it as
    ``inputs.chains[3].loops[0]``) and a message."""

    loc: tuple[str | int, ...]
    message: str


@dataclass(frozen=True)
class KernelBlock:
    """A kernel's answer for ``m`` designs.

    ``values``: per wanted declared path, an array ``(m, *L)`` (one axis per ``[]``),
    NaN where the process reports null or no number; ``refused`` ``(m,)`` integers, -1
    where the process accepts the design, else an index into ``refusals``.
    """

    values: Mapping[str, NDArray[np.float64]]
    refused: NDArray[np.intp]
    refusals: tuple[Refusal, ...] = ()


class KernelPlan(Protocol):
    """A kernel ready for one study's designs (see the module doc)."""

    @property
    def cost(self) -> float:
        """One design's work, in the process's own cost unit."""

    def evaluate(self, values: NDArray[np.float64]) -> KernelBlock:
        """Designs ``(m, d)`` (the varied inputs, in ``request.varied`` order) in."""


@dataclass(frozen=True)
class KernelRequest:
    """What a kernel is prepared for: the process's validated template inputs, the
    varied input paths (parsed: ``("chains", 3, "lengths", 2)``) in column order, and
    the declared result paths the study reads."""

    template: Any
    varied: tuple[tuple[str | int, ...], ...]
    wanted: frozenset[str]


@dataclass(frozen=True)
class StudyKernel:
    """A process's batched evaluation for design studies (see the module doc).

    ``covers``: declared result paths; ``varies``: input path pattern -> reference
    value; ``prepare``: a request in, a plan out; ``seconds_per_cost``: seconds per
    unit of ``plan.cost``; ``description``: a sentence for the docs and the pages.
    """

    covers: tuple[str, ...]
    varies: Mapping[str, float]
    prepare: Callable[[KernelRequest], KernelPlan]
    seconds_per_cost: float
    description: str = ""

"""``fourbar-grashof`` over many sets of lengths (:mod:`worker.families.chains.study`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from worker.common.numeric_ranges import MAX_LENGTH, MAX_LENGTH_RATIO, MIN_LENGTH
from worker.families.chains.kinematics.study_kernel import (
    four_bar_cannot_close,
    four_bar_criteria,
    spread_too_far,
)
from worker.study_kernels import KernelBlock, KernelRequest, Refusal

if TYPE_CHECKING:
    from worker.families.chains.fourbar_spec import FourBarGrashofSpec

__all__ = ["FOURBAR_KERNEL_COST", "FourBarPlan", "range_refusals"]

FloatArray = NDArray[np.float64]
#: A batched four-bar's price in the process's cost unit (one four-bar, a job's whole
#: cost, which pays for its figure: about 0.1 s): about 4 µs of work, so a thousandth is
#: generous.
FOURBAR_KERNEL_COST = 1e-3
#: pydantic's words for a length outside [MIN_LENGTH, MAX_LENGTH].
TOO_SHORT = f"Input should be greater than or equal to {MIN_LENGTH:f}".rstrip("0")
TOO_LONG = f"Input should be less than or equal to {MAX_LENGTH:.0f}"


def range_refusals(
    values: FloatArray,
    locs: list[tuple[str | int, ...]],
    refused: NDArray[np.intp],
    refusals: list[Refusal],
) -> None:
    """Refuse, in ``refused``, each design's first value (columns in the inputs' order)
    outside the lengths' range, as pydantic words it; ``refusals`` grows."""
    for column, loc in enumerate(locs):
        for bad, message in ((values[:, column] < MIN_LENGTH, TOO_SHORT),
                             (values[:, column] > MAX_LENGTH, TOO_LONG)):  # fmt: skip
            hit = bad & (refused < 0)
            if hit.any():
                refused[hit] = len(refusals)
                refusals.append(Refusal(loc, message))


@dataclass(frozen=True, eq=False)
class FourBarPlan:
    """One study of four-bars: the template's lengths and ground, the varied links."""

    template: FourBarGrashofSpec
    columns: dict[int, int]  # link -> column of the designs
    wanted: frozenset[str]

    @classmethod
    def of(cls, request: KernelRequest) -> FourBarPlan:
        columns = {int(path[1]): j for j, path in enumerate(request.varied)}
        return cls(request.template, columns, request.wanted)

    @property
    def cost(self) -> float:
        return FOURBAR_KERNEL_COST

    def evaluate(self, values: FloatArray) -> KernelBlock:
        m = len(values)
        lengths = np.tile(np.asarray(self.template.lengths, dtype=np.float64), (m, 1))
        for link, column in self.columns.items():
            lengths[:, link] = values[:, column]
        refused = np.full(m, -1, dtype=np.intp)
        refusals: list[Refusal] = []
        links = sorted(self.columns)
        range_refusals(lengths[:, links], [("lengths", k) for k in links], refused, refusals)
        spread = spread_too_far(lengths, MAX_LENGTH_RATIO) & (refused < 0)
        if spread.any():
            refused[spread] = len(refusals)
            refusals.append(Refusal(("lengths",), "the longest length is more than "
                                    f"{MAX_LENGTH_RATIO:g} times the shortest"))  # fmt: skip
        open_, longest = four_bar_cannot_close(lengths)
        for link in range(4):
            hit = open_ & (longest == link) & (refused < 0)
            if hit.any():
                refused[hit] = len(refusals)
                refusals.append(Refusal(("lengths", link), f"the loop cannot close: link "
                                        f"{link} is not shorter than the other three"))  # fmt: skip
        return KernelBlock(self._values(lengths), refused, tuple(refusals))

    def _values(self, lengths: FloatArray) -> dict[str, FloatArray]:
        m = len(lengths)
        criteria = four_bar_criteria(lengths)
        found = {
            "lengths[]": lengths,
            "links[].length": lengths,
            "links[].index": np.tile(np.arange(4, dtype=np.float64), (m, 1)),
            "ground": np.full(m, float(self.template.ground)),
            "criterion.shortest": criteria.shortest.astype(np.float64),
            "criterion.longest": criteria.longest.astype(np.float64),
            "criterion.s_plus_l": criteria.s_plus_l,
            "criterion.p_plus_q": criteria.p_plus_q,
            "criterion.margin": criteria.margin,
        }
        return {path: found[path] for path in self.wanted}

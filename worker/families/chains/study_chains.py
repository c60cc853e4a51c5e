"""``chain-parallelism`` over many sets of lengths (:mod:`worker.families.chains.study`).

Each chain's structure comes from the template (a design changes lengths only): its
dimensions in the order of ``ChainStructure.dimensions`` (the order of the inputs: a
loop's lengths, or the links and each polygon's sides as given), where pydantic
locates an error in each, its polygons' and loops' sides as indices into them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from worker.common.numeric_ranges import MAX_LENGTH_RATIO
from worker.families.chains import kinematics as chains
from worker.families.chains.kinematics.measures import SUMS_RTOL
from worker.families.chains.kinematics.study_kernel import (
    ChainMeasures,
    cannot_close,
    chain_measures,
    ranks_of_chains,
    spread_too_far,
)
from worker.families.chains.specs import LoopChain, to_chain
from worker.families.chains.study_fourbar import range_refusals
from worker.study_kernels import KernelBlock, KernelRequest, Refusal

if TYPE_CHECKING:
    from worker.families.chains.specs import ChainParallelismSpec

__all__ = ["ChainLayout", "ChainsPlan"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.intp]
Loc = tuple[str | int, ...]


@dataclass(frozen=True)
class ChainLayout:
    """One chain of the template: its dimensions' lengths, names and error locations,
    its polygons (link name, sides) and loops (sides) as dimension indices, and its
    structure's counts."""

    index: int
    form: str  # "lengths" or "links"
    lengths: FloatArray
    names: tuple[str, ...]
    locs: tuple[Loc, ...]
    polygons: tuple[tuple[str, IntArray], ...]
    loops: tuple[IntArray, ...]
    counts: dict[str, float]

    @classmethod
    def of(cls, index: int, chain: object) -> ChainLayout:
        structure = chains.chain_structure(to_chain(chain))  # type: ignore[arg-type]
        names = tuple(side for side, _ in structure.dimensions)
        lengths = np.array([length for _, length in structure.dimensions], dtype=np.float64)
        at = {name: k for k, name in enumerate(names)}
        if isinstance(chain, LoopChain):
            form = "lengths"
            locs: tuple[Loc, ...] = tuple(
                ("chains", index, "lengths", k) for k in range(len(names))
            )
        else:
            form = "links"
            locs = tuple(
                ("chains", index, "links", *name.split(".", 1)[:1], "sides",
                 name.split(".", 1)[1]) if "." in name
                else ("chains", index, "links", name, "Length")
                for name in names
            )  # fmt: skip
        polygons = []
        for link in structure.links:
            sides = [k for k, name in enumerate(names) if name.startswith(f"{link}.")]
            if sides:
                polygons.append((link, np.array(sides, dtype=np.intp)))
        loops = tuple(np.array([at[s] for s in loop], dtype=np.intp) for loop in structure.loops)
        counts = {"links": float(len(structure.links)), "joints": float(len(structure.joints)),
                  "independent_loops": float(structure.independent_loops),
                  "mobility": float(structure.mobility)}  # fmt: skip
        return cls(index, form, lengths, names, locs, tuple(polygons), loops, counts)

    def dimension_of(self, path: Sequence[str | int]) -> int:
        """The dimension a varied path (below ``chains[i]``) names."""
        if self.form == "lengths" and len(path) == 2 and path[0] == "lengths":
            return int(path[1])
        if self.form == "links" and len(path) == 2 and path[0] == "links":
            return self.names.index(str(path[1]))
        if self.form == "links" and len(path) == 4 and path[2] == "sides":
            return self.names.index(f"{path[1]}.{path[3]}")
        raise ValueError(f"no length of chains[{self.index}] at {list(path)}")


def _refuse(hit: NDArray[np.bool_], loc: Loc, message: str,
            refused: IntArray, refusals: list[Refusal]) -> None:  # fmt: skip
    hit = hit & (refused < 0)
    if hit.any():
        refused[hit] = len(refusals)
        refusals.append(Refusal(loc, message))


@dataclass(frozen=True, eq=False)
class ChainsPlan:
    """One study of chains: each chain's layout and which dimensions are varied."""

    layouts: tuple[ChainLayout, ...]
    varied: tuple[tuple[int, int, int], ...]  # (chain, dimension, column), inputs' order
    wanted: frozenset[str]

    @classmethod
    def of(cls, request: KernelRequest) -> ChainsPlan:
        template: ChainParallelismSpec = request.template
        layouts = tuple(ChainLayout.of(i, chain) for i, chain in enumerate(template.chains))
        varied = sorted(
            (int(path[1]), layouts[int(path[1])].dimension_of(path[2:]), column)
            for column, path in enumerate(request.varied)
        )
        return cls(layouts, tuple(varied), request.wanted)

    @property
    def cost(self) -> float:
        """Links x loops per chain: the process's cost without the arrangements."""
        return float(sum(layout.counts["links"] * len(layout.loops) for layout in self.layouts))

    def evaluate(self, values: FloatArray) -> KernelBlock:
        m = len(values)
        dims = [np.tile(layout.lengths, (m, 1)) for layout in self.layouts]
        for chain, dimension, column in self.varied:
            dims[chain][:, dimension] = values[:, column]
        refused = np.full(m, -1, dtype=np.intp)
        refusals: list[Refusal] = []
        locs = [self.layouts[c].locs[d] for c, d, _ in self.varied]
        range_refusals(values[:, [col for *_, col in self.varied]], locs, refused, refusals)
        for layout, lengths in zip(self.layouts, dims, strict=True):
            self._geometry(layout, lengths, refused, refusals)
        measures = [chain_measures(lengths, layout.loops)
                    for layout, lengths in zip(self.layouts, dims, strict=True)]  # fmt: skip
        return KernelBlock(self._values(measures, m), refused, tuple(refusals))

    @staticmethod
    def _geometry(layout: ChainLayout, lengths: FloatArray, refused: IntArray,
                  refusals: list[Refusal]) -> None:  # fmt: skip
        """A chain's refusals after the ranges: the spread, its polygons, its loops."""
        i = layout.index
        spread = spread_too_far(lengths, MAX_LENGTH_RATIO)
        _refuse(spread, ("chains", i, layout.form), f"chains[{i}]: the longest length is more "
                f"than {MAX_LENGTH_RATIO:g} times the shortest", refused, refusals)  # fmt: skip
        judged = ~spread  # a chain whose lengths spread too far is not checked further
        for link, sides in layout.polygons:
            _refuse(judged & cannot_close(lengths[:, sides]), ("chains", i, "links", link),
                    f"chains[{i}].links['{link}']: link '{link}' cannot close",
                    refused, refusals)  # fmt: skip
        for k, sides in enumerate(layout.loops):
            _refuse(judged & cannot_close(lengths[:, sides]), ("chains", i, "loops", k),
                    f"chains[{i}].loops[{k}]: the loop cannot close", refused,
                    refusals)  # fmt: skip

    def _values(self, measures: list[ChainMeasures], m: int) -> dict[str, FloatArray]:
        out: dict[str, FloatArray] = {}
        if self.wanted & {"chains[].rank.by_P", "chains[].rank.by_Q"}:
            by_p, by_q, _ = ranks_of_chains(measures, SUMS_RTOL)
            out["chains[].rank.by_P"] = by_p.astype(np.float64)
            out["chains[].rank.by_Q"] = by_q.astype(np.float64)
        for path in self.wanted:
            name = path.removeprefix("chains[].")
            if path in out:
                continue
            elif name == "loops[].Q":
                out[path] = np.stack([c.loop_q for c in measures], axis=1)
            elif name in ChainMeasures._fields:
                out[path] = np.stack([getattr(c, name) for c in measures], axis=1)
            else:
                counts = [layout.counts[name] for layout in self.layouts]
                out[path] = np.tile(np.asarray(counts, dtype=np.float64), (m, 1))
        return {path: out[path] for path in self.wanted}

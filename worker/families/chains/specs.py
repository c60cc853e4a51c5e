"""Validated inputs of the kinematic-chain jobs (docs/methods/chains.md).

Every model is frozen with ``extra="forbid"`` and rejects NaN and infinity; the field
descriptions become the public JSON schema served at ``GET /v1/processes/{id}``.

A chain's description is checked in full (:func:`worker.families.chains.kinematics.
chain_problems`) and the chains against each other; every problem becomes a pydantic
error located at the offending field (``chains.1.loops.2``) whose message repeats the
path, e.g. ``chains[1].loops[2]: link '9' is not defined``.
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import (
    BaseModel,
    BeforeValidator,
    Discriminator,
    Field,
    JsonValue,
    StringConstraints,
    Tag,
    ValidationError,
    ValidationInfo,
    model_validator,
)
from pydantic_core import InitErrorDetails, PydanticCustomError

from worker.common.numeric_ranges import PositiveLength, length_ratio_problem, ratio_schema
from worker.common.specs import FrozenSpec
from worker.families.chains import kinematics as chains
from worker.study_kernels import in_study_template

__all__ = [
    "MAX_CHAINS",
    "MAX_LINKS",
    "MAX_LOOPS",
    "MAX_POLYGON_SIDES",
    "MAX_SINGLE_LOOP_LINKS",
    "ChainParallelismSpec",
    "LoopChain",
    "MultiLoopChain",
    "PolygonalLink",
    "chain_error",
    "plots_field",
    "to_chain",
    "unit_field",
]

#: Longest single loop: its (n-1)!/2 cyclic arrangements are all listed (2520 for 8).
MAX_SINGLE_LOOP_LINKS = 8
#: Links of a multi-loop chain, and loops (inner + peripheral); sides of one loop.
MAX_LINKS = 16
MAX_LOOPS = 16
MAX_LOOP_SIDES = 16
#: Sides of one polygonal link (3: ternary, 4: quaternary, ...).
MAX_POLYGON_SIDES = 8
MAX_CHAINS = 20

#: A length: in [MIN_LENGTH, MAX_LENGTH] (worker.common.numeric_ranges); the lengths of
#: one chain span at most MAX_LENGTH_RATIO (checked with the chain).
Length = PositiveLength
_NAME_PATTERN = r"^[A-Za-z0-9_-]{1,16}$"
LinkName = Annotated[str, StringConstraints(pattern=_NAME_PATTERN)]
SideName = Annotated[str, StringConstraints(pattern=_NAME_PATTERN)]
SideRef = Annotated[
    str, StringConstraints(pattern=r"^[A-Za-z0-9_-]{1,16}(\.[A-Za-z0-9_-]{1,16})?$")
]
ChainName = Annotated[str, StringConstraints(min_length=1, max_length=40)]


def _counted(what: str, low: int, high: int) -> Any:
    """Check a list's length before its items, with one message, and publish the bounds.

    (A ``min_length`` on a variable tuple would add a second, confusing error, "should
    have at least n items after validation", whenever an item is invalid.)
    """

    def check(value: Any) -> Any:
        if isinstance(value, list | tuple) and not low <= len(value) <= high:
            raise ValueError(f"{what} must have {low} to {high} entries, not {len(value)}")
        return value

    return BeforeValidator(check)


#: The unit of a length input, for the pages: the job's ``length_unit``.
LENGTH_UNIT: dict[str, JsonValue] = {"x-unit": "length"}


def _bounds(low: int, high: int) -> dict[str, Any]:
    return {"minItems": low, "maxItems": high}


class LoopChain(FrozenSpec):
    """A single loop of binary links, given by their lengths in order round the loop."""

    name: ChainName = Field(..., description="Name of the chain (unique among the chains).")
    lengths: Annotated[tuple[Length, ...], _counted("lengths", 3, MAX_SINGLE_LOOP_LINKS)] = Field(
        ...,
        json_schema_extra={**_bounds(3, MAX_SINGLE_LOOP_LINKS), **ratio_schema(), **LENGTH_UNIT},
        description=f"Link lengths in order round the loop (3..{MAX_SINGLE_LOOP_LINKS}); the "
        "links are named '1', '2', ... in this order. Each in [1e-6, 1e6], the longest at "
        "most 1e6 times the shortest.",
    )


class PolygonalLink(FrozenSpec):
    """A link with three or more joints: a rigid polygon with one length per side."""

    sides: dict[SideName, Length] = Field(
        ...,
        min_length=3,
        max_length=MAX_POLYGON_SIDES,
        description="Side lengths by side name, e.g. {'a': 6, 'b': 7, 'c': 9} for a ternary "
        "link; every side borders one loop and counts as one dimension of the chain.",
    )


def _link_kind(value: Any) -> str | None:
    if isinstance(value, dict | PolygonalLink):
        return "PolygonalLink"
    if isinstance(value, int | float) and not isinstance(value, bool):
        return "Length"
    return None


#: A binary link's length or a polygonal link; the capitalised tags stay out of the
#: field paths the service reports.
LinkValue = Annotated[
    Annotated[Length, Tag("Length")] | Annotated[PolygonalLink, Tag("PolygonalLink")],
    Discriminator(
        _link_kind,
        custom_error_type="link_kind",
        custom_error_message=(
            "a link must be a length (a binary link) or {'sides': {'a': ..., ...}} (a "
            "polygonal link)"
        ),
    ),
]


class MultiLoopChain(FrozenSpec):
    """Links by name and the loops round them, inner loops first, the peripheral last."""

    name: ChainName = Field(..., description="Name of the chain (unique among the chains).")
    links: dict[LinkName, LinkValue] = Field(
        ...,
        min_length=3,
        max_length=MAX_LINKS,
        json_schema_extra={**ratio_schema(), **LENGTH_UNIT},
        description="Each link's length (a binary link) or {'sides': {...}} (a polygonal "
        "link), by link name (letters, digits, '_' or '-'). Every length and side in "
        "[1e-6, 1e6], the longest of the chain at most 1e6 times the shortest.",
    )
    loops: Annotated[
        tuple[
            Annotated[
                tuple[SideRef, ...],
                _counted("a loop", 1, MAX_LOOP_SIDES),
                Field(json_schema_extra=_bounds(1, MAX_LOOP_SIDES)),
            ],
            ...,
        ],
        _counted("loops", 1, MAX_LOOPS),
    ] = Field(
        ...,
        json_schema_extra=_bounds(1, MAX_LOOPS),
        description="Every independent inner loop and, last, the peripheral loop, each as the "
        "link sides met going round it: '2' for binary link 2, '1.a' for side a of link 1. "
        "A single-loop chain lists its one loop once.",
    )


def _chain_kind(value: Any) -> str | None:
    if isinstance(value, dict):
        keys = set(value)
    elif isinstance(value, BaseModel):
        keys = set(type(value).model_fields)
    else:
        return None
    has_lengths, has_links = "lengths" in keys, "links" in keys
    if has_lengths == has_links:
        return None
    return "LoopChain" if has_lengths else "MultiLoopChain"


Chain = Annotated[
    Annotated[LoopChain, Tag("LoopChain")] | Annotated[MultiLoopChain, Tag("MultiLoopChain")],
    Discriminator(
        _chain_kind,
        custom_error_type="chain_kind",
        custom_error_message=(
            "a chain must be an object with a 'name' and either 'lengths' (one loop of "
            "binary links, in order) or 'links' and 'loops' (a multi-loop chain)"
        ),
    ),
]


def to_chain(chain: LoopChain | MultiLoopChain) -> chains.Chain:
    """The plain-data chain of :mod:`worker.families.chains.kinematics`."""
    if isinstance(chain, LoopChain):
        return chains.single_loop_chain(chain.name, chain.lengths)
    links: dict[str, chains.LinkLengths] = {
        name: (dict(value.sides) if isinstance(value, PolygonalLink) else value)
        for name, value in chain.links.items()
    }
    return chains.Chain(chain.name, links, chain.loops)


def _path(where: tuple[str | int, ...]) -> str:
    text = ""
    for part in where:
        text += (
            f"[{part}]"
            if isinstance(part, int)
            else (f"['{part}']" if text.endswith(("links", "sides")) else f".{part}")
        )
    return text


def chain_error(loc: tuple[str | int, ...], message: str, value: Any) -> InitErrorDetails:
    return {
        "type": PydanticCustomError("chain_description", "{message}", {"message": message}),
        "loc": loc,
        "input": value,
    }


def unit_field() -> Any:
    return Field(
        "units",
        min_length=1,
        max_length=16,
        pattern=r"^[\w .°/-]+$",
        description="Name of the length unit, used in plots and reported back.",
    )


def plots_field() -> Any:
    return Field(True, description="Render the PNG/SVG plots. false: the result document only.")


class ChainParallelismSpec(FrozenSpec):
    """Inputs of ``chain-parallelism``: P, Q and rankings of chains to compare."""

    chains: Annotated[tuple[Chain, ...], _counted("chains", 1, MAX_CHAINS)] = Field(
        ...,
        json_schema_extra=_bounds(1, MAX_CHAINS),
        description=f"The chains to compare (1..{MAX_CHAINS}), all with the same number of "
        "links and degrees of freedom: {'name', 'lengths': [...]} for a single loop, or "
        "{'name', 'links': {...}, 'loops': [[...], ...]} for a multi-loop chain.",
    )
    length_unit: str = unit_field()
    plots: bool = plots_field()

    @model_validator(mode="after")
    def _valid_chains(self, info: ValidationInfo) -> ChainParallelismSpec:
        """Every chain valid, the chains comparable.  A design study's template leaves
        out what depends on the lengths (their spread, whether polygons and loops
        close): its kernel checks that design by design (worker.families.chains.study)."""
        template = in_study_template(info.context)
        errors: list[InitErrorDetails] = []
        seen: dict[str, int] = {}
        for index, chain in enumerate(self.chains):
            if chain.name in seen:
                errors.append(
                    chain_error(
                        ("chains", index, "name"),
                        (
                            f"chains[{index}].name: '{chain.name}' is also the name of "
                            f"chains[{seen[chain.name]}]; chain names must be unique"
                        ),
                        chain.name,
                    )
                )
            seen.setdefault(chain.name, index)
            spread = length_ratio_problem(_all_lengths(chain), f"chains[{index}]")
            if spread is not None and not template:
                field = "lengths" if isinstance(chain, LoopChain) else "links"
                errors.append(chain_error(("chains", index, field), spread, None))
                continue
            for problem in chains.chain_problems(to_chain(chain), geometry=not template):
                where = ("chains", index, *problem.where)
                errors.append(
                    chain_error(
                        where, f"chains[{index}]{_path(problem.where)}: {problem.message}", None
                    )
                )
        if not errors:
            errors = _comparable(self.chains)
        if errors:
            raise ValidationError.from_exception_data(type(self).__name__, errors)
        return self


def _all_lengths(chain: LoopChain | MultiLoopChain) -> list[float]:
    """Every length of a chain: its binary links' and its polygonal links' sides."""
    if isinstance(chain, LoopChain):
        return list(chain.lengths)
    found: list[float] = []
    for value in chain.links.values():
        found.extend(value.sides.values() if isinstance(value, PolygonalLink) else [value])
    return found


def _comparable(given: tuple[LoopChain | MultiLoopChain, ...]) -> list[InitErrorDetails]:
    """Chains compared must have the same number of links and degrees of freedom."""
    structures = [chains.chain_structure(to_chain(chain)) for chain in given]
    first = structures[0]
    errors = []
    for index, structure in enumerate(structures[1:], start=1):
        if (len(structure.links), structure.mobility) != (len(first.links), first.mobility):
            errors.append(
                chain_error(
                    ("chains", index),
                    (
                        f"chains[{index}]: '{given[index].name}' has {len(structure.links)} "
                        f"links and mobility {structure.mobility}, but chains[0] "
                        f"'{given[0].name}' has {len(first.links)} links and mobility "
                        f"{first.mobility}; compare only chains with the same number of links "
                        "and degrees of freedom"
                    ),
                    None,
                )
            )
    return errors

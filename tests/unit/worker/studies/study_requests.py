"""Hypothesis strategies for ``design-study`` request bodies, and a check that a field
error names a place in the request.

The bodies start from the registered processes' worked examples and the study's own,
then take random deletions and mutations: unknown and other processes, partial or
wrongly typed ``fixed`` inputs, varied paths that are sound, into lists ``fixed``
lacks, out of range, nested, deep, with ``[]`` or a reduction, grids and samples with
odd or bad counts and bounds, objectives the process reports or not, and stray keys.
"""

from __future__ import annotations

import copy
import json
import os
import re
from collections.abc import Iterator
from functools import cache
from typing import Any

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from worker.registry import default_registry

__all__ = ["names_a_place", "property_settings", "sound_study_bodies", "study_bodies"]

#: Examples per property test (0: each test's own count, the same examples every run);
#: set ``DEXLAB_PROPERTY_EXAMPLES=2000`` to search longer, with fresh examples each time.
RUN_EXAMPLES = int(os.environ.get("DEXLAB_PROPERTY_EXAMPLES", "0"))


def property_settings(examples: int) -> Any:
    return settings(
        max_examples=RUN_EXAMPLES or examples,
        deadline=None,
        derandomize=not RUN_EXAMPLES,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    )


#: Processes a study may evaluate, and their worked examples' inputs (JSON copies).
STUDIED = (
    "planar3r-dexterity-map",
    "planar3r-synthesis",
    "planar3r-design",
    "planar2dof-conditioning-map",
    "planar2dof-optimisation",
    "chain-parallelism",
    "fourbar-grashof",
    "spm-conditioning-map",
    "spm-design-space",
    "spm-optimisation",
)
#: Result paths worth trying: some each process reports, some none does.
RESULT_PATHS = (
    "optimum.eta",
    "optimum.S",
    "indices.rms_inverse_condition",
    "indices.min_inverse_condition",
    "task_points[].d_z|min",
    "task_points[0].d_z",
    "links|sum",
    "links[0]",
    "chains[0].Q_normalized",
    "chains[3].rank.by_Q",
    "chains[].P|max",
    "grashof",
    "full_turns",
    "d_min",
    "summary.best.C_n",
    "areas.full_dexterity",
    "x",
    "links[]",
    "a.b[].c|median",
    "optimum|",
    "",
    "task_points[99].d_z",
)
#: Result paths each process reports (found on its worked examples).
REPORTED = {
    "planar3r-dexterity-map": ("task_points[].d_z|min", "links|sum", "regions[].d_z_min|min"),
    "planar3r-synthesis": ("d_min", "d_max", "links|sum"),
    "planar3r-design": ("optimum.min_dz", "optimum.total_length"),
    "planar2dof-conditioning-map": (
        "summary.inverse_condition.mean",
        "summary.reachable_area_grid",
    ),
    "planar2dof-optimisation": ("optimum.eta", "optimum.S", "S_max"),
    "chain-parallelism": ("chains[0].P", "chains[].P|max", "chains[0].loops[0].Q"),
    "fourbar-grashof": ("criterion.margin", "links[].length|sum"),
    "spm-conditioning-map": ("indices.rms_inverse_condition", "indices.min_inverse_condition"),
    "spm-design-space": ("designs[].f_min|min", "gamma_deg"),
    "spm-optimisation": ("optimum.rms_inverse_condition", "optimum.gci"),
}
#: Inputs that make a design a little work, added where the example leaves the default.
LITTLE_WORK = {
    "planar3r-design": {"max_generations": 2, "population_size": 5},
    "planar2dof-optimisation": {"mean_mesh": 5},
    "spm-optimisation": {"starts": 1, "max_evaluations_per_start": 5},
}
#: Lists a varied path may point into although ``fixed`` lacks them (issue 26, finding 6).
MISSING_LISTS = ("lengths[0]", "chains[3]", "links[0]", "chains[0].lengths[2]", "workspace[0]")


@cache
def examples() -> dict[str, list[dict[str, Any]]]:
    """Each studied process's worked examples' inputs, and the study's own bodies."""
    registry = default_registry()
    found: dict[str, list[dict[str, Any]]] = {}
    for pid in (*STUDIED, "design-study"):
        process = registry.get(pid)
        assert process is not None
        found[pid] = [json.loads(json.dumps(dict(ex.inputs))) for ex in process.examples]
    return found


@cache
def numeric_properties(pid: str) -> tuple[str, ...]:
    """Top-level inputs of ``pid`` that may be a number (the sound varied paths)."""
    process = default_registry().get(pid)
    assert process is not None
    names = []
    for name, prop in process.inputs_schema["properties"].items():
        types = [prop.get("type"), *(a.get("type") for a in prop.get("anyOf", ()))]
        if "number" in types or "integer" in types:
            names.append(name)
    return tuple(names)


def places(document: Any, prefix: str = "") -> Iterator[tuple[str, Any]]:
    """Every place of a JSON document as an input path, with its value."""
    for path, _, value in _steps_to(document, prefix, ()):
        yield path, value


def _steps_to(
    document: Any, prefix: str, steps: tuple[Any, ...]
) -> Iterator[tuple[str, tuple[Any, ...], Any]]:
    if isinstance(document, dict):
        for key, value in document.items():
            path = f"{prefix}.{key}" if prefix else str(key)
            yield path, (*steps, key), value
            yield from _steps_to(value, path, (*steps, key))
    elif isinstance(document, list):
        for index, value in enumerate(document):
            path = f"{prefix}[{index}]"
            yield path, (*steps, index), value
            yield from _steps_to(value, path, (*steps, index))


json_leaves = (
    st.none()
    | st.booleans()
    | st.integers(-(10**6), 10**6)
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(max_size=6)
)


def _containers(inner: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    return st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=4)


json_values = st.recursive(json_leaves, _containers, max_leaves=8)
numbers = (
    st.integers(-5, 50)
    | st.floats(-1e3, 1e3, allow_nan=False)
    | st.sampled_from([0.0, 1e-300, 1e300, -1e308, 1.7e308])
)


def _mutate(draw: st.DrawFn, fixed: dict[str, Any]) -> dict[str, Any]:
    """``fixed`` with a few random places deleted, replaced, truncated or made cheap."""
    fixed = copy.deepcopy(fixed)
    for _ in range(draw(st.integers(0, 3))):
        found = [steps for _, steps, _ in _steps_to(fixed, "", ())]
        if not found:
            break
        steps = draw(st.sampled_from(found))
        parent = fixed
        for step in steps[:-1]:
            parent = parent[step]
        step = steps[-1]
        action = draw(st.sampled_from(["delete", "replace", "truncate"]))
        if action == "delete":
            del parent[step]
        elif action == "replace":
            parent[step] = draw(json_values)
        elif isinstance(parent[step], list):
            parent[step] = parent[step][: draw(st.integers(0, 2))]
    return fixed


#: Inputs that set how much work a design is, and a small value for each.
_SMALL = {
    "points_per_axis": 7,
    "samples": 7,
    "mean_mesh": 5,
    "starts": 1,
    "population_size": 5,
    "max_generations": 2,
    "max_evaluations_per_start": 5,
}


def _cheap(fixed: Any) -> Any:
    """Grids, samples and searches kept small, so that a design is quick to run."""
    if isinstance(fixed, dict):
        out = {k: _cheap(v) for k, v in fixed.items()}
        for key, small in _SMALL.items():
            value = out.get(key)
            if isinstance(value, int) and not isinstance(value, bool) and value > small:
                out[key] = small
        return out
    if isinstance(fixed, list):
        return [_cheap(v) for v in fixed]
    return fixed


@st.composite
def input_paths(draw: st.DrawFn, pid: str, fixed: dict[str, Any]) -> str:
    """A varied path: sound, into a missing list, out of range, deep, or not a path."""
    numeric = (numeric_properties(pid) if pid in STUDIED else ()) or ("alpha1_deg",)
    inside = [path for path, value in places(fixed) if not isinstance(value, bool)]
    lists = [path for path, value in places(fixed) if isinstance(value, list)]
    choices = [
        st.sampled_from(numeric),
        st.sampled_from(MISSING_LISTS),
        st.from_regex(r"\A[a-z_]{1,8}(\[[0-9]{1,2}\])?(\.[a-z_]{1,6}(\[[0-9]\])?){0,3}\Z"),
        st.sampled_from(["links[]", "links|sum", "a..b", "[0]", "a[-1]", "9a", "a" * 201, ""]),
        st.sampled_from(["x" + ".x" * 60, "a[0][0][0][0][0].b[1][2]", "grid.points_per_axis"]),
    ]
    if inside:
        choices.append(st.sampled_from(inside))
    if lists:
        choices.append(
            st.builds(lambda p, i: f"{p}[{i}]", st.sampled_from(lists), st.integers(0, 12))
        )
        choices.append(st.builds(lambda p: f"{p}.a", st.sampled_from(lists)))
    return draw(st.one_of(choices))


grid_axes = st.one_of(
    st.builds(
        lambda lo, span, n: [lo, lo + span, n], numbers, st.floats(0, 100), st.integers(1, 3)
    ),
    st.tuples(numbers, numbers, st.integers(-2, 4)).map(list),
    st.sampled_from([[1, 2, 10**7], [1, 2, 0], [1, 2, 2.5], [1, 2, True], [1, 2], [1, 2, 3, 4]]),
    st.sampled_from([[-1e308, 1.7e308, 3], ["1", 2, 2], [None, 2, 2], "1..2", {"lo": 1}]),
)
bounds = st.one_of(
    st.builds(lambda lo, span: [lo, lo + span], numbers, st.floats(0, 100)),
    st.tuples(numbers, numbers).map(list),
    st.sampled_from([[-1.7e308, 1.7e308], [2, 1], [1], [1, 2, 3], ["a", 1], None]),
)


@st.composite
def samples(draw: st.DrawFn, pid: str, fixed: dict[str, Any]) -> Any:
    method = draw(st.sampled_from(["sobol", "latin_hypercube", "sobol", "random", 3]))
    count = draw(st.one_of(st.integers(1, 9), st.sampled_from([0, -1, 10**7, 2.5, "3"])))
    paths = draw(st.lists(input_paths(pid, fixed), max_size=3))
    sample: dict[str, Any] = {
        "method": method,
        "count": count,
        "bounds": {path: draw(bounds) for path in paths},
    }
    if draw(st.booleans()):
        sample["seed"] = draw(st.integers(-1, 2**33))
    if draw(st.integers(0, 9)) == 0:
        sample[draw(st.sampled_from(["extra", "dimension"]))] = 1
    return sample


def _objectives(pid: str) -> st.SearchStrategy[dict[str, Any]]:
    examples_of = examples()["design-study"]
    known = [p for ex in examples_of if ex["process"] == pid for p in ex["objectives"]]
    paths = st.sampled_from([*known, *RESULT_PATHS]) if known else st.sampled_from(RESULT_PATHS)
    directions = st.sampled_from(["max", "min", "max", "min", "maximise", 1, None])
    return st.dictionaries(paths, directions, max_size=4)


@st.composite
def study_bodies(draw: st.DrawFn) -> dict[str, Any]:
    """A random ``design-study`` inputs document: a sound one with a fault or two (half
    the time), or one random in every part."""
    if draw(st.booleans()):
        return draw(faulty_bodies())
    pid = draw(
        st.sampled_from(STUDIED)
        | st.sampled_from(["design-study", "design-study-chunk", "no-such-process", ""])
        | st.sampled_from([None, 3, ["fourbar-grashof"]])
    )
    known = pid if isinstance(pid, str) and pid in STUDIED else draw(st.sampled_from(STUDIED))
    base = draw(st.sampled_from([*examples()[known], {}]))
    fixed: Any = _cheap(_mutate(draw, base))
    if draw(st.integers(0, 14)) == 0:
        fixed = draw(json_values)
    fixed_dict = fixed if isinstance(fixed, dict) else {}
    body: dict[str, Any] = {"process": pid, "fixed": fixed}
    kind = draw(st.sampled_from(["vary", "vary", "sample", "both", "neither"]))
    if kind in ("vary", "both"):
        paths = draw(st.lists(input_paths(known, fixed_dict), max_size=3))
        body["vary"] = {path: draw(grid_axes) for path in paths}
        if draw(st.integers(0, 14)) == 0:
            body["vary"] = draw(json_values)
    if kind in ("sample", "both"):
        body["sample"] = draw(samples(known, fixed_dict))
    body["objectives"] = draw(_objectives(known))
    _extras(draw, body)
    return body


def _extras(draw: st.DrawFn, body: dict[str, Any]) -> None:
    extras = st.sampled_from(["chunk_size", "allow_partial", "best_count", "plots", "speed"])
    for key in draw(st.lists(extras, max_size=2, unique=True)):
        body[key] = draw(st.sampled_from([0, 1, 3, -1, 10**6, True, "no", None]))
    for key in draw(st.lists(st.sampled_from(list(body)), max_size=1)):
        if draw(st.integers(0, 5)) == 0:
            del body[key]


@st.composite
def faulty_bodies(draw: st.DrawFn) -> dict[str, Any]:
    """A sound body (:func:`sound_study_bodies`) with up to two faults."""
    body = draw(sound_study_bodies())
    pid = body["process"]
    space = body.get("vary") or body["sample"]["bounds"]
    for _ in range(draw(st.integers(0, 2))):
        fault = draw(st.sampled_from(["process", "fixed", "path", "axis", "objective", "extra"]))
        if fault == "process":
            body["process"] = draw(st.sampled_from([*STUDIED, "design-study", "nope", 1]))
        elif fault == "fixed":
            body["fixed"] = _cheap(_mutate(draw, body["fixed"]))
        elif fault == "path":
            path = draw(input_paths(pid, body["fixed"]))
            space[path] = draw(grid_axes) if "vary" in body else draw(bounds)
        elif fault == "axis" and space:
            path = draw(st.sampled_from(sorted(space)))
            space[path] = draw(grid_axes) if "vary" in body else draw(bounds)
        elif fault == "objective":
            body["objectives"] = {**body["objectives"], **draw(_objectives(pid))}
        else:
            _extras(draw, body)
    return body


@cache
def _schema_range(pid: str, name: str) -> tuple[float, float]:
    """The [minimum, maximum] a top-level number input of ``pid`` takes (or +-100)."""
    process = default_registry().get(pid)
    assert process is not None
    prop = process.inputs_schema["properties"].get(name, {})
    low, high = -100.0, 100.0
    for alternative in (prop, *prop.get("anyOf", ())):
        low = max(low, alternative.get("minimum", alternative.get("exclusiveMinimum", low)))
        high = min(high, alternative.get("maximum", alternative.get("exclusiveMaximum", high)))
    return (low, high) if low <= high else (-100.0, 100.0)


@st.composite
def _plausible(draw: st.DrawFn, pid: str, path: str, fixed: dict[str, Any]) -> tuple[float, float]:
    """[lo, hi] for a varied input: around the example's value, within the schema's
    range, or (a time in four) anywhere."""
    given = dict(places(fixed)).get(path)
    if draw(st.integers(0, 3)) == 0:
        lo = draw(numbers)
        return lo, lo + draw(st.floats(0, 100))
    if isinstance(given, int | float) and not isinstance(given, bool):
        below, above = draw(st.floats(0, 0.3)), draw(st.floats(0, 0.3))
        return given - abs(given) * below, given + abs(given) * above
    low, high = _schema_range(pid, path)
    a, b = sorted(draw(st.floats(low, high)) for _ in range(2))
    return a, b


@st.composite
def sound_study_bodies(draw: st.DrawFn) -> dict[str, Any]:
    """A ``design-study`` inputs document likely to be accepted: a worked example's
    fixed inputs, varying inputs the process takes as numbers (or list elements the
    example gives), a few designs, and objectives the study examples use or any."""
    pid = draw(st.sampled_from(STUDIED))
    study_examples = [ex for ex in examples()["design-study"] if ex["process"] == pid]
    if study_examples and draw(st.booleans()):
        base = copy.deepcopy(draw(st.sampled_from(study_examples)))
        fixed = _cheap(base["fixed"])
        objectives = base["objectives"]
    else:
        fixed = _cheap(draw(st.sampled_from(examples()[pid])))
        paths = st.sampled_from(REPORTED[pid])
        objectives = draw(st.dictionaries(paths, st.sampled_from(["max", "min"]), min_size=1))
    fixed = {**LITTLE_WORK.get(pid, {}), **fixed}
    numeric = [name for name in numeric_properties(pid) if name not in fixed]
    elements = [
        path
        for path, value in places(fixed)
        if path.endswith("]") and isinstance(value, int | float) and not isinstance(value, bool)
    ]
    candidates = numeric + elements
    if not candidates:
        candidates = ["alpha1_deg"]
    paths = draw(st.lists(st.sampled_from(candidates), min_size=1, max_size=3, unique=True))
    axes = {path: [*draw(_plausible(pid, path, fixed)), draw(st.integers(1, 3))] for path in paths}
    body: dict[str, Any] = {"process": pid, "fixed": fixed, "objectives": objectives}
    if draw(st.booleans()):
        body["vary"] = axes
    else:
        body["sample"] = {
            "method": draw(st.sampled_from(["sobol", "latin_hypercube"])),
            "count": draw(st.integers(1, 7)),
            "bounds": {path: [lo, hi] for path, (lo, hi, _) in axes.items()},
            "seed": draw(st.integers(0, 99)),
        }
    body["plots"] = False
    if draw(st.booleans()):
        body["chunk_size"] = draw(st.integers(1, 4))
    return body


def names_a_place(field: str, document: Any) -> bool:
    """Whether a field error's ``field`` (``inputs.vary.chains[3].lengths[2]``) names a
    place in ``document``, or a member missing from a mapping there.  Keys may hold
    dots and brackets themselves, so every key that fits is tried."""
    if field == "":
        return True
    if isinstance(document, list):
        match = re.match(r"\[(\d+)\]", field)
        return (
            bool(match)
            and int(match.group(1)) < len(document)
            and names_a_place(field[match.end() :], document[int(match.group(1))])
        )
    if not isinstance(document, dict):
        return False
    rest = field[1:] if field.startswith(".") else field
    for key in sorted(document, key=len, reverse=True):
        if isinstance(key, str) and rest.startswith(key):
            after = rest[len(key) :]
            if after[:1] in ("", ".", "[") and names_a_place(after, document[key]):
                return True
    return re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", rest) is not None  # a missing member

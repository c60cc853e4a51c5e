"""Notes on the parallelism paper's misprints, for chains that are recognisably its figures.

docs/methods/chains.md lists what re-computation found wrong; a note is added only when a
chain is one of the paper's (the same loop up to rotation and reflection; for the
order-free normalised P, the same lengths in any order) and says both the printed and
the correct value.  The paper's conclusions are checked when both chains compared are
present.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from worker.families.chains.examples import FIG_2, FIG_3, FIG_4A, FIG_4B

__all__ = ["parallelism_errata_notes"]

Key = tuple[float, ...]
Entry = dict[str, Any]


def _cyclic_key(values: Sequence[float]) -> Key:
    """The same for a loop and its rotations and reflections."""
    seq = [float(v) for v in values]
    forms = [tuple(s[i:] + s[:i]) for s in (seq, seq[::-1]) for i in range(len(seq))]
    return min(forms)


def _chain_key(loops: Sequence[Sequence[float]]) -> tuple[Key, ...]:
    """Inner loops in any order, the peripheral loop last."""
    keys = [_cyclic_key(loop) for loop in loops]
    return (*sorted(keys[:-1]), keys[-1])


def _figure_4_key(chain: dict[str, Any]) -> tuple[Key, ...]:
    def length(side: str) -> float:
        link, _, name = side.partition(".")
        value = chain["links"][link]
        return float(value["sides"][name]) if name else float(value)

    return _chain_key([[length(side) for side in loop] for loop in chain["loops"]])


def _entry_key(entry: Entry) -> tuple[Key, ...]:
    return _chain_key([loop["lengths"] for loop in entry["loops"]])


def _is_loop(entry: Entry, lengths: Sequence[float]) -> bool:
    return len(entry["loops"]) == 1 and _entry_key(entry) == (_cyclic_key(lengths),)


def _same_dimensions(entry: Entry, lengths: Sequence[float]) -> bool:
    return sorted(d["length"] for d in entry["dimensions"]) == sorted(map(float, lengths))


def _values(values: Sequence[float]) -> str:
    return ", ".join(f"{v:g}" for v in values)


def _fig_2d(entry: Entry) -> list[str]:
    deviations = entry["loops"][0]["deviations"]
    return [
        f"{entry['name']} is the paper's Fig 2d: it prints the deviations as 36, 120, 20, "
        f"126; with eps_i = l_(i-1) l_i - l_i l_(i+1) they are {_values(deviations)} for "
        f"the links in the order ({_values(entry['loops'][0]['lengths'])}) (the paper prints "
        f"magnitudes, and 126 is a typo for 136), Q = {entry['Q']:g}."
    ]


def _fig_2e(entry: Entry) -> list[str]:
    deviations = entry["loops"][0]["deviations"]
    return [
        f"{entry['name']} is the paper's Fig 2e: it prints the deviations as 90, 10, 85, 75; "
        f"they are {_values(deviations)} for the links in the order "
        f"({_values(entry['loops'][0]['lengths'])}) (75 = |18 x 10 - 17 x 15| is an "
        f"'opposite product' difference, not the deviation of the 15 link), Q = {entry['Q']:g}."
    ]


def _fig_2d_normalised(entry: Entry) -> list[str]:
    shares = ", ".join(f"{d['length']:g}/{entry['total_length']:g}" for d in entry["dimensions"])
    return [
        f"{entry['name']}: the paper gives Fig 2d's normalised lengths as 1/60, 1/60, 17/60, "
        f"18/60; they are {shares}, and P_normalized = "
        f"{entry['P_normalized']:.5g} (printed 0.00354, which is right)."
    ]


def _fig_3(entry: Entry) -> list[str]:
    return [
        f"{entry['name']} has Fig 3's lengths (30, 17, 18, 25): the paper prints its "
        f"normalised P as 0.0349; it is {entry['P_normalized']:.5g} (a factor-10 slip). Only "
        "the corrected value supports the paper's conclusion that Fig 2d (0.0035417) is more "
        "uniformly rigid than Fig 3."
    ]


def _fig_4_mobility(entry: Entry) -> str:
    return (
        f"The paper calls its Fig 4 chains single-DOF; {entry['links']} links and "
        f"{entry['joints']} joints give mobility 3 x {entry['links'] - 1} - 2 x "
        f"{entry['joints']} = {entry['mobility']} by Grübler-Kutzbach."
    )


def _fig_4a(entry: Entry) -> list[str]:
    shares = " + ".join(f"{loop['Q']:g}" for loop in entry["loops"])
    return [
        f"{entry['name']} is the paper's Fig 4a: it prints the total deviation as 11214; its "
        f"own product tables give {shares} = {entry['Q']:g}.",
        _fig_4_mobility(entry),
    ]


def _fig_4b(entry: Entry) -> list[str]:
    shares = " + ".join(f"{loop['Q']:g}" for loop in entry["loops"])
    return [
        f"{entry['name']} is the paper's Fig 4b: it prints the total deviation as 9538. Its "
        "table as printed gives 10474, but its loop 3 cannot come from real lengths "
        "(99 x 90 x 70 != 110 x 63 x 70); with '7 and 1 = 90' (link 7 = 10 against side "
        f"c = 9 of link 1) the tables are consistent and Q = {shares} = {entry['Q']:g}.",
        _fig_4_mobility(entry),
    ]


_RECOGNISERS: tuple[tuple[Callable[[Entry], bool], Callable[[Entry], list[str]]], ...] = (
    (lambda e: _is_loop(e, FIG_2["Fig 2d"]), _fig_2d),
    (lambda e: _is_loop(e, FIG_2["Fig 2e"]), _fig_2e),
    (lambda e: _is_loop(e, FIG_2["Fig 2d"]), _fig_2d_normalised),
    (lambda e: len(e["loops"]) == 1 and _same_dimensions(e, FIG_3), _fig_3),
    (lambda e: _entry_key(e) == _figure_4_key(FIG_4A), _fig_4a),
    (lambda e: _entry_key(e) == _figure_4_key(FIG_4B), _fig_4b),
)


def _find(entries: list[Entry], recognise: Callable[[Entry], bool]) -> Entry | None:
    return next((e for e in entries if recognise(e)), None)


def _conclusion(
    entries: list[Entry],
    better: Callable[[Entry], bool],
    worse: Callable[[Entry], bool],
    key: str,
    claim: str,
    larger_is_better: bool = False,
    remark: str = "",
) -> list[str]:
    first, second = _find(entries, better), _find(entries, worse)
    if first is None or second is None:
        return []
    a, b = first[key], second[key]
    holds = a > b if larger_is_better else a < b
    relation = ">" if a > b else ("<" if a < b else "=")
    verdict = "holds" if holds else "does NOT hold"
    return [
        f"The paper's conclusion '{claim}' {verdict}: {key} {a:.6g} {relation} {b:.6g}{remark}."
    ]


def parallelism_errata_notes(entries: list[Entry]) -> tuple[list[str], list[str]]:
    """Notes for the chains that are the paper's figures (docs/methods/chains.md), as
    ``(errata, confirmations)``: the paper's misprints and the conclusions that do not
    hold, then the conclusions that do (plain notes, not errata)."""
    errata: list[str] = []
    for entry in entries:
        for recognise, note in _RECOGNISERS:
            if recognise(entry):
                errata += [text for text in note(entry) if text not in errata]
    conclusions = [
        *_conclusion(
            entries,
            lambda e: _is_loop(e, FIG_2["Fig 2e"]),
            lambda e: _is_loop(e, FIG_2["Fig 2d"]),
            "Q",
            "Fig 2e is more parallel than Fig 2d",
        ),
        *_conclusion(
            entries,
            lambda e: _is_loop(e, FIG_2["Fig 2b"]),
            lambda e: _is_loop(e, FIG_2["Fig 2c"]),
            "Q",
            "Fig 2b is more parallel than Fig 2c",
            remark=" (2b taken as the parallelogram, 2c as the kite)",
        ),
        *_conclusion(
            entries,
            lambda e: _entry_key(e) == _figure_4_key(FIG_4B),
            lambda e: _entry_key(e) == _figure_4_key(FIG_4A),
            "Q",
            "Fig 4b is more parallel than Fig 4a",
        ),
        *_conclusion(
            entries,
            lambda e: _is_loop(e, FIG_2["Fig 2d"]),
            lambda e: _is_loop(e, FIG_3),
            "P_normalized",
            "Fig 2d's links are more uniformly rigid than Fig 3's",
            larger_is_better=True,
        ),
    ]
    errata += [text for text in conclusions if "does NOT hold" in text]
    return errata, [text for text in conclusions if "does NOT hold" not in text]

"""A process description as the pages show it: its first paragraph, the rest folded
away (``<details>``, which opens without JavaScript).

The registry's descriptions are mostly one long paragraph; that paragraph's first
sentence then stands for it.  A sentence ends at ``.``, ``!`` or ``?`` before a space
and a capital letter or digit, unless the word ending there is an abbreviation the
descriptions use (``Fig.``, ``eq.``, ``et al.``, ``e.g.``) or an ellipsis.
"""

from __future__ import annotations

import re

__all__ = ["lead_and_rest"]

#: Shorter first parts are not worth folding the rest away for.
_MIN_LEAD = 40
_ABBREVIATIONS = frozenset({"fig", "figs", "eq", "eqs", "al", "e.g", "i.e", "vs", "cf", "ref",
                            "sec", "no", "approx", "resp"})  # fmt: skip
_SENTENCE_END = re.compile(r"(?<!\.)[.!?](?=\s+[A-Z0-9(])")  # not an ellipsis "..."


def lead_and_rest(text: str) -> tuple[str, str]:
    """``(first paragraph, the rest)``: split at the first blank line, else after the
    first sentence; ``(text, "")`` when there is nothing worth folding."""
    text = text.strip()
    head, blank, tail = text.partition("\n\n")
    if blank and tail.strip():
        return head.strip(), tail.strip()
    for end in _SENTENCE_END.finditer(text):
        cut = end.end()
        word = re.split(r"[\s(]", text[:cut - 1])[-1].lower()  # fmt: skip
        if cut < _MIN_LEAD or word in _ABBREVIATIONS or len(word) == 1:
            continue
        rest = text[cut:].strip()
        return (text[:cut], rest) if rest else (text, "")
    return text, ""

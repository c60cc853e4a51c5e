"""Process descriptions folded to their first paragraph (or first sentence)."""

from __future__ import annotations

import pytest

from service.pages.descriptions import lead_and_rest
from worker.registry import default_registry


def test_a_blank_line_ends_the_first_paragraph() -> None:
    assert lead_and_rest("First part, long enough to fold.\n\nSecond.\n\nThird.") == (
        "First part, long enough to fold.",
        "Second.\n\nThird.",
    )


def test_one_paragraph_folds_after_its_first_sentence_not_an_abbreviation() -> None:
    text = ("Huang et al. chose the design of Fig. 1 by eq. 7, e.g. for kappa. "
            "The rest explains more. And more.")  # fmt: skip
    lead, rest = lead_and_rest(text)
    assert lead == "Huang et al. chose the design of Fig. 1 by eq. 7, e.g. for kappa."
    assert rest == "The rest explains more. And more."


@pytest.mark.parametrize(
    "text", ["Short. Then more.", "One sentence only, long enough to be worth folding.", ""]
)
def test_nothing_worth_folding_stays_whole(text: str) -> None:
    assert lead_and_rest(text) == (text, "")


def test_every_process_description_folds_to_a_shorter_lead() -> None:
    for definition in default_registry():
        lead, rest = lead_and_rest(definition.description)
        assert rest and len(lead) < len(definition.description), definition.id
        assert definition.description.startswith(lead), definition.id
        assert definition.description.rstrip().endswith(rest), definition.id

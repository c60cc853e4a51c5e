"""The README is a front door and every link in the documentation leads somewhere.

README.md stays short (what dexlab is, the two set-up commands, the three ways in, which
process answers which question, links); the rest lives in ``docs/``. Every relative link
of README.md and of the pages under ``docs/`` names a file of the repository (and, into
a Markdown page, one of its headings), and none leaves the repository (issue 27).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import NamedTuple

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
DOCS = ROOT / "docs"

#: A page at least this long (lines) with two or more sections opens with its contents.
CONTENTS_FROM_LINES = 80

#: The front door's length, in lines.
README_MAX_LINES = 200

#: The set-up commands, byte for byte: CI (``.ci/run``) runs the README's test command.
SERVE_COMMAND = "python3.11 -m venv .venv && .venv/bin/pip install -e . && .venv/bin/dexlab serve"
TEST_COMMAND = "./scripts/test"

FENCE = re.compile(r"^\s*(```|~~~)")
CODE_SPAN = re.compile(r"(`+).+?\1")
#: ``[text](target)`` and ``![alt](target)``; the target may carry a ``"title"``.
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^(#{1,6})\s+(.+?)\s*#*\s*$")
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


class Link(NamedTuple):
    """One link of a Markdown page: where it is and what it points at."""

    page: Path
    line: int
    target: str

    def __str__(self) -> str:
        return f"{self.page.relative_to(ROOT)}:{self.line}: ({self.target})"


def prose_lines(text: str, *, code_spans: bool = False) -> list[tuple[int, str]]:
    """``(line number, line)`` outside fenced code blocks, code spans blanked unless
    ``code_spans`` (a heading's anchor counts their text)."""
    lines: list[tuple[int, str]] = []
    fenced = False
    for number, line in enumerate(text.splitlines(), start=1):
        if FENCE.match(line):
            fenced = not fenced
        elif not fenced:
            lines.append((number, line if code_spans else CODE_SPAN.sub("", line)))
    return lines


def links(page: Path) -> list[Link]:
    """Every inline link and image of a Markdown page (not those shown as code)."""
    return [
        Link(page, number, match.group(1))
        for number, line in prose_lines(page.read_text(encoding="utf-8"))
        for match in INLINE_LINK.finditer(line)
    ]


def slug(heading: str) -> str:
    """The anchor GitHub gives a heading: its text, lower case, punctuation dropped,
    spaces as hyphens (links inside it count by their text)."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading).strip().lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(page: Path) -> set[str]:
    """The anchors of a Markdown page's headings (a repeated one gains ``-1``, ``-2``...)."""
    seen: dict[str, int] = {}
    found: set[str] = set()
    for _, line in prose_lines(page.read_text(encoding="utf-8"), code_spans=True):
        match = HEADING.match(line)
        if match is None:
            continue
        base = slug(match.group(2))
        count = seen.get(base, 0)
        seen[base] = count + 1
        found.add(base if count == 0 else f"{base}-{count}")
    return found


def documentation_pages() -> list[Path]:
    return [README, *sorted(DOCS.rglob("*.md"))]


def relative_links() -> list[Link]:
    return [
        link
        for page in documentation_pages()
        for link in links(page)
        if not SCHEME.match(link.target)
    ]


def test_the_readme_is_a_front_door() -> None:
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines"


def test_the_readme_gives_the_two_set_up_commands() -> None:
    text = README.read_text(encoding="utf-8")
    set_up = text.split("\n## Set up\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"^```sh\n(.*?)^```$", set_up, re.MULTILINE | re.DOTALL)
    assert blocks == [SERVE_COMMAND + "\n", TEST_COMMAND + "\n"]
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert re.search(rf"^{re.escape(TEST_COMMAND)}\b", ci, re.MULTILINE), "CI runs it"


def test_the_readme_says_how_to_choose_the_port() -> None:
    text = README.read_text(encoding="utf-8")
    assert "--port" in text and "DEXLAB_PORT" in text and "DEXLAB_URL" in text


def test_the_readme_and_the_docs_index_link_every_docs_page() -> None:
    readme = {link.target.split("#")[0] for link in links(README)}
    index = {link.target.split("#")[0] for link in links(DOCS / "README.md")}
    for page in sorted(DOCS.glob("*.md")):
        if page.name != "README.md":
            assert f"docs/{page.name}" in readme, f"README.md does not link docs/{page.name}"
            assert page.name in index, f"docs/README.md does not link {page.name}"


def _sections(text: str) -> list[str]:
    return [line for _, line in prose_lines(text, code_spans=True) if line.startswith("## ")]


#: The pages long enough to need a contents list.
LONG_PAGES = [
    page
    for page in sorted(DOCS.glob("*.md"))
    if len((text := page.read_text(encoding="utf-8")).splitlines()) >= CONTENTS_FROM_LINES
    and len(_sections(text)) >= 2
]


def test_the_long_pages_are_the_guides() -> None:
    """The contents rule reaches the long guides (the reader sees their length)."""
    names = {page.name for page in LONG_PAGES}
    assert {"architecture.md", "operations.md", "api.md", "data-files.md"} <= names, names


@pytest.mark.parametrize("page", LONG_PAGES, ids=lambda p: p.name)
def test_a_long_docs_page_opens_with_its_contents(page: Path) -> None:
    """A page longer than a screen lists its sections, as links, before the first one."""
    text = page.read_text(encoding="utf-8")
    before = text.split("\n## ", 1)[0]
    listed = {link.target for link in links(page) if link.line <= before.count("\n") + 1}
    for heading in _sections(text):
        assert f"#{slug(heading[3:])}" in listed, f"{page.name}: contents lack {heading!r}"


def test_the_link_reader_sees_what_it_should(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(
        '# A page\n\nSee [one](a.md#x), ![a figure](f.png "title") and `[no](code.md)`.\n'
        '```\n[no](fenced.md)\n```\n## Joint limits: exact (`method: "x"`) & more\n'
        "## A page\n",
        encoding="utf-8",
    )
    assert [link.target for link in links(page)] == ["a.md#x", "f.png"]
    assert anchors(page) == {"a-page", "joint-limits-exact-method-x--more", "a-page-1"}


def test_every_relative_link_resolves_inside_the_repository() -> None:
    found = relative_links()
    assert len(found) > 50, "the reader finds the links"
    broken: list[str] = []
    for link in found:
        path, _, fragment = link.target.partition("#")
        if path.startswith("/"):
            broken.append(f"{link}: an absolute path")
            continue
        target = (link.page.parent / path).resolve() if path else link.page
        if not target.is_relative_to(ROOT):
            broken.append(f"{link}: leaves the repository")
        elif not target.exists():
            broken.append(f"{link}: no such file")
        elif fragment and target.suffix == ".md" and fragment not in anchors(target):
            broken.append(f"{link}: no heading #{fragment} in {target.name}")
    assert not broken, "\n".join(broken)


def test_a_method_page_links_only_what_the_service_serves() -> None:
    """The service serves docs/methods/<page>.md at ``/methods/<page>`` and the index
    (docs/README.md) as ``/methods``, and nothing else of docs/: a link from a method page
    to another file would be a dead link on the service's page."""
    methods = DOCS / "methods"
    offending = [
        str(link)
        for page in sorted(methods.glob("*.md"))
        for link in links(page)
        if not SCHEME.match(link.target)
        and (path := link.target.partition("#")[0])
        and (page.parent / path).resolve() not in {*methods.glob("*.md"), DOCS / "README.md"}
    ]
    assert not offending, "\n".join(offending)


def test_no_link_names_a_path_on_this_machine() -> None:
    """``file:`` URLs point outside the repository too."""
    offending = [
        str(link)
        for page in documentation_pages()
        for link in links(page)
        if link.target.lower().startswith("file:")
    ]
    assert not offending, "\n".join(offending)

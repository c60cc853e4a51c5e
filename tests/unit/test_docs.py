"""The product carries its own methods: docs/methods/ has a page for every process, every
formula in docs/ converts to MathML, and no product file sends a reader outside the
repository (issue 11, item 5)."""

from __future__ import annotations

import re
from pathlib import Path
from typing import NamedTuple

import pytest
from latex2mathml.converter import convert

from worker.registry import default_registry

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
METHODS = DOCS / "methods"

#: What the product is made of: a reference outside the repository must not appear there.
PRODUCT_FILES = ("README.md", "Dockerfile", "docker-compose.yml", "pyproject.toml")
PRODUCT_DIRS = ("service", "worker", "bench", "docs")
PRODUCT_SUFFIXES = {".py", ".md", ".html", ".css", ".js", ".txt", ".toml", ".yml", ".yaml"}
OUTSIDE_REFERENCE = re.compile(r"\.\./shared|METHODS\.md|\bpapers/")

#: A fenced code block, and an inline code span (formulas there are shown, not rendered).
FENCE = re.compile(r"^\s*(```|~~~)")
CODE_SPAN = re.compile(r"(`+).*?\1", re.DOTALL)
INLINE_MATH = re.compile(r"(?<![\\$])\$(?!\$)(.+?)(?<![\\$])\$(?!\$)", re.DOTALL)


class Formulas(NamedTuple):
    """The formulas of a Markdown page, and the ``$`` signs that open none."""

    found: list[tuple[int, str, str]]
    unpaired: list[int]


def formulas(path: Path) -> Formulas:
    """``(line, "inline" | "block", latex)`` of every formula of a Markdown page.

    Display formulas are ``$$`` lines around their LaTeX (indented inside list items, as
    markdown-it's dollarmath reads them); inline ones are ``$...$`` within a paragraph
    (they may wrap). A ``$`` left over is a formula the renderer would not see.
    """
    found: list[tuple[int, str, str]] = []
    unpaired: list[int] = []
    paragraph: list[str] = []
    first = 0

    def flush() -> None:
        text = CODE_SPAN.sub(lambda m: "\n" * m.group(0).count("\n"), "\n".join(paragraph))
        for match in INLINE_MATH.finditer(text):
            found.append((first + text.count("\n", 0, match.start()), "inline", match.group(1)))
        rest = INLINE_MATH.sub(lambda m: "\n" * m.group(0).count("\n"), text)
        unpaired.extend(first + rest.count("\n", 0, i) for i, c in enumerate(rest) if c == "$")
        paragraph.clear()

    block: list[str] | None = None
    fenced = False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if FENCE.match(line):
            flush()
            fenced = not fenced
        elif fenced:
            continue
        elif line.strip() == "$$":
            flush()
            if block is None:
                block, first = [], number
            else:
                found.append((first, "block", "\n".join(block)))
                block = None
        elif block is not None:
            block.append(line)
        elif not line.strip():
            flush()
        else:
            if not paragraph:
                first = number
            paragraph.append(line)
    flush()
    if block is not None:
        unpaired.append(first)
    return Formulas(found, unpaired)


def braces_balance(latex: str) -> bool:
    depth = 0
    for char in re.sub(r"\\[{}]", "", latex):
        depth += {"{": 1, "}": -1}.get(char, 0)
        if depth < 0:
            return False
    return depth == 0


def method_pages() -> list[Path]:
    return sorted(METHODS.glob("*.md"))


ALL_FORMULAS = [
    pytest.param(kind, latex, id=f"{path.relative_to(DOCS)}:{line}")
    for path in sorted(DOCS.rglob("*.md"))
    for line, kind, latex in formulas(path).found
]


def test_every_process_names_a_method_page_that_exists() -> None:
    pages = {path.stem for path in method_pages()}
    for definition in default_registry():
        assert definition.method_doc, f"{definition.id} names no method page"
        assert definition.method_doc in pages, f"{definition.id}: no docs/methods/*.md for it"
    used = {definition.method_doc for definition in default_registry()}
    assert pages == used, f"pages no process uses: {sorted(pages - used)}"


def test_the_index_links_every_method_page() -> None:
    index = (DOCS / "README.md").read_text(encoding="utf-8")
    for path in method_pages():
        assert f"(methods/{path.name})" in index, path.name


@pytest.mark.parametrize("path", method_pages(), ids=lambda p: p.name)
def test_a_method_page_opens_with_a_summary_and_ends_with_its_citation(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    assert lines[0].startswith("# "), "a page starts with its title"
    summary = text.split("\n\n")[1]
    assert not summary.startswith(("#", "-", "|", "$$")), "the summary paragraph comes first"
    assert len(summary.split()) >= 30, "the summary says what the method does"
    headings = [line for line in lines if line.startswith("## ")]
    for required in ("## Conventions", "## The paper's errata", "## Doubts and open questions"):
        assert required in headings, f"{path.name} has no '{required}' section"
    citation = re.search(r"^## (Citation|References?)\n(.+)", text, re.MULTILINE | re.DOTALL)
    assert citation is not None, f"{path.name} has no Citation section"
    assert len(citation.group(2).split()) >= 20, "the citation names authors, title, venue"
    assert formulas(path).found, "a method page states its equations"


@pytest.mark.parametrize(("kind", "latex"), ALL_FORMULAS)
def test_every_formula_converts_to_mathml(kind: str, latex: str) -> None:
    assert latex.strip(), "an empty formula"
    assert braces_balance(latex), f"unbalanced braces in {latex!r}"
    mathml = convert(latex.strip(), display="block" if kind == "block" else "inline")
    assert mathml.startswith("<math") and mathml.endswith("</math>")
    # latex2mathml keeps a command it does not know as text: "<mi>\foo</mi>"
    assert "\\" not in mathml, f"a LaTeX command latex2mathml does not know in {latex!r}"


def test_the_formula_reader_sees_what_it_should(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(
        "Inline $a_1 + b$ and `$not math$`, and one that\nwraps $c +\nd$.\n\n- item\n\n"
        "  $$\n  x = \\frac{1}{2}\n  $$\n\n```\n$$\nnot math either\n```\n",
        encoding="utf-8",
    )
    assert formulas(page) == Formulas(
        [(1, "inline", "a_1 + b"), (2, "inline", "c +\nd"), (7, "block", "  x = \\frac{1}{2}")],
        [],
    )
    page.write_text("Text.\n\nA lone $ sign\nin a paragraph.\n\n$$\nx\n", encoding="utf-8")
    assert formulas(page).unpaired == [3, 6]


@pytest.mark.parametrize("path", sorted(DOCS.rglob("*.md")), ids=lambda p: p.name)
def test_every_dollar_sign_opens_a_formula(path: Path) -> None:
    assert formulas(path).unpaired == [], f"unpaired $ (or an unclosed $$) at these lines of {path}"


def product_files() -> list[Path]:
    files = [ROOT / name for name in PRODUCT_FILES if (ROOT / name).is_file()]
    for directory in PRODUCT_DIRS:
        files += [
            path
            for path in sorted((ROOT / directory).rglob("*"))
            if path.is_file() and path.suffix in PRODUCT_SUFFIXES
        ]
    return files


def test_no_product_file_sends_a_reader_outside_the_repository() -> None:
    files = product_files()
    assert ROOT / "worker" / "families" / "planar_serial" / "__init__.py" in files
    offending = [
        f"{path.relative_to(ROOT)}:{number}: {line.strip()}"
        for path in files
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1)
        if OUTSIDE_REFERENCE.search(line)
    ]
    assert not offending, "\n".join(offending)


def test_process_descriptions_point_to_their_method_page() -> None:
    for definition in default_registry():
        assert not OUTSIDE_REFERENCE.search(definition.description), definition.id

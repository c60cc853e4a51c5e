"""The method pages, ``docs/methods/<slug>.md``, rendered to HTML with MathML.

Markdown goes through markdown-it-py (CommonMark, tables, raw HTML off) with the
``dollarmath`` plugin; each ``$...$`` and ``$$...$$`` formula becomes MathML on the
server (latex2mathml), so the pages need no JavaScript and no web fonts.  A formula
latex2mathml cannot convert is shown as its TeX source rather than failing the page.

A method page starts with a title and a short summary paragraph (shown on the process
page), and has a "Citation" (or "References") section with the paper's reference.
"""

from __future__ import annotations

import html
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from latex2mathml.converter import convert
from markdown_it import MarkdownIt
from markdown_it.token import Token
from mdit_py_plugins.dollarmath import dollarmath_plugin

__all__ = ["MethodDocs", "MethodPage", "default_docs_dir"]

_MATHML_NS = ' xmlns="http://www.w3.org/1998/Math/MathML"'
_SLUG = re.compile(r"^[a-z0-9][a-z0-9-]{0,63}$")
_CITATION = re.compile(r"^(citation|citations|reference|references)\b", re.IGNORECASE)


def default_docs_dir() -> Path:
    """The repository's ``docs/`` next to the ``service`` package."""
    return Path(__file__).resolve().parents[2] / "docs"


def _math(tex: str, options: dict[str, Any]) -> str:
    display = "block" if options.get("display_mode") else "inline"
    try:
        mathml = convert(tex, display=display)
    except Exception:  # latex2mathml raises many kinds; show the source instead
        return f'<code class="tex">{html.escape(tex)}</code>'
    # The namespace is implied in HTML; without it no URL appears in the page.
    return mathml.replace(_MATHML_NS, "")


def _local_href(href: str) -> str:
    """A link to another method page (``chains.md#errata``) as its page URL."""
    path, hash_, fragment = href.partition("#")
    name = path.rsplit("/", 1)[-1]
    if "://" in path or not name.endswith(".md"):
        return href
    stem = name.removesuffix(".md")
    if stem == "README":
        return "/methods" + (f"#{fragment}" if hash_ else "")
    return f"/methods/{stem}" + (f"#{fragment}" if hash_ else "")


def _markdown() -> MarkdownIt:
    md = MarkdownIt("commonmark", {"html": False, "typographer": False}).enable("table")
    md.use(dollarmath_plugin, renderer=_math)

    # Render rules are bound to the renderer: (renderer, tokens, idx, options, env).
    def table_open(renderer: Any, tokens: Sequence[Token], idx: int, options: Any, env: Any) -> str:
        return '<div class="table-wrap">' + str(renderer.renderToken(tokens, idx, options, env))

    def table_close(
        renderer: Any, tokens: Sequence[Token], idx: int, options: Any, env: Any
    ) -> str:
        return str(renderer.renderToken(tokens, idx, options, env)) + "</div>\n"

    def link_open(renderer: Any, tokens: Sequence[Token], idx: int, options: Any, env: Any) -> str:
        href = tokens[idx].attrGet("href")
        if isinstance(href, str):
            tokens[idx].attrSet("href", _local_href(href))
        return str(renderer.renderToken(tokens, idx, options, env))

    md.add_render_rule("table_open", table_open)
    md.add_render_rule("table_close", table_close)
    md.add_render_rule("link_open", link_open)
    return md


@dataclass(frozen=True)
class MethodPage:
    """One method page: its slug, title and HTML (whole, summary, citation)."""

    slug: str
    title: str
    html: str
    summary_html: str
    citation_html: str


def _lines(text: str, start: int, stop: int | None) -> str:
    return "\n".join(text.splitlines()[start:stop])


def _heading_text(tokens: list[Token], i: int) -> str:
    inline = tokens[i + 1] if i + 1 < len(tokens) else None
    return inline.content.strip() if inline is not None else ""


def _parts(md: MarkdownIt, text: str) -> tuple[str, str, str]:
    """``(title, summary markdown, citation markdown)`` of a page's source."""
    tokens = md.parse(text)
    title, summary, citation = "", "", ""
    headings = [(i, t) for i, t in enumerate(tokens) if t.type == "heading_open"]
    for i, token in headings:
        if token.tag == "h1":
            title = _heading_text(tokens, i)
            break
    for token in tokens:
        if token.type == "paragraph_open" and token.level == 0 and token.map:
            summary = _lines(text, *token.map)
            break
    for n, (i, token) in enumerate(headings):
        if token.map and _CITATION.match(_heading_text(tokens, i)):
            level = int(token.tag[1])
            stop = next(
                (t.map[0] for _, t in headings[n + 1 :] if t.map and int(t.tag[1]) <= level),
                None,
            )
            citation = _lines(text, token.map[1], stop)
            break
    return title, summary, citation


class MethodDocs:
    """The method pages under ``<docs_dir>/methods``, read when asked for (they are
    edited while the service runs in development)."""

    def __init__(self, docs_dir: Path) -> None:
        self.directory = docs_dir / "methods"
        self._md = _markdown()

    def slugs(self) -> list[str]:
        """Every page's slug, sorted."""
        if not self.directory.is_dir():
            return []
        return sorted(p.stem for p in self.directory.glob("*.md") if _SLUG.match(p.stem))

    def page(self, slug: str) -> MethodPage | None:
        """The page ``slug``, or None if there is none (or the slug is not a page name)."""
        if not _SLUG.match(slug):
            return None
        path = self.directory / f"{slug}.md"
        try:
            text = path.read_text(encoding="utf-8")
        except (FileNotFoundError, IsADirectoryError, NotADirectoryError):
            return None
        title, summary, citation = _parts(self._md, text)
        return MethodPage(
            slug=slug,
            title=title or slug,
            html=self._md.render(text),
            summary_html=self._md.render(summary) if summary else "",
            citation_html=self._md.render(citation) if citation else "",
        )

"""The HTML side of the service: templates, the method pages, the family catalogue.

One :class:`Pages` is built by ``create_app`` and kept on ``app.state.pages``; route
handlers reach it through :data:`PagesDep`.  Templates are Jinja2 with autoescaping
on; a page loads nothing from outside the service (its Content-Security-Policy says
so to the browser as well).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

import jinja2
from fastapi import Depends, Request
from fastapi.responses import HTMLResponse
from markupsafe import Markup

from service.pages.descriptions import lead_and_rest
from service.pages.forms import form_protection
from service.pages.method_docs import MethodDocs
from service.pages.result_view import format_scalar
from service.pages.settings import PageSettings
from worker.processes import ProcessDefinition, ProcessRegistry

__all__ = ["PAGE_POLICY", "STATIC_PREFIX", "Family", "Pages", "PagesDep", "get_pages"]

#: Where the pages' own CSS and script are served (a StaticFiles mount in the app).
STATIC_PREFIX = "/static/pages"

#: Pages load only from the service itself; forms post only to it.
PAGE_POLICY = (
    "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; "
    "object-src 'none'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'"
)

_TEMPLATES = Path(__file__).resolve().parent / "templates"
STATIC_DIR = Path(__file__).resolve().parent / "static"


@dataclass(frozen=True)
class Family:
    """A job family as the pages list it: its tag, description and processes."""

    key: str
    title: str
    description: str
    processes: tuple[ProcessDefinition, ...]

    @property
    def method_docs(self) -> list[str]:
        """The method pages of its processes, in order, each once."""
        return list(dict.fromkeys(p.method_doc for p in self.processes if p.method_doc))


def _file_size(size: int) -> str:
    value = float(size)
    for unit in ("bytes", "KB", "MB", "GB"):
        if value < 1024 or unit == "GB":
            return f"{size} bytes" if unit == "bytes" else f"{value:.1f} {unit}"
        value /= 1024
    return f"{size} bytes"  # pragma: no cover - the loop always returns


def _pretty_json(value: Any) -> str:
    return json.dumps(value, indent=2, ensure_ascii=False)


def _when(value: str | None) -> str:
    """An ISO 8601 UTC time (``2026-01-02T03:04:05.678Z``) as ``2026-01-02 03:04:05 UTC``."""
    if not value:
        return ""
    date, _, time = value.partition("T")
    return f"{date} {time[:8]} UTC" if time else date


_METHOD_PATH = re.compile(r"docs/methods/([a-z0-9-]+)\.md")


def link_method_pages(text: str) -> Markup:
    """Escape ``text`` and turn each repository path of a method page
    (``docs/methods/<slug>.md``) into a link to the page this service serves."""
    escaped = str(Markup.escape(text))
    return Markup(_METHOD_PATH.sub(r'<a href="/methods/\1">the method page</a>', escaped))


def _environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(_TEMPLATES),
        autoescape=True,
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters["scalar"] = format_scalar
    env.filters["pretty_json"] = _pretty_json
    env.filters["filesize"] = _file_size
    env.filters["when"] = _when
    env.filters["method_links"] = link_method_pages
    env.filters["lead_and_rest"] = lead_and_rest
    env.globals["static"] = lambda path: f"{STATIC_PREFIX}/{path}"
    return env


class Pages:
    """Renders the pages; knows the families and the method pages."""

    def __init__(
        self,
        settings: PageSettings,
        *,
        family_tags: Mapping[str, tuple[str, str]],
        family_of: Callable[[ProcessDefinition], str],
    ) -> None:
        self.settings = settings
        self.methods = MethodDocs(settings.docs_dir)
        self._family_tags = dict(family_tags)
        self._family_of = family_of
        self._env = _environment()

    def families(self, definitions: ProcessRegistry | Iterable[ProcessDefinition]) -> list[Family]:
        """The processes (a registry's, or some of them) by family, families in their
        documented order (processes of no known family last, under "Other processes")."""
        grouped: dict[str, list[ProcessDefinition]] = {}
        for definition in definitions:
            grouped.setdefault(self._family_of(definition), []).append(definition)
        order = [*self._family_tags, *sorted(k for k in grouped if k not in self._family_tags)]
        return [
            Family(key, *self._family_tags.get(key, ("Other processes", "")), tuple(grouped[key]))
            for key in order
            if key in grouped
        ]

    def render(
        self,
        request: Request,
        template: str,
        context: Mapping[str, Any],
        *,
        status_code: int = 200,
        headers: Mapping[str, str] | None = None,
    ) -> HTMLResponse:
        """``template`` rendered with ``context`` (plus the request and the form
        protection every form carries) as a page."""
        html = self._env.get_template(template).render(
            {
                **context,
                "request_path": request.url.path,
                "form_protection": Markup(form_protection(request)),
                # Who is signed in (the header shows it; None: no gate ran).
                "identity": getattr(request.state, "identity", None),
            }
        )
        response = HTMLResponse(html, status_code=status_code, headers=dict(headers or {}))
        response.headers["Content-Security-Policy"] = PAGE_POLICY
        response.headers["Referrer-Policy"] = "same-origin"
        response.headers.setdefault("Vary", "Accept")
        return response


async def get_pages(request: Request) -> Pages:
    pages: Pages = request.app.state.pages
    return pages


PagesDep = Annotated[Pages, Depends(get_pages)]

"""The absolute URLs the façade links to, from the public base of the request; and
the ``self``/``alternate`` pair every document carries (it answers JSON and HTML)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any
from urllib.parse import quote

from starlette.requests import Request

from service.ogc.forwarded import public_base_url
from service.ogc.vocabulary import HTML, JSON, OGC_PREFIX

__all__ = ["PublicUrls", "public_urls", "self_and_alternate", "with_format"]


@dataclass(frozen=True)
class PublicUrls:
    """URLs under ``root`` (``scheme://host[:port][/prefix]``, no trailing slash)."""

    root: str

    @property
    def ogc(self) -> str:
        return self.root + OGC_PREFIX

    def process(self, process_id: str) -> str:
        return f"{self.ogc}/processes/{quote(process_id, safe='')}"

    def job(self, job_id: str) -> str:
        return f"{self.ogc}/jobs/{quote(job_id, safe='')}"

    def results(self, job_id: str) -> str:
        return f"{self.job(job_id)}/results"

    def output(self, job_id: str, output_id: str) -> str:
        """One output of a job (a result member, as JSON)."""
        return f"{self.results(job_id)}/{quote(output_id, safe='')}"

    def artifact(self, job_id: str, name: str) -> str:
        """One file of a job: the native download (ETag, streamed)."""
        return f"{self.root}/v1/jobs/{quote(job_id, safe='')}/results/{quote(name, safe='')}"


def public_urls(request: Request) -> PublicUrls:
    return PublicUrls(public_base_url(request))


def with_format(href: str, f: str) -> str:
    """``href`` with its ``f`` query parameter set to ``f`` (any other kept as it is):
    the URL of one representation of the resource."""
    path, _, query = href.partition("?")
    kept = [part for part in query.split("&") if part and not part.startswith("f=")]
    return f"{path}?{'&'.join([*kept, f'f={f}'])}"


def self_and_alternate(href: str, title: str) -> list[dict[str, Any]]:
    """The links of a JSON document at ``href`` titled ``title``: itself (``self``),
    and the same resource as a page (``alternate``, ``f=html``)."""
    return [
        {"href": href, "rel": "self", "type": JSON, "title": title},
        {
            "href": with_format(href, "html"),
            "rel": "alternate",
            "type": HTML,
            "title": f"{title} as HTML",
        },
    ]

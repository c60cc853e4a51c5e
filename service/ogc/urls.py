"""The absolute URLs the façade links to, from the public base of the request."""

from __future__ import annotations

from dataclasses import dataclass
from urllib.parse import quote

from starlette.requests import Request

from service.ogc.forwarded import public_base_url
from service.ogc.vocabulary import OGC_PREFIX

__all__ = ["PublicUrls", "public_urls"]


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

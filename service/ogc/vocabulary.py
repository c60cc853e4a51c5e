"""The URIs and names OGC API - Processes - Part 1: Core 1.0 (OGC 18-062r2) defines.

Conformance classes (clause 2), link relations (clause 5.2), exception types (the
``/req/core/...-exception/...`` requirements), and the media types the façade answers.
"""

from __future__ import annotations

__all__ = [
    "CALLBACK_CONFORMANCE",
    "CONFORMANCE",
    "EXCEPTION_TYPES",
    "HTML",
    "INVALID_PARAMETER_VALUE",
    "JSON",
    "OAS30_CONFORMANCE",
    "OGC_PREFIX",
    "REL_CONFORMANCE",
    "REL_EXCEPTIONS",
    "REL_EXECUTE",
    "REL_JOB_LIST",
    "REL_PROCESSES",
    "REL_RESULTS",
    "TAG",
    "conformance_classes",
    "exception_type",
    "is_ogc_path",
    "openapi_media_type",
]

#: Where the façade lives.
OGC_PREFIX = "/ogc"

#: The OpenAPI tag of its operations.
TAG = "OGC API – Processes"

_CONF = "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/"

#: The conformance classes this service always meets (``html``: every GET resource
#: also answers a page, :mod:`service.ogc.pages`); ``oas30`` only while the served
#: definition is OpenAPI 3.0, ``callback`` only while callbacks are on
#: (:func:`conformance_classes`).
CONFORMANCE: tuple[str, ...] = (
    _CONF + "core",
    _CONF + "ogc-process-description",
    _CONF + "json",
    _CONF + "html",
    _CONF + "job-list",
    _CONF + "dismiss",
)
CALLBACK_CONFORMANCE = _CONF + "callback"
OAS30_CONFORMANCE = _CONF + "oas30"

_REL = "http://www.opengis.net/def/rel/ogc/1.0/"
REL_CONFORMANCE = _REL + "conformance"
REL_PROCESSES = _REL + "processes"
REL_JOB_LIST = _REL + "job-list"
REL_EXECUTE = _REL + "execute"
REL_RESULTS = _REL + "results"
REL_EXCEPTIONS = _REL + "exceptions"

#: dexlab problem slug -> the exception type 1.0 defines for it.
EXCEPTION_TYPES: dict[str, str] = {
    slug: f"http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/{slug}"
    for slug in ("no-such-process", "no-such-job", "result-not-ready", "invalid-parameter-value")
}

#: The type of a 400 for a query, path or header parameter with a bad value: the
#: exception OGC web services name ``InvalidParameterValue`` (OWS Common, as pygeoapi
#: answers), spelt like its siblings under the standard's exception namespace.
INVALID_PARAMETER_VALUE = EXCEPTION_TYPES["invalid-parameter-value"]

JSON = "application/json"
HTML = "text/html"


def openapi_media_type(version: str) -> str:
    """The media type of an OpenAPI JSON document of ``version`` (e.g. "3.1.0")."""
    major_minor = ".".join(version.split(".")[:2])
    return f"application/vnd.oai.openapi+json;version={major_minor}"


def is_ogc_path(path: str | None) -> bool:
    """Whether a request path is under the façade."""
    return bool(path) and (path == OGC_PREFIX or str(path).startswith(OGC_PREFIX + "/"))


def exception_type(slug: str, path: str | None) -> str | None:
    """The OGC exception type of a problem answered at ``path``, or None (then the
    problem keeps dexlab's own type)."""
    return EXCEPTION_TYPES.get(slug) if is_ogc_path(path) else None


def conformance_classes(callbacks: bool, openapi_version: str) -> list[str]:
    """The ``conformsTo`` list: the classes met; ``oas30`` when the served OpenAPI
    document is 3.0, ``callback`` when callbacks are on."""
    classes = list(CONFORMANCE)
    if openapi_version.startswith("3.0."):
        classes.append(OAS30_CONFORMANCE)
    if callbacks:
        classes.append(CALLBACK_CONFORMANCE)
    return classes

"""The settings tree: one :class:`Settings`, built once by an entry point, passed down.

Every setting is an environment variable ``DEXLAB_<FIELD>`` (or a command-line option
of ``dexlab serve`` / ``dexlab worker``).  The tree is flat, for the variables are, and
made of sections, each a plain model that reads nothing and is what its consumer takes:

==============================================  ==========================================
section                                         read by
==============================================  ==========================================
:class:`worker.settings.WorkerSettings`         the job runtime: store, pool, Celery
:class:`ServiceSettings` (adds to the worker's)  the HTTP layer: listening, limits, keys
:class:`service.pages.settings.PageSettings`    the browser pages
:class:`service.metrics.settings.MetricsSettings`  ``/metrics``
:class:`worker.logs.LogSettings`                every process's log lines
==============================================  ==========================================

:class:`Settings` is all of them and the only class that reads the environment; only
the entry points build it (``dexlab serve``, ``dexlab worker``, ``dexlab keys``, the
test deployments), and ``tests/test_environment_reads.py`` keeps it so.
"""

from __future__ import annotations

from urllib.parse import urlsplit

from pydantic import ConfigDict, Field, SecretStr, field_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

from service.metrics.settings import MetricsSettings
from service.pages.settings import PageSettings
from worker.logs import LogSettings
from worker.settings import WorkerSettings

__all__ = ["ServiceSettings", "Settings"]


class ServiceSettings(WorkerSettings):
    """The HTTP section (with the worker section it adds to): where ``dexlab serve``
    listens, what requests it accepts, its keys and sessions."""

    # A refused value is not echoed in the error: it may hold key secrets.
    model_config = ConfigDict(hide_input_in_errors=True)

    host: str = Field("127.0.0.1", description="Address the HTTP server binds to.")
    port: int = Field(8000, ge=0, le=65535, description="Port the HTTP server listens on.")
    log_level: str = Field("info", description="Log level of the server and the pool.")
    max_body_bytes: int = Field(
        1024 * 1024,
        ge=1024,
        le=1024**3,
        description="Largest request body accepted (bytes); a larger one is answered 413.",
    )
    max_json_depth: int = Field(
        64, ge=8, le=512, description="Deepest nesting of a JSON request body accepted."
    )
    forwarded_allow_ips: str = Field(
        "127.0.0.1,::1",
        max_length=4096,
        description="Proxies whose X-Forwarded-Proto/-For/-Host/-Prefix headers are "
        "trusted: comma-separated addresses or networks (CIDR), or '*' for any; the "
        "links and Location headers the API sends are then the proxy's public URLs.",
    )
    outbound_allow_hosts: str = Field(
        "",
        max_length=4096,
        description="The only hosts this service sends requests to (OGC `subscriber` "
        "callbacks, inputs given by reference): comma-separated host names or "
        "host:port.  Empty (the default): it sends none, and both are refused.",
    )
    outbound_timeout_s: float = Field(
        5.0, gt=0, le=60, description="Connect and read timeout of one outbound request."
    )
    callback_max_attempts: int = Field(
        5, ge=1, le=50, description="Tries of one callback before it is given up."
    )
    api_keys: SecretStr = Field(
        SecretStr(""),
        description="API keys made in the store at start-up: 'name:secret' entries, "
        "comma-separated ('name:secret:admin' for an admin).  With any key in the store "
        "the service needs one; with none it is open.",
    )
    session_secret: SecretStr | None = Field(
        None,
        description="Signs browser sessions (at least 32 characters); unset: a secret "
        "generated once and kept in the store, shared by every replica.",
    )
    session_seconds: float = Field(
        12 * 3600.0, ge=60, le=30 * 86400, description="How long a browser login lasts."
    )
    cors_origins: str = Field(
        "",
        max_length=4096,
        description="Origins (scheme://host[:port], comma-separated, or '*') whose "
        "pages may call the API from a browser (CORS, with the Authorization header); "
        "empty (the default): none.",
    )

    @field_validator("api_keys")
    @classmethod
    def _declared_keys(cls, value: SecretStr) -> SecretStr:
        # lazy: keeps the settings, which every command line reads, free of the HTTP layer
        from service.auth.seeding import parse_api_keys

        parse_api_keys(value.get_secret_value())  # ValueError names the entry, not its secret
        return value

    @field_validator("session_secret")
    @classmethod
    def _session_secret(cls, value: SecretStr | None) -> SecretStr | None:
        if value is not None and len(value.get_secret_value()) < 32:
            raise ValueError("The 'session_secret' setting must be at least 32 characters.")
        return value

    @field_validator("cors_origins")
    @classmethod
    def _origins(cls, value: str) -> str:
        for origin in cls.origin_list(value):
            parts = urlsplit(origin)
            if origin != "*" and (
                parts.scheme not in ("http", "https")
                or not parts.netloc
                or parts.path
                or parts.query
                or parts.fragment
            ):
                raise ValueError(
                    "Each of the 'cors_origins' must be scheme://host[:port] or '*'. "
                    f"Got {origin!r} instead."
                )
        return value

    @staticmethod
    def origin_list(value: str) -> list[str]:
        """The origins of a ``cors_origins`` value."""
        return [o.strip().rstrip("/") for o in value.split(",") if o.strip()]

    @field_validator("forwarded_allow_ips")
    @classmethod
    def _trusted_proxies(cls, value: str) -> str:
        # lazy: keeps the settings, which every command line reads, free of the HTTP layer
        from service.ogc.forwarded import parse_trusted

        parse_trusted(value)  # ValueError names a bad entry
        return value

    @field_validator("outbound_allow_hosts")
    @classmethod
    def _outbound_hosts(cls, value: str) -> str:
        # lazy: keeps the settings, which every command line reads, free of the HTTP layer
        from service.ogc.outbound import OutboundPolicy

        OutboundPolicy.from_setting(value)  # ValueError names a bad entry
        return value


class Settings(BaseSettings, ServiceSettings, PageSettings, MetricsSettings, LogSettings):
    """Every setting of a dexlab process: the one settings tree (see the module).

    ``Settings()`` reads ``DEXLAB_<FIELD>`` for each field of each section; keyword
    arguments (the command-line options given) win over the environment.  An entry
    point builds it once and passes it down; nothing else reads the environment.
    """

    model_config = SettingsConfigDict(
        env_prefix="DEXLAB_", extra="forbid", frozen=True, hide_input_in_errors=True
    )

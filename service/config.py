"""Service settings: the worker settings plus where the HTTP server listens."""

from __future__ import annotations

from pydantic import Field, field_validator

from worker.settings import WorkerSettings

__all__ = ["ServiceSettings"]


class ServiceSettings(WorkerSettings):
    """Settings of ``dexlab serve`` (environment ``DEXLAB_*`` or command-line options)."""

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

    @field_validator("forwarded_allow_ips")
    @classmethod
    def _trusted_proxies(cls, value: str) -> str:
        from service.ogc.forwarded import parse_trusted

        parse_trusted(value)  # ValueError names a bad entry
        return value

    @field_validator("outbound_allow_hosts")
    @classmethod
    def _outbound_hosts(cls, value: str) -> str:
        from service.ogc.outbound import OutboundPolicy

        OutboundPolicy.from_setting(value)  # ValueError names a bad entry
        return value

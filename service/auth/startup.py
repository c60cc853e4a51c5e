"""Authentication at start-up: seed the declared keys, build the authenticator, and
warn when an open service listens beyond this machine."""

from __future__ import annotations

import ipaddress
import logging

from service.auth.authenticator import Authenticator, session_signer
from service.auth.key_cache import KeyCache
from service.auth.seeding import seed_keys
from service.config import ServiceSettings
from worker.store.base import JobStore

__all__ = ["start_auth"]

log = logging.getLogger("dexlab.service")


def _loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:  # a host name: it may resolve anywhere
        return False


def start_auth(settings: ServiceSettings, store: JobStore) -> Authenticator:
    """Seed ``DEXLAB_API_KEYS`` into the (open) store and return the authenticator."""
    seed_keys(store, settings.api_keys.get_secret_value())
    secret = settings.session_secret.get_secret_value() if settings.session_secret else None
    auth = Authenticator(KeyCache(store), session_signer(store, secret, settings.session_seconds))
    if not auth.keys.table().configured:
        if _loopback(settings.host):
            log.info("no API keys: the service is open to this machine (%s)", settings.host)
        else:
            log.warning(
                "no API keys and listening on %s: anyone who reaches this port can run, "
                "read and dismiss every job; make a key with 'dexlab keys create NAME' "
                "(or set DEXLAB_API_KEYS)",
                settings.host,
            )
    return auth

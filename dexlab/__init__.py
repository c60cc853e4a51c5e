"""dexlab for its users: the ``dexlab`` command line (and, later, a Python client).

Importing this package does no work and imports neither the server nor the worker: the
server-side commands (``dexlab serve``, ``dexlab worker``) import them when they run.
"""

from __future__ import annotations

__all__: list[str] = []

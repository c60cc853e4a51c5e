"""The ``dexlab`` command (Click, with Rich for output).

Server commands (``serve``, ``worker``) run the service; the other command groups talk
to it.  Usage errors exit 2 with one line on stderr; no user error ends in a Python
traceback.
"""

from __future__ import annotations

from dexlab.cli.app import cli, main

__all__ = ["cli", "main"]

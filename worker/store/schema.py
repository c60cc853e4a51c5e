"""The job store's schema, as an ordered list of migrations.

Each migration runs once, in order, inside the transaction that records its version in
``schema_version``; a store created by an older dexlab is migrated forward on start-up,
never dropped.  Append new migrations; never edit an applied one.  ``{seq_pk}``,
``{blob}`` and ``{float}`` are filled in with each database's type names.
"""

from __future__ import annotations

__all__ = ["MIGRATIONS"]

MIGRATIONS: tuple[tuple[int, tuple[str, ...]], ...] = (
    (
        1,
        (
            """CREATE TABLE jobs (
                seq {seq_pk},
                job_id TEXT NOT NULL UNIQUE,
                process_id TEXT NOT NULL,
                status TEXT NOT NULL,
                inputs TEXT NOT NULL,
                progress {float} NOT NULL DEFAULT 0,
                message TEXT NOT NULL DEFAULT '',
                created {float} NOT NULL,
                updated {float} NOT NULL,
                started {float},
                finished {float},
                attempts INTEGER NOT NULL DEFAULT 0,
                max_attempts INTEGER NOT NULL,
                time_limit_s {float} NOT NULL,
                lease_token TEXT,
                lease_expires {float},
                worker_id TEXT,
                attempt_started {float},
                error TEXT,
                result TEXT,
                idempotency_key TEXT UNIQUE,
                request_hash TEXT
            )""",
            "CREATE INDEX jobs_status_seq ON jobs (status, seq)",
            "CREATE INDEX jobs_process_seq ON jobs (process_id, seq)",
            """CREATE TABLE artifacts (
                job_id TEXT NOT NULL REFERENCES jobs (job_id) ON DELETE CASCADE,
                name TEXT NOT NULL,
                media_type TEXT NOT NULL,
                title TEXT NOT NULL DEFAULT '',
                size INTEGER NOT NULL,
                data {blob} NOT NULL,
                ord INTEGER NOT NULL DEFAULT 0,
                PRIMARY KEY (job_id, name)
            )""",
            """CREATE TABLE workers (
                worker_id TEXT PRIMARY KEY,
                host TEXT NOT NULL,
                pid INTEGER NOT NULL,
                started {float} NOT NULL,
                heartbeat {float} NOT NULL
            )""",
        ),
    ),
    (
        2,
        # When the job was last handed to a broker (NULL: never), so a sweeper can
        # re-dispatch a job whose message was lost.
        ("ALTER TABLE jobs ADD COLUMN dispatched {float}",),
    ),
)

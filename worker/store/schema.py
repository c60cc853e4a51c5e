"""The job store's schema, as an ordered list of migrations.

Each migration runs once, in order, inside the transaction that records its version in
``schema_version``; a store created by an older dexlab is migrated forward on start-up,
never dropped.  Append new migrations; never edit an applied one.
"""

from __future__ import annotations

__all__ = ["MIGRATIONS"]

MIGRATIONS: tuple[tuple[int, tuple[str, ...]], ...] = (
    (
        1,
        (
            """CREATE TABLE jobs (
                seq INTEGER PRIMARY KEY AUTOINCREMENT,
                job_id TEXT NOT NULL UNIQUE,
                process_id TEXT NOT NULL,
                status TEXT NOT NULL,
                inputs TEXT NOT NULL,
                progress REAL NOT NULL DEFAULT 0,
                message TEXT NOT NULL DEFAULT '',
                created REAL NOT NULL,
                updated REAL NOT NULL,
                started REAL,
                finished REAL,
                attempts INTEGER NOT NULL DEFAULT 0,
                max_attempts INTEGER NOT NULL,
                time_limit_s REAL NOT NULL,
                lease_token TEXT,
                lease_expires REAL,
                worker_id TEXT,
                attempt_started REAL,
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
                data BLOB NOT NULL,
                ord INTEGER NOT NULL DEFAULT 0,
                PRIMARY KEY (job_id, name)
            )""",
            """CREATE TABLE workers (
                worker_id TEXT PRIMARY KEY,
                host TEXT NOT NULL,
                pid INTEGER NOT NULL,
                started REAL NOT NULL,
                heartbeat REAL NOT NULL
            )""",
        ),
    ),
)

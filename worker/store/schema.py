"""The job store's schema, as an ordered list of migrations.

Each migration runs once, in order, inside the transaction that records its version in
``schema_version``; a store created by an older dexlab is migrated forward on start-up,
never dropped.  Append new migrations; never edit an applied one.  ``{seq_pk}``,
``{blob}``, ``{float}`` and ``{bigint}`` are filled in with each database's type
names.  A migration that moves data runs its statements, then the store's data step
for that version (:meth:`worker.store.sql.SqlJobStore._migrate_data`), in the same
transaction.
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
    (
        3,
        # Artifacts leave the job row's transaction: their bytes live outside the
        # database (embedded: files) or in ~1 MiB chunks (PostgreSQL), one folder or
        # chunk set per attempt; the index row points at the attempt that committed.
        # The data step moves the old BLOBs out, drops the old table, and recomputes
        # the idempotency hashes in their canonical form (worker.request_hash).
        (
            """CREATE TABLE artifact_index (
                job_id TEXT NOT NULL REFERENCES jobs (job_id) ON DELETE CASCADE,
                name TEXT NOT NULL,
                media_type TEXT NOT NULL,
                title TEXT NOT NULL DEFAULT '',
                size {bigint} NOT NULL,
                ord INTEGER NOT NULL DEFAULT 0,
                attempt INTEGER NOT NULL,
                etag TEXT NOT NULL,
                PRIMARY KEY (job_id, name)
            )""",
            """CREATE TABLE artifact_chunks (
                job_id TEXT NOT NULL,
                attempt INTEGER NOT NULL,
                name TEXT NOT NULL,
                chunk INTEGER NOT NULL,
                data {blob} NOT NULL,
                PRIMARY KEY (job_id, attempt, name, chunk)
            )""",
        ),
    ),
    (
        4,
        # OGC API - Processes: how the client asked for the results (response form,
        # outputs, transmission modes) and where to send callbacks, kept with the job;
        # `callbacks_open` marks jobs whose callbacks may still become due.  Each due
        # callback is a row, claimed by one sender at a time under a lease.
        (
            "ALTER TABLE jobs ADD COLUMN presentation TEXT",
            "ALTER TABLE jobs ADD COLUMN subscriber TEXT",
            "ALTER TABLE jobs ADD COLUMN callbacks_open INTEGER NOT NULL DEFAULT 0",
            "CREATE INDEX jobs_callbacks_open ON jobs (callbacks_open, seq)",
            "CREATE INDEX jobs_created ON jobs (created)",
            """CREATE TABLE callbacks (
                job_id TEXT NOT NULL REFERENCES jobs (job_id) ON DELETE CASCADE,
                event TEXT NOT NULL,
                uri TEXT NOT NULL,
                attempts INTEGER NOT NULL DEFAULT 0,
                next_try {float} NOT NULL,
                claim_token TEXT,
                claim_until {float},
                delivered {float},
                gave_up {float},
                PRIMARY KEY (job_id, event)
            )""",
            "CREATE INDEX callbacks_due ON callbacks (next_try)",
        ),
    ),
    (
        5,
        # Many users on one service.  Each job names its `owner` (the API key that
        # created it; '' = anonymous, the open service's one owner).  Idempotency keys
        # become unique per owner: SQLite cannot drop the old column-level UNIQUE
        # without rebuilding `jobs` (and with foreign keys on, dropping the old table
        # would cascade into artifacts and callbacks), so the keys move to a new column
        # with a unique (owner, key) index and the old column stays, always NULL.
        # `api_keys` holds each key's SHA-256 (never its secret); `key_id` changes when
        # a secret is replaced, ending the sessions that name it.  `service_secrets`
        # holds what every replica must share (the session-signing secret).
        (
            "ALTER TABLE jobs ADD COLUMN owner TEXT NOT NULL DEFAULT ''",
            "ALTER TABLE jobs ADD COLUMN idempotency TEXT",
            "UPDATE jobs SET idempotency = idempotency_key, idempotency_key = NULL "
            "WHERE idempotency_key IS NOT NULL",
            "CREATE UNIQUE INDEX jobs_owner_idempotency ON jobs (owner, idempotency)",
            "CREATE INDEX jobs_owner_seq ON jobs (owner, seq)",
            """CREATE TABLE api_keys (
                name TEXT PRIMARY KEY,
                key_id TEXT NOT NULL UNIQUE,
                secret_hash TEXT NOT NULL UNIQUE,
                admin INTEGER NOT NULL DEFAULT 0,
                created {float} NOT NULL,
                revoked {float},
                last_used {float}
            )""",
            """CREATE TABLE service_secrets (
                name TEXT PRIMARY KEY,
                value TEXT NOT NULL
            )""",
        ),
    ),
    (
        6,
        # Running counts of job events for the metrics (worker.store.tallies), added to
        # in the transaction of each event: submitted, attempts, retries, finished by
        # status, and the duration and queue-wait histograms' buckets (`count` events
        # in the bucket, `total` their seconds).  They start at zero here.
        (
            """CREATE TABLE job_tallies (
                process_id TEXT NOT NULL,
                tally TEXT NOT NULL,
                label TEXT NOT NULL,
                count {bigint} NOT NULL,
                total {float} NOT NULL,
                PRIMARY KEY (process_id, tally, label)
            )""",
        ),
    ),
    (
        7,
        # Sharing one service: quotas, fair claims, retention (worker.store.quotas,
        # .scheduling, .retention).  Each job records whether it is `cheap` (within its
        # process's sync_cost_limit), the `parent_id` of work a job makes for itself
        # (quotas count jobs without one), its `retention_s` once finished, and when it
        # `expires` (set as it finishes; jobs finished before this migration keep 7
        # days).  `job_owners` holds, per owner, when a claim last took one of its jobs
        # (the round-robin order) and its submission token bucket.  `expired_jobs` holds
        # the tombstones of deleted jobs (410 until `forget`, then 404).
        (
            "ALTER TABLE jobs ADD COLUMN cheap INTEGER NOT NULL DEFAULT 0",
            "ALTER TABLE jobs ADD COLUMN parent_id TEXT",
            "ALTER TABLE jobs ADD COLUMN retention_s {float} NOT NULL DEFAULT 604800",
            "ALTER TABLE jobs ADD COLUMN expires {float}",
            "UPDATE jobs SET expires = finished + retention_s WHERE finished IS NOT NULL",
            "CREATE INDEX jobs_expires ON jobs (expires)",
            "CREATE INDEX jobs_owner_queue ON jobs (owner, status, seq)",
            "CREATE INDEX jobs_owner_cheap_queue ON jobs (owner, status, cheap, seq)",
            """CREATE TABLE job_owners (
                owner TEXT PRIMARY KEY,
                last_claim {float} NOT NULL DEFAULT 0,
                tokens {float},
                refilled {float}
            )""",
            "INSERT INTO job_owners (owner) SELECT DISTINCT owner FROM jobs",
            """CREATE TABLE expired_jobs (
                job_id TEXT PRIMARY KEY,
                owner TEXT NOT NULL,
                expired {float} NOT NULL,
                forget {float} NOT NULL
            )""",
            "CREATE INDEX expired_jobs_forget ON expired_jobs (forget)",
        ),
    ),
    (
        8,
        # Jobs that fan out (worker.store.fan_out): a parent's `phase` (NULL, 'waiting'
        # while its children run, 'assembling' once they all ended), how many children
        # it has and how many ended (and failed), and whether it accepts a partial result.
        (
            "ALTER TABLE jobs ADD COLUMN phase TEXT",
            "ALTER TABLE jobs ADD COLUMN children_total INTEGER",
            "ALTER TABLE jobs ADD COLUMN children_done INTEGER NOT NULL DEFAULT 0",
            "ALTER TABLE jobs ADD COLUMN children_failed INTEGER NOT NULL DEFAULT 0",
            "ALTER TABLE jobs ADD COLUMN partial_ok INTEGER NOT NULL DEFAULT 0",
            "CREATE INDEX jobs_parent ON jobs (parent_id, seq)",
        ),
    ),
    (
        9,
        # Reuse (worker.store.reuse): each job's `result_key` (worker.provenance.build),
        # whether another owner may reuse its result (`shareable`), whether it may be
        # reused at all (`reusable`: an admin's invalidation clears it), and, for a job
        # created by reuse, the job that computed its result (`reused_from`) and whether
        # that job was this job's owner's (`reused_own`); the scope its submission
        # asked reuse in (`reuse_scope`: 'owner', 'all', NULL: none), which a design
        # study's chunks inherit.  An index row's `holder` is the job whose stored bytes
        # it reads (NULL: its own).
        (
            "ALTER TABLE jobs ADD COLUMN result_key TEXT",
            "ALTER TABLE jobs ADD COLUMN shareable INTEGER NOT NULL DEFAULT 1",
            "ALTER TABLE jobs ADD COLUMN reusable INTEGER NOT NULL DEFAULT 1",
            "ALTER TABLE jobs ADD COLUMN reused_from TEXT",
            "ALTER TABLE jobs ADD COLUMN reused_own INTEGER NOT NULL DEFAULT 0",
            "ALTER TABLE jobs ADD COLUMN reuse_scope TEXT",
            "CREATE INDEX jobs_result_key ON jobs (result_key, status, seq)",
            "ALTER TABLE artifact_index ADD COLUMN holder TEXT",
            "CREATE INDEX artifact_index_holder ON artifact_index (holder)",
        ),
    ),
)

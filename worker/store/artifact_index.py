"""Artifacts in the job store: the index rows, their bytes, and the fenced completion.

A job's artifacts are written before the transaction that completes it, each attempt
to its own place (embedded: a folder of files; PostgreSQL: ~1 MiB chunk rows, one short
transaction each), so no transaction ever holds a blob.  The completing transaction is
fenced by the lease token and points the index at that attempt; a stale attempt's
bytes can never replace the committed ones, and are removed.  Reads stream chunk by
chunk.
"""

from __future__ import annotations

import hashlib
import json
import logging
import time
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

from worker.contract import Artifact, ArtifactInfo, JobStatus
from worker.request_hash import request_hash
from worker.store.artifact_files import checked_name
from worker.store.connector import Conn, SqlConnector
from worker.store.records import StoredArtifact
from worker.store.retry import retrying

__all__ = ["ArtifactIndex"]

log = logging.getLogger("dexlab.store")

_RUNNING = JobStatus.RUNNING.value
_SUCCESSFUL = JobStatus.SUCCESSFUL.value


class ArtifactIndex(SqlConnector):
    """The artifact half of :class:`worker.store.sql.SqlJobStore`."""

    # -- bytes no index row points at ------------------------------------------------
    def _discard_artifact_data(self, job_id: str, keep_attempt: int | None = None) -> None:
        """Best-effort clean-up of bytes no index row points at (logged, never raised:
        what is left is found again by the next clean-up of this job)."""
        try:
            held = self._held_attempt(job_id)  # bytes other jobs' rows read stay
            self._drop_artifact_data(job_id, held if keep_attempt is None else keep_attempt)
        except Exception:
            log.warning("could not remove unused artifact data of job %s", job_id, exc_info=True)

    # -- completion ---------------------------------------------------------------------
    @retrying
    def complete(
        self,
        job_id: str,
        lease_token: str,
        result: Mapping[str, Any],
        artifacts: Sequence[Artifact],
    ) -> bool:
        """Store the artifacts' bytes, then, in one short fenced transaction, the result,
        the index and the status.  False (and this attempt's bytes removed) if the
        attempt no longer owns the job; True again if this call's own earlier try
        committed."""
        payload = json.dumps(result, allow_nan=False)
        names = [checked_name(a.name) for a in artifacts]
        if len(set(names)) != len(names):
            raise ValueError(f"job {job_id} produced two artifacts with one name: {names}")
        attempt: int | None = None
        if artifacts:  # their bytes go first, under this attempt's number
            stored = self._store_bytes(job_id, lease_token, artifacts)
            if isinstance(stored, bool):
                return stored
            attempt = stored
        quick, committed = self._quick_complete(job_id, lease_token, payload, artifacts)
        if quick is not None:
            return self._after_commit(job_id, quick, attempt if committed is None else committed)
        now = time.time()
        with self._batch() as conn:
            row = self._one(
                conn,
                "SELECT status, process_id, started, attempts, parent_id FROM jobs "
                f"WHERE job_id = ? AND lease_token = ?{self.lock_clause}",
                (job_id, lease_token),
            )
            owner = row is not None and row["status"] in (_RUNNING, _SUCCESSFUL)
            if owner and row["status"] == _RUNNING:
                attempt = int(row["attempts"])
                self._index(conn, job_id, attempt, artifacts)
                # The token stays on the row so a retried call recognises its commit.
                self._exec(
                    conn,
                    "UPDATE jobs SET result = ?, status = ?, progress = 100, finished = ?, "
                    "updated = ?, expires = ? + retention_s, message = 'finished', "
                    "lease_expires = NULL WHERE job_id = ?",
                    (payload, _SUCCESSFUL, now, now, now, job_id),
                )
                self._tally_finish(conn, row, JobStatus.SUCCESSFUL, now)
                if row["parent_id"] is not None:
                    self._child_ended(conn, job_id, JobStatus.SUCCESSFUL, None, now)
        return self._after_commit(job_id, owner, attempt)

    def _quick_complete(
        self, job_id: str, lease_token: str, payload: str, artifacts: Sequence[Artifact]
    ) -> tuple[bool | None, int | None]:
        """A completion in one statement where the dialect has one
        (:mod:`worker.store.postgres_quick`): ``(outcome, attempt)``, where outcome None
        means "take the general path"."""
        return None, None

    def _after_commit(self, job_id: str, owner: bool, attempt: int | None) -> bool:
        """Tidy the bytes after a completion's commit: this attempt's if it no longer
        owned the job, earlier attempts' if it succeeded."""
        if not owner:
            if attempt is not None:
                self._discard_attempt(job_id, attempt)
            return False
        if attempt is not None and attempt > 1:  # earlier attempts may have left bytes
            self._discard_artifact_data(job_id, keep_attempt=attempt)
        return True

    def _store_bytes(
        self, job_id: str, lease_token: str, artifacts: Sequence[Artifact]
    ) -> int | bool:
        """Store the artifacts' bytes under the attempt's number, before its commit: the
        number, or what :meth:`complete` answers now (False: the attempt no longer owns
        the job; True: this call's own earlier try committed)."""
        row = self._one(
            self._conn(),
            "SELECT status, attempts FROM jobs WHERE job_id = ? AND lease_token = ?",
            (job_id, lease_token),
        )
        if row is None or row["status"] not in (_RUNNING, _SUCCESSFUL):
            return False
        if row["status"] == _SUCCESSFUL:
            return True
        attempt = int(row["attempts"])
        for artifact in artifacts:
            if not self._put_artifact_data(
                job_id, attempt, artifact.name, artifact.data, lease_token=lease_token
            ):
                log.warning(
                    "job %s: attempt %d lost its lease while storing results", job_id, attempt
                )
                self._discard_attempt(job_id, attempt)
                return False
        return attempt

    def _index(self, conn: Conn, job_id: str, attempt: int, artifacts: Sequence[Artifact]) -> None:
        """The index rows of a succeeding attempt's artifacts (a running job has none:
        they come with its success)."""
        if not artifacts:
            return
        conn.cursor().executemany(
            self._sql(
                "INSERT INTO artifact_index (job_id, name, media_type, title, size, "
                "ord, attempt, etag) VALUES (?, ?, ?, ?, ?, ?, ?, ?)"
            ),
            [
                (job_id, a.name, a.media_type, a.title, len(a.data), i, attempt,
                 hashlib.sha256(a.data).hexdigest())
                for i, a in enumerate(artifacts)
            ],
        )  # fmt: skip

    def _discard_attempt(self, job_id: str, attempt: int) -> None:
        """Remove one attempt's bytes unless the index points at them."""
        row = self._one(
            self._conn(),
            "SELECT 1 AS x FROM artifact_index WHERE job_id = ? AND attempt = ?",
            (job_id, attempt),
        )
        if row is None:
            self._discard_artifact_data(job_id, keep_attempt=self._committed_attempt(job_id))

    def _committed_attempt(self, job_id: str) -> int | None:
        row = self._one(
            self._conn(),
            "SELECT MAX(attempt) AS a FROM artifact_index WHERE job_id = ?",
            (job_id,),
        )
        return None if row is None or row["a"] is None else int(row["a"])

    # -- reading ------------------------------------------------------------------------
    def _artifact_rows(self, conn: Conn, job_id: str) -> list[StoredArtifact]:
        rows = self._all(
            conn,
            "SELECT name, media_type, size, title, attempt, etag, "
            "COALESCE(holder, job_id) AS holder FROM artifact_index "
            "WHERE job_id = ? ORDER BY ord",
            (job_id,),
        )
        return [
            StoredArtifact(
                ArtifactInfo(r["name"], r["media_type"], int(r["size"]), r["title"]),
                r["attempt"],
                r["etag"],
                r["holder"],
            )
            for r in rows
        ]

    @retrying
    def artifact(self, job_id: str, name: str) -> StoredArtifact | None:
        """A successful job's artifact by name (its metadata; read it with
        :meth:`artifact_chunks`)."""
        for stored in self._artifact_rows(self._conn(), job_id):
            if stored.info.name == name:
                return stored
        return None

    def artifact_chunks(self, job_id: str, stored: StoredArtifact) -> Iterator[bytes]:
        """The artifact's bytes, about 1 MiB at a time."""
        return self._artifact_data(stored.holder or job_id, stored.attempt, stored.info.name)

    def get_artifact(self, job_id: str, name: str) -> Artifact | None:
        """The whole artifact in memory (for tests and small files; the API streams)."""
        stored = self.artifact(job_id, name)
        if stored is None:
            return None
        data = b"".join(self.artifact_chunks(job_id, stored))
        return Artifact(stored.info.name, stored.info.media_type, data, stored.info.title)

    # -- migration ----------------------------------------------------------------------
    def _migrate_data(self, conn: Conn, version: int) -> None:
        """The data step of a migration, in its transaction (see worker.store.schema)."""
        if version != 3:
            return
        rows = self._all(
            conn,
            "SELECT a.job_id, a.name, a.media_type, a.title, a.data, a.ord, j.attempts "
            "FROM artifacts a JOIN jobs j ON j.job_id = a.job_id",
        )
        for r in rows:
            data = bytes(r["data"])
            attempt = max(1, int(r["attempts"]))
            self._put_artifact_data(r["job_id"], attempt, r["name"], data, conn=conn)
            self._exec(
                conn,
                "INSERT INTO artifact_index (job_id, name, media_type, title, size, ord, "
                "attempt, etag) VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    r["job_id"],
                    r["name"],
                    r["media_type"],
                    r["title"],
                    len(data),
                    r["ord"],
                    attempt,
                    hashlib.sha256(data).hexdigest(),
                ),
            )
        self._exec(conn, "DROP TABLE artifacts")
        for r in self._all(
            conn,
            "SELECT job_id, process_id, inputs FROM jobs WHERE idempotency_key IS NOT NULL",
        ):
            self._exec(
                conn,
                "UPDATE jobs SET request_hash = ? WHERE job_id = ?",
                (request_hash(r["process_id"], json.loads(r["inputs"])), r["job_id"]),
            )

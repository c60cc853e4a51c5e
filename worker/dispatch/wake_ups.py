"""Wake-ups of the local pool: an idle pool process starts a queued job at once.

The local pool's processes take work by claiming it from the store, which stays the
truth.  Rather than polling the store often, an idle process sleeps on its pool's
wake-up socket: a Unix datagram socket that the pool's supervisor binds in the store's
wake-up directory (:func:`wake_up_dir`: ``<data dir>/jobs.db-wake/<pid>-<tag>.sock``)
and hands to every process of the pool.  Whoever queues jobs sends every pool of the
store on the machine one datagram, a hint holding how many jobs were queued
(:class:`WakeUpSender`): the API's :class:`~worker.dispatch.LocalDispatch` for a
submission, a pool process for a study's chunks or a study queued to assemble, a
supervisor for the jobs of a process that died.

- One datagram wakes one idle process (epoll's ``EPOLLEXCLUSIVE`` on Linux; elsewhere
  each idle process of the pool wakes and one of them reads it); a busy process takes
  none.
- The woken process claims a job; when the hints it holds announced more jobs than it
  took, it passes the rest on to its pool in one datagram
  (:meth:`WakeUpListener.pass_on`), so a study's chunks wake the idle processes one
  after another, as fast as the store serialises their claims.
- A process that finds nothing to claim takes the hints that came in meanwhile and, if
  there were any, claims once more (they may announce jobs queued after its claim);
  then it drops them, their jobs being taken.  Hints left from a burst cost one claim.
- A hint is only a hint.  One lost (a socket's queue full, a process dying with it, a
  pool started later, the directory removed) costs a wait of at most ``poll_seconds``:
  every idle process still claims that often, as a safety net.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import logging
import os
import select
import selectors
import socket
import stat
import sys
import tempfile
import time
import uuid
from collections.abc import Sequence
from pathlib import Path

__all__ = ["PoolWakeUps", "WakeUpListener", "WakeUpSender", "wake_up_dir"]

log = logging.getLogger("dexlab.pool")

#: The longest socket path used (``sun_path`` holds 108 bytes on Linux, 104 on BSDs,
#: with the final NUL).
MAX_SOCKET_PATH = 103
#: The longest socket name in the directory: ``<pid>-<8 hex>.sock``.
MAX_SOCKET_NAME = 21
#: The most jobs one hint announces.
MAX_HINT = 1 << 30
_SUFFIX = ".sock"


def wake_up_dir(store_url: str) -> Path | None:
    """The directory where the local pools of the store at ``store_url`` bind their
    wake-up sockets, the same for every process of the machine that uses that store:
    beside a SQLite file (``jobs.db-wake``), else (another store, or a path too long
    for a socket) ``dexlab-wake-<hash>`` in the temporary directory.  None where the
    system has no Unix sockets."""
    if not hasattr(socket, "AF_UNIX"):
        return None
    prefix = "sqlite:///"
    key = store_url
    if store_url.startswith(prefix):
        database = Path(os.path.realpath(store_url[len(prefix) :]))
        beside = database.with_name(database.name + "-wake")
        if len(os.fsencode(beside)) + 1 + MAX_SOCKET_NAME <= MAX_SOCKET_PATH:
            return beside
        key = str(database)
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    return Path(tempfile.gettempdir()) / f"dexlab-wake-{digest}"


def _hint(count: int) -> bytes:
    return str(max(1, min(count, MAX_HINT))).encode()


def _count(payload: bytes) -> int:
    """The jobs a datagram announces (a malformed one announces one)."""
    try:
        return max(1, min(int(payload), MAX_HINT))
    except ValueError:
        return 1


class WakeUpSender:
    """Tells the local pools of a store on this machine that jobs were queued.  Safe to
    use from several threads."""

    def __init__(self, directory: Path | None) -> None:
        self.directory = directory
        self._sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM) if directory else None
        if self._sock is not None:
            self._sock.setblocking(False)

    def wake(self, jobs: int = 1) -> int:
        """Send every pool one hint that ``jobs`` jobs were queued; how many pools it
        reached.  Never raises: a pool gone, or one whose queue of hints is full
        (its processes are all busy, or awake already), is skipped."""
        if self._sock is None or self.directory is None or jobs < 1:
            return 0
        try:
            names = [n for n in os.listdir(self.directory) if n.endswith(_SUFFIX)]
        except OSError:  # no pool has bound a socket yet
            return 0
        payload = _hint(jobs)
        reached = 0
        for name in names:
            try:
                self._sock.sendto(payload, os.fsencode(self.directory / name))
                reached += 1
            except OSError:  # ECONNREFUSED, ENOENT (a pool gone), EAGAIN (queue full)
                continue
        return reached

    def wake_for(self, job_ids: Sequence[str]) -> None:
        """:meth:`wake` for the jobs ``job_ids`` (a pool process's queued chunks, or a
        study queued to assemble)."""
        self.wake(len(job_ids))

    def close(self) -> None:
        if self._sock is not None:
            self._sock.close()


class PoolWakeUps:
    """A pool's wake-up socket: bound by its supervisor in the wake-up directory,
    handed to each of its processes (a spawned process gets it as an argument), and
    removed when the pool stops."""

    def __init__(self, sock: socket.socket, path: Path) -> None:
        self.sock = sock
        self.path = path

    @classmethod
    def bind(cls, directory: Path | None) -> PoolWakeUps | None:
        """Bind a new socket in ``directory`` (made if missing; sockets left by pools
        that are gone are removed); None when it cannot be done (idle processes then
        find work by polling alone).  One in the shared temporary directory is made for
        this user alone."""
        if directory is None:
            return None
        try:
            if directory.parent == Path(tempfile.gettempdir()):
                directory.mkdir(mode=0o700, exist_ok=True)
                _check_owned(directory)
            else:
                directory.mkdir(parents=True, exist_ok=True)
            _remove_dead_sockets(directory)
            path = directory / f"{os.getpid()}-{uuid.uuid4().hex[:8]}{_SUFFIX}"
            sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
            try:
                sock.bind(os.fsencode(path))
            except OSError:
                sock.close()
                raise
        except OSError as exc:
            log.warning(
                "no wake-up socket in %s (%s): idle worker processes look for work every "
                "poll_seconds only",
                directory,
                exc,
            )
            return None
        sock.setblocking(False)
        return cls(sock, path)

    def close(self) -> None:
        """Remove the socket (its processes must have ended)."""
        with contextlib.suppress(FileNotFoundError):
            self.path.unlink()
        self.sock.close()


def _check_owned(directory: Path) -> None:
    """Refuse a directory in the shared temporary directory that is a link or another
    user's: no socket of ours goes where another user decides."""
    info = os.lstat(directory)
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid():
        raise OSError(errno.EPERM, "not a directory of this user")


def _remove_dead_sockets(directory: Path) -> None:
    """Remove the sockets no process holds any more (their pool was killed)."""
    probe = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    with probe:
        for entry in directory.glob(f"*{_SUFFIX}"):
            try:
                probe.connect(os.fsencode(entry))
            except ConnectionRefusedError:
                with contextlib.suppress(FileNotFoundError):
                    entry.unlink()
                    log.info("removed the wake-up socket %s of a pool that is gone", entry)
            except OSError:
                continue


class WakeUpListener:
    """In a pool process: waits for its pool's hints, and holds those it took until
    it claims (:meth:`pass_on`) or finds nothing to claim (:meth:`drop`)."""

    def __init__(self, sock: socket.socket) -> None:
        sock.setblocking(False)
        self._sock = sock
        self._address: bytes | str = sock.getsockname()
        self._interrupt_r, self._interrupt_w = os.pipe()
        os.set_blocking(self._interrupt_w, False)
        self._poller = _Poller(sock.fileno(), self._interrupt_r)
        #: Jobs announced by the hints this process took and has not passed on.
        self.held = 0

    def take(self) -> bool:
        """Take the hints waiting in the socket, without waiting; whether there were
        any."""
        took = False
        while True:
            try:
                payload = self._sock.recv(64)
            except (BlockingIOError, InterruptedError):
                return took
            self.held += _count(payload)
            took = True

    def wait(self, timeout_s: float) -> None:
        """Sleep until a hint comes (then hold it), :meth:`interrupt` is called, or
        ``timeout_s`` passes."""
        deadline = time.monotonic() + timeout_s
        while (left := deadline - time.monotonic()) > 0:
            ready = self._poller.poll(left)
            if self._interrupt_r in ready:
                return
            if ready and self.take():
                return
            # Another process of the pool took the hint first; sleep on.

    def pass_on(self) -> None:
        """This process claimed one job: send the pool a hint for the rest it held."""
        rest, self.held = self.held - 1, 0
        if rest > 0:
            with contextlib.suppress(OSError):
                self._sock.sendto(_hint(rest), self._address)

    def drop(self) -> None:
        """Nothing was claimable: every job the held hints announced is taken."""
        self.held = 0

    def interrupt(self) -> None:
        """Cut a :meth:`wait` short (safe in a signal handler)."""
        with contextlib.suppress(OSError):
            os.write(self._interrupt_w, b"\0")

    def close(self) -> None:
        self._poller.close()
        for fd in (self._interrupt_r, self._interrupt_w):
            with contextlib.suppress(OSError):
                os.close(fd)
        self._sock.close()


class _Poller:
    """Waits up to a timeout for either of two files to be readable.  On Linux one
    datagram wakes one of the processes waiting on the socket."""

    def __init__(self, sock_fd: int, interrupt_fd: int) -> None:
        self._epoll: select.epoll | None = None
        self._selector: selectors.BaseSelector | None = None
        if sys.platform == "linux":
            self._epoll = select.epoll()
            try:
                self._epoll.register(sock_fd, select.EPOLLIN | select.EPOLLEXCLUSIVE)
            except OSError:  # a kernel before 4.5
                self._epoll.register(sock_fd, select.EPOLLIN)
            self._epoll.register(interrupt_fd, select.EPOLLIN)
        else:
            self._selector = selectors.DefaultSelector()
            self._selector.register(sock_fd, selectors.EVENT_READ)
            self._selector.register(interrupt_fd, selectors.EVENT_READ)

    def poll(self, timeout_s: float) -> set[int]:
        """The files readable within ``timeout_s``."""
        if self._epoll is not None:
            return {fd for fd, _ in self._epoll.poll(timeout_s)}
        assert self._selector is not None
        return {key.fd for key, _ in self._selector.select(timeout_s)}

    def close(self) -> None:
        if self._epoll is not None:
            self._epoll.close()
        if self._selector is not None:
            self._selector.close()

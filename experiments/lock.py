"""One writer per results folder: an exclusive, advisory lock held while an experiment writes.

``FolderLock(folder)`` takes ``fcntl.flock`` on ``folder/.lock`` without waiting. A second
experiment started on the same folder is refused with the holder's process id and start time,
and never touches the folder (in particular it never deletes the temporaries of a live
writer). The operating system drops the lock when its holder exits, however it exits, so a
killed experiment leaves no stale lock. (``flock`` is local to one machine: two machines
writing one folder over NFS are not excluded.)
"""

from __future__ import annotations

import fcntl
import os
import socket
import time
from pathlib import Path
from types import TracebackType

LOCK_FILE = ".lock"


class FolderBusyError(RuntimeError):
    """The folder is being written by another process."""


class FolderLock:
    """``with FolderLock(folder):`` holds the folder's lock or raises :class:`FolderBusyError`."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.path = folder / LOCK_FILE
        self._handle: int | None = None

    def __enter__(self) -> FolderLock:
        self.folder.mkdir(parents=True, exist_ok=True)
        handle = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(handle, 512, 0).decode("utf-8", "replace").strip()
            os.close(handle)
            raise FolderBusyError(
                f"{self.folder} is being written by another experiment ({holder or 'unknown'}); "
                "wait for it to finish, or choose another --out"
            ) from None
        except BaseException:
            os.close(handle)
            raise
        since = time.strftime("%Y-%m-%d %H:%M:%S")
        note = f"pid {os.getpid()} on {socket.gethostname()}, since {since}"
        os.ftruncate(handle, 0)
        os.pwrite(handle, note.encode("utf-8"), 0)
        self._handle = handle
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        if self._handle is not None:
            os.ftruncate(self._handle, 0)
            fcntl.flock(self._handle, fcntl.LOCK_UN)
            os.close(self._handle)
            self._handle = None

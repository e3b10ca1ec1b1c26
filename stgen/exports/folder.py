"""Write files into a folder that stgen shares with its user, without ever losing a user's file.

stgen owns exactly the files listed in the folder's manifest
(:data:`MANIFEST_NAME`, JSON: file name -> SHA-256 of the content stgen wrote,
and the stgen version), and only while their content is still what stgen
wrote. Everything else in the folder is the user's. So:

* a file to be written that exists and is not stgen's (not in the manifest, a
  content that changed since stgen wrote it, a symbolic link, a FIFO, a
  folder) stops the run with :class:`ForeignFileError` before anything is
  written; a file whose content is already exactly what would be written is
  replaced (nothing is lost);
* files of the previous run that this run does not write (a POU renamed, the
  other determinant variant) are removed if their content is unchanged; a
  changed one is the user's now: kept, dropped from the manifest and reported
  in :attr:`FolderUpdate.kept`;
* every file is written to a temporary name in the same folder
  (:data:`TEMP_PREFIX` + its name) and renamed into place, so a file is
  either its old or its new content, never a part; before the first rename
  the manifest lists the new hashes as *pending* next to the old ones, so a
  run killed at any point (even ``kill -9``) leaves a folder the next run
  recognises as its own. Temporary files left by such a run are removed by
  the next one and reported in :attr:`FolderUpdate.recovered`;
* a run holds a lock on the folder (:data:`LOCK_NAME`, ``flock``, released by
  the kernel when the process dies); a second concurrent run refuses at once
  with :class:`FolderBusyError`, naming the first (pid and host).

Nothing is ever written through a symbolic link: renames replace a link
itself, and a link at a name to be written is not stgen's. Only the folder
itself is managed, never its sub-folders. POSIX only (``fcntl.flock``).
"""

from __future__ import annotations

import hashlib
import json
import os
import socket
import stat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable

#: The manifest: which files of the folder stgen wrote, with their SHA-256.
MANIFEST_NAME = ".stgen-manifest.json"
#: The lock file of a run in progress (removed at its end).
LOCK_NAME = ".stgen-lock"
#: Prefix of the temporary name a file is written to before it is renamed into place.
TEMP_PREFIX = ".stgen-tmp."
#: Names stgen keeps for itself in every folder it writes.
RESERVED_NAMES = (MANIFEST_NAME, LOCK_NAME)
#: A manifest larger than this is not stgen's (it lists a few dozen files).
_MANIFEST_MAX_BYTES = 1 << 20
_CHUNK = 1 << 16
#: Files named in a refusal (the rest are counted).
_LISTED = 4


class FolderError(ValueError):
    """The folder cannot be written safely; nothing was changed."""


class ForeignFileError(FolderError):
    """The run would overwrite files that are not stgen's (``paths``: path -> why)."""

    def __init__(self, reasons: dict[Path, str]) -> None:
        self.reasons = reasons
        self.path = next(iter(reasons))
        listed = "; ".join(f"{path}: {why}" for path, why in list(reasons.items())[:_LISTED])
        if len(reasons) > _LISTED:
            listed += f"; and {len(reasons) - _LISTED} more"
        super().__init__(
            f"{listed}; not overwritten, nothing written "
            f"(move {'it' if len(reasons) == 1 else 'them'} away or choose another --out folder)"
        )


class FolderBusyError(FolderError):
    """Another stgen run holds the folder's lock."""

    def __init__(self, folder: Path, holder: str) -> None:
        self.folder, self.holder = folder, holder
        super().__init__(
            f"{folder}: another stgen run is writing this folder ({holder or 'holder not yet recorded'}); "
            f"try again when it has finished"
        )


@dataclass(frozen=True)
class FolderUpdate:
    """What a run did to the folder."""

    written: list[Path] = field(default_factory=list)
    removed: list[Path] = field(default_factory=list)
    #: Files of an earlier run that are no longer written but were changed since: the user's, kept.
    kept: list[Path] = field(default_factory=list)
    #: Temporary files of an earlier run that was interrupted, removed.
    recovered: list[Path] = field(default_factory=list)

    def summary(self) -> str:
        """The removed, kept and recovered files, as one line (empty when there are none)."""
        parts = []
        if self.removed:
            parts.append(f"removed {len(self.removed)} stale: " + ", ".join(p.name for p in self.removed))
        if self.kept:
            parts.append(f"kept {len(self.kept)} changed since stgen wrote them (yours now): "
                         + ", ".join(p.name for p in self.kept))
        if self.recovered:
            parts.append(f"cleared {len(self.recovered)} unfinished file(s) of an interrupted run")
        return "; ".join(parts)


def sha256_of(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _regular_file_hash(path: Path) -> str | None:
    """SHA-256 of a regular file, never following a link nor blocking on a FIFO; ``None`` otherwise."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return None
    with os.fdopen(fd, "rb") as stream:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        digest = hashlib.sha256()
        while chunk := stream.read(_CHUNK):
            digest.update(chunk)
        return digest.hexdigest()


def _why_not_ours(path: Path, known: set[str], new_hash: str | None) -> str | None:
    """Why the existing ``path`` is not stgen's to replace, or ``None`` (missing, or stgen's)."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return None
    if stat.S_ISLNK(mode):
        return "is a symbolic link"
    if not stat.S_ISREG(mode):
        return "exists and is not a regular file"
    current = _regular_file_hash(path)
    if current is not None and (current in known or current == new_hash):
        return None
    if known:
        return "changed since stgen wrote it"
    return f"exists and was not written by stgen (not in {MANIFEST_NAME})"


def _stgen_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("stgen")
    except PackageNotFoundError:
        return "unknown"


def _fsync_folder(folder: Path) -> None:
    fd = os.open(folder, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


class _Manifest:
    """The manifest's two maps: ``files`` (name -> hash as last finished) and ``pending`` (a run's new hashes)."""

    def __init__(self, files: dict[str, str] | None = None, pending: dict[str, str] | None = None) -> None:
        self.files = dict(files or {})
        self.pending = dict(pending or {})

    @classmethod
    def read(cls, folder: Path) -> _Manifest:
        """The folder's manifest; an absent, unreadable or malformed one owns nothing."""
        path = folder / MANIFEST_NAME
        try:
            fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
        except OSError:
            return cls()
        with os.fdopen(fd, "rb") as stream:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                return cls()
            raw = stream.read(_MANIFEST_MAX_BYTES + 1)
        try:
            data = json.loads(raw.decode("utf-8")) if len(raw) <= _MANIFEST_MAX_BYTES else None
        except (UnicodeDecodeError, ValueError, RecursionError):
            data = None
        if not isinstance(data, dict) or data.get("generator") != "stgen":
            return cls()
        return cls(_name_map(data.get("files")), _name_map(data.get("pending")))

    def known(self, name: str) -> set[str]:
        """The hashes of ``name`` that are stgen's."""
        return {h for h in (self.files.get(name), self.pending.get(name)) if h}

    def names(self) -> set[str]:
        return set(self.files) | set(self.pending)

    def text(self) -> str:
        data = {"generator": "stgen", "stgen_version": _stgen_version(),
                "files": dict(sorted(self.files.items()))}
        if self.pending:
            data["pending"] = dict(sorted(self.pending.items()))
        return json.dumps(data, indent=2) + "\n"


def _name_map(value: object) -> dict[str, str]:
    if not isinstance(value, dict):
        return {}
    return {k: v for k, v in value.items() if isinstance(k, str) and isinstance(v, str) and _plain_name(k)}


def _plain_name(name: str) -> bool:
    """A file name directly in the folder, not one stgen reserves for itself."""
    return (bool(name) and name not in (".", "..") and "/" not in name and "\\" not in name and "\0" not in name
            and name not in RESERVED_NAMES and not name.startswith(TEMP_PREFIX))


def _write_new_file(path: Path, data: bytes) -> None:
    """Create ``path`` (which must not exist) with ``data``, flushed to disk."""
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o666)
    with os.fdopen(fd, "wb") as stream:
        stream.write(data)
        stream.flush()
        os.fsync(fd)


class FolderLock:
    """``flock`` on ``folder/.stgen-lock``, recording pid and host; the file is removed on release."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.path = folder / LOCK_NAME
        self._fd: int | None = None

    def acquire(self) -> None:
        import fcntl

        while True:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o666)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = _holder(fd)
                os.close(fd)
                raise FolderBusyError(self.folder, holder) from None
            try:  # the previous holder may have removed the file between our open and our flock
                same = os.stat(self.path, follow_symlinks=False).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if same:
                break
            os.close(fd)
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"pid {os.getpid()} on host {socket.gethostname()}\n".encode(), 0)
        self._fd = fd

    def release(self) -> None:
        if self._fd is None:
            return
        try:
            self.path.unlink()  # while still locked: a waiting run then sees another inode and retries
        except FileNotFoundError:
            pass
        os.close(self._fd)
        self._fd = None


def refuse_links_below(root: str | Path, folder: str | Path) -> None:
    """Raise :class:`FolderError` if ``folder`` (at or below ``root``) passes through a symbolic link below ``root``."""
    root, folder = Path(root), Path(folder)
    path = root
    for part in folder.relative_to(root).parts:
        path = path / part
        if path.is_symlink():
            raise FolderError(f"{path}: is a symbolic link; stgen does not write through links out of {root}")


def _holder(fd: int) -> str:
    """What the lock's holder recorded; it writes just after taking the lock, so wait a moment for it."""
    import time

    for _ in range(50):
        holder = os.pread(fd, 400, 0).decode("utf-8", "replace").strip()
        if holder:
            return holder
        time.sleep(0.005)
    return ""


class OwnedFolder:
    """A run's writes into one folder: lock, manifest, staged files, commit.

    Use as a context manager::

        with OwnedFolder(out) as folder:
            folder.check(["a.st", "b.csv"])          # refuse early, before long work
            folder.stage("a.st", text.encode())
            folder.stage_with("b.csv", lambda temp: write_csv(temp))
            update = folder.commit()

    Leaving the block without :meth:`commit` removes the staged temporary
    files and changes nothing else. ``inside``: a folder that ``folder`` must
    lie in without passing through a symbolic link (``stgen demo --out D``
    writes ``D/generated/nj501``).
    """

    def __init__(self, folder: str | Path, inside: str | Path | None = None) -> None:
        self.folder = Path(folder)
        self.inside = None if inside is None else Path(inside)
        self._lock = FolderLock(self.folder)
        self._manifest = _Manifest()
        self._staged: dict[str, tuple[Path, str]] = {}
        self._recovered: list[Path] = []

    def __enter__(self) -> OwnedFolder:
        if self.inside is not None:
            refuse_links_below(self.inside, self.folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self._lock.acquire()
        try:
            self._manifest = _Manifest.read(self.folder)
            self._recovered = self._clear_unfinished()
        except BaseException:
            self._lock.release()
            raise
        return self

    def __exit__(self, *exc) -> None:
        try:
            for temp, _ in self._staged.values():
                temp.unlink(missing_ok=True)
        finally:
            self._staged.clear()
            self._lock.release()

    def _clear_unfinished(self) -> list[Path]:
        """Remove the temporary files of an interrupted run (no run holds the lock but this one)."""
        cleared = []
        for entry in sorted(os.scandir(self.folder), key=lambda e: e.name):
            if entry.name.startswith(TEMP_PREFIX) and entry.is_file(follow_symlinks=False):
                os.unlink(entry.path)
                cleared.append(Path(entry.path))
        return cleared

    def check(self, names: Iterable[str], new_hashes: dict[str, str] | None = None) -> None:
        """Raise :class:`ForeignFileError` if writing ``names`` would replace a file that is not stgen's.

        ``new_hashes``: the hashes of the contents to be written, where known
        (a file that already holds exactly that content may be replaced).
        """
        new_hashes = new_hashes or {}
        reasons = {}
        for name in names:
            if not _plain_name(name):
                raise ValueError(f"{name!r}: not a plain file name stgen may write")
            why = _why_not_ours(self.folder / name, self._manifest.known(name), new_hashes.get(name))
            if why:
                reasons[self.folder / name] = why
        if reasons:
            raise ForeignFileError(reasons)

    def stage(self, name: str, data: bytes) -> None:
        """Write ``data`` to ``name``'s temporary file; it replaces ``name`` at :meth:`commit`."""
        self.stage_with(name, lambda temp: _write_new_file(temp, data))

    def stage_with(self, name: str, writer: Callable[[Path], object]) -> None:
        """Let ``writer(temp_path)`` write ``name``'s content to a temporary file (its extension kept)."""
        if not _plain_name(name):
            raise ValueError(f"{name!r}: not a plain file name stgen may write")
        temp = self.folder / (TEMP_PREFIX + name)
        temp.unlink(missing_ok=True)
        self._staged[name] = (temp, "")
        writer(temp)
        digest = _regular_file_hash(temp)
        if digest is None:
            raise FolderError(f"{temp}: the writer left no regular file")
        self._staged[name] = (temp, digest)

    def commit(self) -> FolderUpdate:
        """Put every staged file in place and remove the previous run's files that are not written now.

        Checks again (under the lock nothing of stgen's changed, but the user
        may have put a file there meanwhile) before the first rename.
        """
        staged = dict(self._staged)
        new = {name: digest for name, (_, digest) in staged.items()}
        self.check(staged, new)
        old = self._manifest
        # 1. Pending: every state a file can be in until step 4 is recognised as stgen's: its
        # content now (an earlier run's, or one an interrupted run left) or the new one.
        self._write_manifest(_Manifest(self._owned_now(old), new))
        update = FolderUpdate(recovered=self._recovered)
        # 2. The files, each renamed over its old content.
        for name, (temp, _) in staged.items():
            os.replace(temp, self.folder / name)
            update.written.append(self.folder / name)
        self._staged.clear()
        _fsync_folder(self.folder)
        # 3. The previous run's files that are not written now.
        for name in sorted(old.names() - set(new)):
            path = self.folder / name
            why = _why_not_ours(path, old.known(name), None)
            if why is None and path.exists():
                path.unlink()
                update.removed.append(path)
            elif why is not None:
                update.kept.append(path)
        # 4. Finished.
        self._write_manifest(_Manifest(new))
        self._manifest = _Manifest(new)
        return update

    def _owned_now(self, manifest: _Manifest) -> dict[str, str]:
        """Name -> hash of the files ``manifest`` owns, as they are on disk now (changed ones left out)."""
        owned = {}
        for name in manifest.names():
            digest = _regular_file_hash(self.folder / name)
            if digest is not None and digest in manifest.known(name):
                owned[name] = digest
        return owned

    def _write_manifest(self, manifest: _Manifest) -> None:
        temp = self.folder / (TEMP_PREFIX + MANIFEST_NAME)
        temp.unlink(missing_ok=True)
        _write_new_file(temp, manifest.text().encode("utf-8"))
        os.replace(temp, self.folder / MANIFEST_NAME)
        _fsync_folder(self.folder)


def write_files(files: dict[str, str | bytes], out_dir: str | Path, inside: str | Path | None = None) -> FolderUpdate:
    """Write ``{file name: text or bytes}`` into ``out_dir`` (created if missing) and remove its stale files.

    The safe way for any exporter to write a folder of generated files: see
    the module docstring. Raises :class:`ForeignFileError` (nothing written)
    when a file to be written exists and is not stgen's, :class:`FolderBusyError`
    when another run is writing the folder.
    """
    contents = {name: text.encode("utf-8") if isinstance(text, str) else text for name, text in files.items()}
    with OwnedFolder(out_dir, inside=inside) as folder:
        folder.check(contents, {name: sha256_of(data) for name, data in contents.items()})
        for name, data in contents.items():
            folder.stage(name, data)
        return folder.commit()

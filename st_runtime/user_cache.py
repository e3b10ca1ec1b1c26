"""A private per-user cache directory for what start-up would otherwise rebuild.

Two things are kept here, both keyed by a hash of everything they are built
from, so a stale entry is never found (a changed input is a new file name):
the LALR tables of the grammar (`grammar_cache`) and the parsed native
prelude (`prelude`).

Where: `$ST_RUNTIME_CACHE_DIR` when set (an empty value turns the cache
off), else `$XDG_CACHE_HOME/st_runtime` or `~/.cache/st_runtime`, else (a
read-only home) `st_runtime-<uid>` in the temp dir, if it is this user's.

Why it is safe to read back:

* the directory is used only when it belongs to the current user and no
  one else may write to it (created mode 0700; on POSIX its owner and mode
  are checked every time, and a default location must not be a symbolic
  link), never a file straight in a shared place like /tmp, where another
  user could plant one (Lark's own `cache=True` reads its pickle there);
* every entry is written whole or not at all (a temporary file in the same
  directory, then `os.replace`), so a reader never sees half a file, and a
  file that is not a regular file owned by the user is ignored;
* what is read is decoded by `loads`, a pickle reader that refuses every
  global except the classes a caller names: the grammar tables are plain
  lists, dicts and strings (no class at all), the prelude only AST nodes.
  Such a pickle can build data but never call a function, so even a forged
  entry cannot run code; at worst it is refused and the entry rebuilt;
* any failure (no home, a read-only or full disk, a foreign owner) means no
  cache: the caller builds what it needs as if the entry were missing.
"""

from __future__ import annotations

import io
import os
import pickle
import stat

#: Bumped when the layout of an entry changes.
FORMAT = "1"


def directory() -> str | None:
    """The cache directory (created if needed), or None when there is no safe one."""
    chosen = os.environ.get("ST_RUNTIME_CACHE_DIR")
    if chosen is not None:
        return _usable(chosen, follow=True) if chosen else None
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    if os.path.isabs(base) and _usable(os.path.join(base, "st_runtime"), follow=False):
        return os.path.join(base, "st_runtime")
    getuid = getattr(os, "getuid", None)
    if getuid is None:
        return None
    import tempfile  # a read-only home: a private folder of this user in the temp dir

    return _usable(os.path.join(tempfile.gettempdir(), f"st_runtime-{getuid()}"), follow=False)


def _usable(folder: str, follow: bool) -> str | None:
    """`folder`, created (mode 0700) if missing, when it is a private directory of this user.

    A default location must not be a symbolic link (`follow` False): in a
    shared temp dir another user could point one anywhere.
    """
    try:
        os.makedirs(folder, mode=0o700, exist_ok=True)
        info = os.stat(folder) if follow else os.lstat(folder)
    except OSError:
        return None
    if not stat.S_ISDIR(info.st_mode) or not _private(info):
        return None
    return folder


def read(name: str) -> bytes | None:
    """The bytes of entry `name`, or None (missing, unreadable, not private)."""
    folder = directory()
    if folder is None:
        return None
    try:
        fd = os.open(os.path.join(folder, name), os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    except OSError:
        return None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or not _private(info):
            return None
        with os.fdopen(fd, "rb", closefd=False) as handle:
            return handle.read()
    except OSError:
        return None
    finally:
        os.close(fd)


def write(name: str, data: bytes) -> bool:
    """Store entry `name` atomically; False (and nothing left behind) when it cannot."""
    folder = directory()
    if folder is None:
        return False
    import tempfile  # only when writing: start-up reads

    try:
        fd, temporary = tempfile.mkstemp(dir=folder, prefix=".tmp-")
    except OSError:
        return False
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        os.replace(temporary, os.path.join(folder, name))
        return True
    except OSError:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        return False


def dumps(value) -> bytes:
    return pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)


def loads(data: bytes, allowed: dict[tuple[str, str], type] | None = None):
    """Unpickle `data`, refusing every global not in `allowed` ((module, name) -> class).

    Raises pickle.UnpicklingError (or another Exception on damaged data).
    """
    return _Restricted(io.BytesIO(data), allowed or {}).load()


class _Restricted(pickle.Unpickler):
    def __init__(self, handle, allowed):
        super().__init__(handle)
        self.allowed = allowed

    def find_class(self, module, name):
        try:
            return self.allowed[(module, name)]
        except KeyError:
            raise pickle.UnpicklingError(f"refused global {module}.{name}") from None


def _private(info: os.stat_result) -> bool:
    """Owned by this user and writable by no one else (POSIX); always True elsewhere."""
    getuid = getattr(os, "getuid", None)
    if getuid is None:
        return True
    return info.st_uid == getuid() and not info.st_mode & (stat.S_IWGRP | stat.S_IWOTH)

"""Read an input file safely: only a regular file, and only up to a size limit.

Opening a FIFO for reading blocks until a writer comes, and reading a device
such as ``/dev/zero`` never ends (issue 9: ``stgen check fifo.st`` hung
forever, ``--config /dev/zero`` read 3.7 GB and ended in MemoryError). Every
input file of the tools (ST sources, ``--axes``, the platform TOML) goes
through :func:`read_bounded`: it opens without blocking, refuses anything but
a regular file (a symbolic link counts as what it points to) and reads at most
the limit.
"""

from __future__ import annotations

import os
import stat

#: Largest ST source file read (the largest generated POU is about 0.3 MB).
MAX_SOURCE_BYTES = 16 * 1024 * 1024
#: Largest TOML file read (a platform or axes file is a few kB).
MAX_TOML_BYTES = 1024 * 1024

_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
          (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISSOCK, "a socket"))


class InputFileError(OSError):
    """A file that is not read: ``reason`` says why (no path in it)."""

    def __init__(self, path: str, reason: str) -> None:
        super().__init__(reason)
        self.path, self.reason = path, reason

    def __str__(self) -> str:
        return f"'{self.path}': {self.reason}"


def kind_of(mode: int) -> str:
    """What a non-regular file is, in words."""
    for test, words in _KINDS:
        if test(mode):
            return words
    return "not a regular file"


def read_bounded(path: str | os.PathLike, limit: int) -> bytes:
    """The bytes of the regular file ``path``; :class:`InputFileError` if it is none or exceeds ``limit``."""
    name = os.fspath(path)
    try:
        fd = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise InputFileError(name, f"cannot read: {exc.strerror or type(exc).__name__}") from None
    with os.fdopen(fd, "rb") as stream:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputFileError(name, f"is {kind_of(info.st_mode)}, not a regular file")
        if info.st_size > limit:
            raise InputFileError(name, f"is {info.st_size:,} bytes; the limit is {limit:,}")
        try:
            data = stream.read(limit + 1)
        except OSError as exc:
            raise InputFileError(name, f"cannot read: {exc.strerror or type(exc).__name__}") from None
    if len(data) > limit:  # it grew while being read
        raise InputFileError(name, f"is more than {limit:,} bytes, the limit")
    return data

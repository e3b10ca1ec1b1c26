"""Write an export's files into its folder, and keep the folder free of stale ones.

``stgen generate`` owns only the files it writes. A file counts as written
by stgen when its first line is one of the export's *signature lines*: the
banner of a ``.st`` file, the column header of a Sysmac Studio ``.tsv``
table, the title of the export's README. So:

* before anything is written, a file the export would overwrite but that
  does not start with a signature line (a user's own ``README.md``, say)
  stops the export with :class:`ForeignFileError`, and nothing is written;
* after writing, every other file directly in the folder that starts with a
  signature line is stale (a POU that no longer exists, a table of another
  determinant variant) and is removed;
* files that do not start with a signature line, symbolic links and
  sub-folders are never touched.

A generated file a user edited keeps its first line, so it is overwritten or
removed like any other: its banner says to edit the templates instead.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

#: Bytes read to find a file's first line (every signature line is shorter).
_FIRST_LINE_BYTES = 512


class ForeignFileError(ValueError):
    """The export would overwrite a file that stgen did not write."""

    def __init__(self, path: Path) -> None:
        self.path = path
        super().__init__(
            f"{path}: exists and was not written by stgen; not overwritten "
            f"(move it away or choose another --out folder)"
        )


@dataclass(frozen=True)
class FolderUpdate:
    """What :func:`write_files` did: the files written and the stale files removed."""

    written: list[Path] = field(default_factory=list)
    removed: list[Path] = field(default_factory=list)


def first_line(path: Path) -> str | None:
    """The first line of a regular file (``None`` for links, folders and unreadable or binary files)."""
    if path.is_symlink() or not path.is_file():
        return None
    try:
        with path.open("rb") as stream:
            head = stream.read(_FIRST_LINE_BYTES)
        return head.decode("utf-8").splitlines()[0] if head else ""
    except (OSError, UnicodeDecodeError):
        return None


def is_generated(path: Path, signatures: frozenset[str]) -> bool:
    return first_line(path) in signatures


def write_files(files: dict[str, str], out_dir: str | Path, signatures: frozenset[str]) -> FolderUpdate:
    """Write ``{file name: text}`` into ``out_dir`` (created if missing) and remove its stale files.

    Every text must start with one of ``signatures``, so the next run
    recognises it. Raises :class:`ForeignFileError` before writing anything
    when a file to be written exists without a signature line.
    """
    out = Path(out_dir)
    for name, text in files.items():
        if text.splitlines()[0] not in signatures:
            raise ValueError(f"{name}: generated text must start with a signature line")
        target = out / name
        if target.exists() or target.is_symlink():
            if not is_generated(target, signatures):
                raise ForeignFileError(target)
    out.mkdir(parents=True, exist_ok=True)
    update = FolderUpdate()
    for name, text in files.items():
        path = out / name
        path.write_text(text, encoding="utf-8")
        update.written.append(path)
    for path in sorted(out.iterdir()):
        if path.name not in files and is_generated(path, signatures):
            path.unlink()
            update.removed.append(path)
    return update

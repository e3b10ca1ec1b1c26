"""Load ST files: read, parse and check them as one program.

    result = load(["src/", "extra.st"], dialect="nj")
    if result.program is None: print(result.render())

Directories expand to the `.st` files below them, sorted by path; an entry
skipped on the way (a symbolic link to a directory, which is not followed; a
directory that cannot be read; a `.st` name that is a FIFO, a device or a
broken link) is named in a W-LOAD-005 warning with the reason.  A `.xml` file
named on its own (PLCopen TC6 XML or IEC 61131-10) is read through
`xml_reader`.  Only regular files are read, at most `MAX_SOURCE_BYTES` each
(`st_runtime.input_files`), so a FIFO or `/dev/zero` never hangs the loader.
The native prelude (`st_runtime.prelude`, parsed once per process and
dialect) is the file "<builtin>", checked with the user's files.  Unreadable
or non-UTF-8 files become diagnostics, never exceptions.
"""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass, field

from . import ast, xml_reader
from .checker import check
from .checker.limits import file_too_large
from .checker import codes as _codes  # noqa: F401  (registers E-LOAD-*)
from .diagnostics import Diagnostic, ERROR, WARNING
from .input_files import MAX_SOURCE_BYTES, InputFileError, kind_of, read_bounded
from .parser import parse
from .prelude import prelude_file
from .symbols import CheckedProgram

BUILTIN = "<builtin>"


@dataclass
class LoadResult:
    program: CheckedProgram | None          # None when any error was found
    diagnostics: list[Diagnostic] = field(default_factory=list)
    sources: dict[str, str] = field(default_factory=dict)   # path -> text

    @property
    def ok(self) -> bool:
        return self.program is not None

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.is_error]

    def render(self) -> str:
        """Every diagnostic gcc-style, with its source line and a caret."""
        return "\n".join(d.render(self.sources.get(d.pos.file)) for d in self.diagnostics)


def expand(paths: list[str]) -> tuple[list[str], list[Diagnostic]]:
    """The files named by `paths` (directories expanded), and problems found."""
    files: list[str] = []
    diagnostics: list[Diagnostic] = []
    for path in paths:
        if os.path.isdir(path):
            found: list[str] = []
            _walk(path, found, diagnostics)
            found.sort()
            if not found:
                diagnostics.append(Diagnostic("W-LOAD-004", f"directory '{path}' holds no .st file",
                                              ast.Pos(path, 0, 0), WARNING))
            files.extend(found)
        elif os.path.exists(path):
            files.append(path)
        else:
            diagnostics.append(Diagnostic("E-LOAD-001", f"no such file or directory: '{path}'",
                                          ast.Pos(path, 0, 0), ERROR))
    unique = list(dict.fromkeys(files))
    return unique, diagnostics


def _walk(folder: str, found: list[str], diagnostics: list[Diagnostic]) -> None:
    """Collect the `.st` files below `folder`; a W-LOAD-005 warning for each entry skipped."""
    def skipped(path: str, why: str) -> None:
        diagnostics.append(Diagnostic("W-LOAD-005", f"skipped '{path}': {why}", ast.Pos(path, 0, 0), WARNING))

    try:
        entries = sorted(os.scandir(folder), key=lambda e: e.name)
    except OSError as exc:
        skipped(folder, f"cannot read the directory: {exc.strerror or type(exc).__name__}")
        return
    for entry in entries:
        try:
            is_link, mode = entry.is_symlink(), os.stat(entry.path).st_mode
        except OSError:
            if entry.name.lower().endswith(".st"):
                skipped(entry.path, "a broken symbolic link")
            continue
        if stat.S_ISDIR(mode):
            if is_link:
                skipped(entry.path, "a symbolic link to a directory (not followed)")
            else:
                _walk(entry.path, found, diagnostics)
        elif entry.name.lower().endswith(".st"):
            if stat.S_ISREG(mode):
                found.append(entry.path)
            else:
                skipped(entry.path, f"{kind_of(mode)}, not a regular file")


def read_source(path: str) -> tuple[str | None, Diagnostic | None]:
    try:
        data = read_bounded(path, MAX_SOURCE_BYTES)
    except InputFileError as exc:
        return None, Diagnostic("E-LOAD-002", f"cannot read '{path}': {exc.reason}",
                                ast.Pos(path, 0, 0), ERROR)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        col = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        return None, Diagnostic("E-LOAD-003", f"'{path}' is not UTF-8 text: byte "
                                f"0x{data[exc.start]:02X} cannot be decoded; save the file as UTF-8",
                                ast.Pos(path, line, col), ERROR)
    return text, None


def parse_texts(texts: dict[str, str], dialect: str = "iec", parser_for=None):
    """Parse in-memory sources (path -> text) after the dialect's native prelude.

    Returns (prelude text, [(path, parsed file)], diagnostics), the prelude
    first as "<builtin>". A `.xml` source (PLCopen TC6 or IEC 61131-10) is
    parsed as the ST text of `xml_reader`, laid out on the XML file's lines;
    a source above the size limit is E-LIMIT-012 and not parsed.
    `parser_for(path, st_text, from_xml)` picks the parse function of a
    source (default `parse`; `stgen test` parses test files with its own).
    """
    st_of_xml, diagnostics = xml_reader.translate(texts)
    prelude, parsed, found = prelude_file(dialect)      # parsed once per process and dialect
    diagnostics.extend(found)
    files = [(BUILTIN, parsed)] if parsed is not None else []
    for path, text in texts.items():
        too_large = file_too_large(text)
        if too_large:
            diagnostics.append(Diagnostic("E-LIMIT-012", too_large, ast.Pos(path, 1, 1), ERROR))
            continue
        from_xml = path in st_of_xml
        if from_xml:
            text = st_of_xml[path]
            if text is None:  # diagnostics from the XML reader already
                continue
        parse_file = parser_for(path, text, from_xml) if parser_for is not None else parse
        parsed, found = parse_file(text, path)
        diagnostics.extend(found)
        if parsed is not None:
            files.append((path, parsed))
    return prelude, files, diagnostics


def load_texts(texts: dict[str, str], dialect: str = "iec", memory_limit: int | None = None) -> LoadResult:
    """Parse (`parse_texts`) and check in-memory sources (path -> text), with the native prelude;
    `sources` keeps the text of each, an XML file's XML."""
    prelude, parsed, diagnostics = parse_texts(texts, dialect)
    sources = {BUILTIN: prelude, **texts}
    program, found = check([file for _, file in parsed], dialect, memory_limit)
    diagnostics.extend(found)
    program.sources = {p: t for p, t in sources.items() if p != BUILTIN}
    ok = not any(d.is_error for d in diagnostics)
    return LoadResult(program if ok else None, _ordered(diagnostics, list(sources)), sources)


def load(paths: list[str], dialect: str = "iec", extra: dict[str, str] | None = None,
         memory_limit: int | None = None) -> LoadResult:
    """Read, parse and check the files and directories in `paths` as one program.

    `extra` adds in-memory sources (name -> ST text) after the files, e.g. the
    axis globals of a motion configuration (`MotionTask.globals_source()`).
    """
    names, diagnostics = expand(list(paths))
    texts: dict[str, str] = {}
    for name in names:
        text, problem = read_source(name)
        if problem is not None:
            diagnostics.append(problem)
        else:
            texts[name] = text
    texts.update(extra or {})
    result = load_texts(texts, dialect, memory_limit)
    if diagnostics:
        result.diagnostics = diagnostics + result.diagnostics
        if any(d.is_error for d in diagnostics):
            result.program = None
    return result


def _ordered(diagnostics: list[Diagnostic], paths: list[str]) -> list[Diagnostic]:
    """Diagnostics by file (in load order), then line and column."""
    rank = {p: i for i, p in enumerate(paths)}
    return sorted(diagnostics, key=lambda d: (rank.get(d.pos.file, len(rank)), d.pos.line, d.pos.col))

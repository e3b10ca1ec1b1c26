"""Load ST files: read, parse and check them as one program.

    result = load(["src/", "extra.st"], dialect="nj")
    if result.program is None: print(result.render())

Directories expand to the `.st` files below them, sorted by path; a `.xml`
file named on its own (PLCopen TC6 XML or IEC 61131-10) is read through
`xml_reader`.  The native prelude (`st_runtime.prelude`, parsed once per
process and dialect) is the file "<builtin>", checked with the user's
files.  Unreadable or non-UTF-8 files
become diagnostics, never exceptions.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from . import ast, xml_reader
from .checker import check
from .checker.limits import file_too_large
from .checker import codes as _codes  # noqa: F401  (registers E-LOAD-*)
from .diagnostics import Diagnostic, ERROR, WARNING
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
            found = sorted(
                os.path.join(root, name)
                for root, _dirs, names in os.walk(path)
                for name in names
                if name.lower().endswith(".st")
            )
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


def read_source(path: str) -> tuple[str | None, Diagnostic | None]:
    try:
        with open(path, "rb") as handle:
            data = handle.read()
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        return None, Diagnostic("E-LOAD-002", f"cannot read '{path}': {reason}",
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


def load_texts(texts: dict[str, str], dialect: str = "iec", memory_limit: int | None = None) -> LoadResult:
    """Parse and check in-memory sources (path -> text), with the native prelude.

    A `.xml` source (PLCopen TC6 or IEC 61131-10) is read as the ST text of
    `xml_reader`, laid out on the XML file's lines; `sources` keeps the XML.
    """
    sources: dict[str, str] = {}
    files: list[ast.SourceFile] = []
    st_of_xml, diagnostics = xml_reader.translate(texts)
    prelude, parsed, found = prelude_file(dialect)      # parsed once per process and dialect
    sources[BUILTIN] = prelude
    diagnostics.extend(found)
    if parsed is not None:
        files.append(parsed)
    for path, text in texts.items():
        sources[path] = text
        too_large = file_too_large(text)
        if too_large:
            diagnostics.append(Diagnostic("E-LIMIT-012", too_large, ast.Pos(path, 1, 1), ERROR))
            continue
        if path in st_of_xml:
            text = st_of_xml[path]
            if text is None:  # diagnostics from the XML reader already
                continue
        parsed, found = parse(text, path)
        diagnostics.extend(found)
        if parsed is not None:
            files.append(parsed)
    program, found = check(files, dialect, memory_limit)
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

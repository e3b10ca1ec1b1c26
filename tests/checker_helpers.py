"""Helpers for the checker tests: load ST text, find AST nodes."""

from __future__ import annotations

import dataclasses

from st_runtime import ast
from st_runtime.loader import load_texts


def load(text: str, dialect: str = "iec"):
    """(result, program) of one in-memory file named `t.st`; program may be None."""
    result = load_texts({"t.st": text}, dialect)
    return result, result.program


def checked(text: str, dialect: str = "iec"):
    result, program = load(text, dialect)
    assert program is not None, result.render()
    return program


def walk(node):
    """Every AST node below (and including) `node`, depth first, in source order."""
    stack = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, (list, tuple)):
            stack.extend(reversed(n))
            continue
        if not dataclasses.is_dataclass(n) or isinstance(n, ast.Pos):
            continue
        yield n
        children = [getattr(n, f.name) for f in dataclasses.fields(n) if f.name != "pos"]
        stack.extend(reversed(children))


def body(program, pou: str = "Main"):
    return program.pous[pou.upper()].node.body


def statement(program, index: int, pou: str = "Main"):
    return body(program, pou)[index]


def nodes(root, kind):
    return [n for n in walk(root) if isinstance(n, kind)]


def diagnostics(text: str, dialect: str = "iec") -> list[tuple[str, int, int, str]]:
    """(code, line, column, message) of every diagnostic of `text`."""
    result, _ = load(text, dialect)
    return [(d.code, d.pos.line, d.pos.col, d.message) for d in result.diagnostics]


def only(text: str, dialect: str = "iec") -> tuple[str, int, int, str]:
    """The one diagnostic of `text` (fails when there are none or several)."""
    found = diagnostics(text, dialect)
    assert len(found) == 1, found
    return found[0]


def program(decls: str, body: str) -> str:
    """`PROGRAM Main` with these declarations and this body."""
    return f"PROGRAM Main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"

"""The native prelude: the ST declarations of the native FBs and types
(TON, R_TRIG, MC_Power, AXIS_REF, ...), read once per process.

The loader owns this stage (DESIGN: "let the stage that owns the work, the
loader, prepare what the lower ones need, the native prelude, once"): it
imports the native libraries here, so they are registered before the prelude
text is built, and takes the parsed prelude from `prelude_file()`, which
parses it once per dialect (the dialect decides the pin names of the
counters, `st_runtime.dialects`), again only when the set of natives has
changed since. The AST is immutable, so every load can share it.
"""

from __future__ import annotations

import os

from . import ast, native, user_cache
# Register every native FB before the prelude is read: the standard FBs
# (TON, R_TRIG, ...) and the PLCopen motion FBs (MC_Power, ...) with AXIS_REF.
from . import motion as _motion  # noqa: F401
from . import stdlib as _stdlib  # noqa: F401
from .checker.context import BUILTIN_FILE
from .diagnostics import Diagnostic
from .parser import parse

#: Per dialect, the last prelude parsed: (its text, its AST, the diagnostics of the parse).
_cache: dict[str, tuple[str, ast.SourceFile | None, list[Diagnostic]]] = {}


def prelude_text(dialect: str = "iec") -> str:
    """The native declarations as one ST text (types first), with the dialect's pin names."""
    registered = (len(native.NATIVE_TYPE_SOURCES), tuple(native.NATIVE_FBS.items()))
    made = _texts.get(dialect)
    if made is None or made[0] != registered:
        made = _texts[dialect] = (registered, native.prelude_source(dialect))
    return made[1]


#: Per dialect, (the natives registered, the prelude text made of them): the text is
#: made again only when a native type or FB is registered (the registries only grow;
#: a class's DECLARATION and a dialect's pin names are constants).
_texts: dict[str, tuple[tuple, str]] = {}


def prelude_file(dialect: str = "iec") -> tuple[str, ast.SourceFile | None, list[Diagnostic]]:
    """(text, parsed file, parse diagnostics) of the dialect's prelude, parsed
    once per process (again only if a native was registered since)."""
    text = prelude_text(dialect)
    cached = _cache.get(dialect)
    if cached is None or cached[0] != text:
        parsed = _stored(text)
        diagnostics: list[Diagnostic] = []
        if parsed is None:
            parsed, diagnostics = parse(text, BUILTIN_FILE)
            if parsed is not None and not diagnostics:
                _store(text, parsed)
        cached = _cache[dialect] = (text, parsed, list(diagnostics))
    return cached


# ----------------------------------------------------------- across processes
# The parsed prelude is kept in the user cache (`user_cache`: a private
# directory, entries written atomically).  The entry's name is a hash of the
# prelude text and of every file that decides what the parser makes of it
# (the grammar, the parser and its lexer, the AST builder, the AST classes,
# the literal rules, this cache's format), with Lark's and Python's
# versions: after any change the name differs, so a stale AST is never
# read.  It is read back by a pickle reader that accepts no global but the
# AST classes (nothing can be called), and an entry that fails to read is
# parsed again.  Only a prelude that parsed without a diagnostic is stored.
# The checked prelude is not stored across processes: a process checks and
# compiles it once and shares it with every load (checker/prelude_base.py,
# docs/load.md), and its types and symbols would widen what the reader must
# accept far beyond the AST's node classes.

#: The files whose content decides the AST parsed from a text.
PARSER_FILES = ("grammar.lark", "parser.py", "lalr_fast.py", "grammar_cache.py", "ast_builder.py", "ast.py",
                "frozen_dataclasses.py", "literals.py", "diagnostics.py", "user_cache.py")


def _entry_name(text: str) -> str:
    import hashlib
    import sys

    import lark

    digest = hashlib.sha256()
    for part in (user_cache.FORMAT, lark.__version__, sys.version.split()[0], text):
        digest.update(part.encode("utf-8", "surrogatepass") + b"\0")
    folder = os.path.dirname(os.path.abspath(__file__))
    for name in PARSER_FILES:
        with open(os.path.join(folder, name), "rb") as handle:
            digest.update(handle.read() + b"\0")
    return f"prelude-{digest.hexdigest()[:40]}.pickle"


def _ast_classes() -> dict[tuple[str, str], type]:
    """The classes an entry may name: the AST's node classes and Pos, nothing else."""
    return {(ast.__name__, name): value for name, value in vars(ast).items()
            if isinstance(value, type) and value.__module__ == ast.__name__
            and (issubclass(value, ast.Node) or value is ast.Pos)}


def _stored(text: str) -> ast.SourceFile | None:
    try:
        data = user_cache.read(_entry_name(text))
        if data is None:
            return None
        parsed = user_cache.loads(data, _ast_classes())
    except Exception:  # no entry, or a damaged or refused one: parse again
        return None
    return parsed if isinstance(parsed, ast.SourceFile) else None


def _store(text: str, parsed: ast.SourceFile) -> None:
    try:
        data = user_cache.dumps(parsed)
        if user_cache.loads(data, _ast_classes()) == parsed:   # stored only if it reads back
            user_cache.write(_entry_name(text), data)
    except Exception:  # pickling failed, no cache: the next process parses again
        pass

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

from . import ast, native
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
    return native.prelude_source(dialect)


def prelude_file(dialect: str = "iec") -> tuple[str, ast.SourceFile | None, list[Diagnostic]]:
    """(text, parsed file, parse diagnostics) of the dialect's prelude, parsed
    once per process (again only if a native was registered since)."""
    text = prelude_text(dialect)
    cached = _cache.get(dialect)
    if cached is None or cached[0] != text:
        parsed, diagnostics = parse(text, BUILTIN_FILE)
        cached = _cache[dialect] = (text, parsed, list(diagnostics))
    return cached

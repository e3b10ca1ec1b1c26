"""Diagnostics: findings of the parser, the checker and the runtime.

A diagnostic has a stable code (`E-PARSE-001`, `E-TYPE-004`, `W-NJ-001`, ...),
a severity, a message that says what was expected and what was found, and a
position.  It renders gcc-style:

    file.st:12:5: error[E-TYPE-004]: cannot assign LREAL to INT ...
        x := y * 2.0;
        ^

The catalogue of codes with one-line explanations lives in `CODES`; every
code used anywhere must be registered there (a test enforces it).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from .ast import Pos

ERROR = "error"
WARNING = "warning"
FAULT = "fault"


@dataclass(frozen=True, slots=True)
class Diagnostic:
    code: str
    message: str
    pos: Pos
    severity: str = ERROR

    @property
    def is_error(self) -> bool:
        return self.severity != WARNING

    def header(self) -> str:
        return f"{shown(str(self.pos))}: {self.severity}[{self.code}]: {shown(self.message)}"

    def render(self, source: str | None = None) -> str:
        """The header line, then the source line and a caret when known."""
        text = self.header()
        if source is None or self.pos.line <= 0:
            return text
        lines = source.splitlines()
        if self.pos.line > len(lines):
            return text
        line = lines[self.pos.line - 1]
        caret_col = max(self.pos.col, 1)
        # Keep tabs in the caret line so the caret lines up with the (escaped) source.
        prefix = "".join(ch if ch == "\t" else " " for ch in shown(line[: caret_col - 1]))
        return f"{text}\n    {shown(line)}\n    {prefix}^"


#: Characters never echoed to a terminal: C0/C1 controls but tab (an ESC starts a
#: terminal escape sequence), DEL, and the bidirectional controls that reorder text.
_UNSAFE = re.compile("[\x00-\x08\x0a-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")


def shown(text: str) -> str:
    """`text` safe to print: each unsafe character as `\\xhh` or `\\uhhhh` (ST text is data)."""
    return _UNSAFE.sub(lambda m: f"\\x{ord(m.group()):02x}" if ord(m.group()) < 256
                       else f"\\u{ord(m.group()):04x}", text)


class DiagnosticError(Exception):
    """Raised to abandon a stage that cannot go on; carries its findings."""

    def __init__(self, diagnostics: list[Diagnostic]):
        super().__init__("\n".join(d.header() for d in diagnostics))
        self.diagnostics = diagnostics


@dataclass
class DiagnosticSink:
    """Collects diagnostics of one run, in order, without duplicates."""

    items: list[Diagnostic] = field(default_factory=list)

    def add(self, code: str, message: str, pos: Pos, severity: str = ERROR) -> None:
        diag = Diagnostic(code, message, pos, severity)
        if diag not in self.items:
            self.items.append(diag)

    def error(self, code: str, message: str, pos: Pos) -> None:
        self.add(code, message, pos, ERROR)

    def warning(self, code: str, message: str, pos: Pos) -> None:
        self.add(code, message, pos, WARNING)

    @property
    def has_errors(self) -> bool:
        return any(d.is_error for d in self.items)


# Code catalogue: code -> one-line explanation.  Stages register their codes
# here (one dict per stage keeps merge conflicts away); `all_codes()` joins them.
CODES: dict[str, str] = {}


def register(codes: dict[str, str]) -> dict[str, str]:
    for code, text in codes.items():
        if code in CODES and CODES[code] != text:
            raise ValueError(f"diagnostic code {code} registered twice")
        CODES[code] = text
    return codes

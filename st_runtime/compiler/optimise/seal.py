"""`seal`: a body reads the controller's seal once, in its prologue, not at each rest test.

The call sites of idle Execute FBs (calls.py, `NativeFB.REST`: MC_Stop, MC_Reset, ...) test
`fb._at_rest is not _ctx.seal` and note `fb._at_rest = _ctx.seal` (SP_Controller: twelve a
scan).  `ScanContext.seal` is replaced only between the programs' runs (controller.py: before
a scan's hooks when they may write, at the exit of `run` and `scan`), never while a body runs,
so a body that reads it twice or more reads it once into `_seal` at its start: the same object
at every test and note.  Only reads in the code count and change, found by Python's own
tokenizer: the text `_ctx.seal` inside a string literal (an ST STRING) is a value.
"""

from __future__ import annotations

import io
import tokenize

from ..pysrc import indentation

_READ = "_ctx.seal"


def hoist(lines: list[str], start: int) -> None:
    """`_seal = _ctx.seal` first in the function whose lines after the `def` begin at
    `lines[start]`, and `_seal` for each read, when it reads the seal twice or more."""
    if "\n".join(lines[start:]).count(_READ) < 2:
        return                  # (each read is one of these texts: fewer than two, no line to read)
    reads = {i: _reads(line) for i, line in enumerate(lines[start:], start) if _READ in line}
    if sum(len(columns) for columns in reads.values()) < 2:
        return
    for i, columns in reads.items():
        line = lines[i]
        for column in reversed(columns):
            line = line[:column] + "_seal" + line[column + len(_READ):]
        lines[i] = line
    lines.insert(start, "    _seal = " + _READ)


def _reads(line: str) -> list[int]:
    """The columns where `line` reads `_ctx.seal` as code (not inside a string literal)."""
    try:
        tokens = [t for t in tokenize.generate_tokens(io.StringIO(line.strip() + "\n").readline)
                  if t.type in (tokenize.NAME, tokenize.OP, tokenize.STRING)]
    except (tokenize.TokenError, SyntaxError):      # a line that is not a whole statement
        return []
    indent = indentation(line)
    return [indent + first.start[1] for first, dot, name in zip(tokens, tokens[1:], tokens[2:])
            if (first.string, dot.string, name.string) == ("_ctx", ".", "seal")
            and first.end == dot.start and dot.end == name.start]

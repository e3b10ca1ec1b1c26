"""`seal`: a body reads the controller's seal once, in its prologue, not at each rest test.

The call sites of idle Execute FBs (calls.py, `NativeFB.REST`: MC_Stop, MC_Reset, ...) test
`fb._at_rest is not _ctx.seal` and note `fb._at_rest = _ctx.seal` (SP_Controller: twelve a
scan).  `ScanContext.seal` is replaced only between the programs' runs (controller.py: before
a scan's hooks when they may write, at the exit of `run` and `scan`), never while a body runs,
so a body that reads it twice or more reads it once into `_seal` at its start: the same object
at every test and note.
"""

from __future__ import annotations

_READ = "_ctx.seal"


def hoist(lines: list[str], start: int) -> None:
    """`_seal = _ctx.seal` first in the function whose lines after the `def` begin at
    `lines[start]`, and `_seal` for each read, when it reads the seal twice or more."""
    if sum(line.count(_READ) for line in lines[start:]) < 2:
        return
    lines[start:] = [line.replace(_READ, "_seal") for line in lines[start:]]
    lines.insert(start, "    _seal = " + _READ)

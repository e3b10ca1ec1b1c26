"""One C call for a body's prologue: consecutive `v_X = self.v_X` loads become
`v_A, v_B, ... = _kN(self)` with `_kN = operator.attrgetter("v_A", "v_B", ...)`.

A POU body starts by copying the variables it uses into Python locals (scope.py);
the controller's program uses some 60 of them, so the copies were a tenth of
its opcodes per scan.  `attrgetter` reads the same attributes in the same order
(a located or union property runs as before), and a missing one raises the same
AttributeError before the body starts; only the interpreter's dispatch per load
goes.  Runs shorter than `MIN_RUN` stay as they are.  Switch: `Optimisations.gather`.

Off by default (issue 17): it executes fewer bytecodes but takes longer.  On
CPython 3.11 `self.v_X` is a specialised slot load (a version check and a read),
while attrgetter does a generic lookup per name through the type's method cache,
whose slot depends on the string's hash, so on PYTHONHASHSEED.  Measured side
by side (60 slotted variables, best of 7): the loads 0.43-0.50 us, attrgetter
1.03-1.77 us by seed; the FK iteration 1-2.5 us faster and the controller 4 %
faster with the loads.
"""

from __future__ import annotations

import re
from operator import attrgetter

MIN_RUN = 4

_LOAD = re.compile(r"^([A-Za-z_]\w*) = (self|_G)\.([A-Za-z_]\w*)$")


def prologue(lines: list[str], register) -> list[str]:
    """`lines` with runs of loads from one owner gathered; `register(value)` binds the getter."""
    out: list[str] = []
    run: list[tuple[str, str]] = []
    owner = None

    def flush() -> None:
        if len(run) >= MIN_RUN:
            getter = register(attrgetter(*(attr for _, attr in run)))
            out.append(f"{', '.join(name for name, _ in run)} = {getter}({owner})")
        else:
            out.extend(f"{name} = {owner}.{attr}" for name, attr in run)
        run.clear()

    for line in lines:
        match = _LOAD.match(line) if isinstance(line, str) else None
        if match is None or (run and match.group(2) != owner):
            flush()
        if match is None:
            out.append(line)
            continue
        owner = match.group(2)
        run.append((match.group(1), match.group(3)))
    flush()
    return out

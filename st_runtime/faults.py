"""Runtime faults: what an NJ controller reports as an instruction error.

Library code raises `STFault(code, message)`; the compiled code catches it
around every statement, abandons that statement (the rest of the POU goes on,
as an NJ goes on after an instruction error), and the controller records a
`FaultRecord` with the POU, file, line and scan number, then keeps scanning
unless told to stop at the first fault (`StopRun`).

Two conditions are not instruction errors and end the whole scan instead:
`ScanOverrun` (the scan's estimated NJ501 time passed the task period:
"task period exceeded"; see st_runtime/compiler/cost.py) and `StopRun` (stop_on_fault).  Neither derives from `STFault`, so
the per-statement handlers let them through.  Codes are stable strings
registered in `FAULT_CODES`.
"""

from __future__ import annotations

from dataclasses import dataclass

FAULT_CODES: dict[str, str] = {
    "F-DIV-ZERO": "integer division or MOD by zero",
    "F-INDEX": "array index out of range",
    "F-PERIOD": "task period exceeded (the scan's estimated NJ501 time passed the period)",
    "F-MATH": "math error in a standard function (e.g. SQRT of a negative value)",
    "F-CONVERT": "value cannot be converted (out of range or not finite)",
    "F-NULL-REF": "VAR_IN_OUT used before the caller passed a variable",
    "F-SUBRANGE": "a value stored in a subrange variable (INT (0..100)) lies outside its range",
}


class STFault(Exception):
    """Raised by compiled code or library code; caught by the compiled code."""

    def __init__(self, code: str, message: str, line: int | None = None, col: int | None = None):
        super().__init__(message)
        self.code = code
        self.message = message
        self.line = line  # where the fault happened, when more precise than the statement
        self.col = col


class ScanOverrun(Exception):
    """The task's estimated NJ501 time passed its limit: F-PERIOD, the task's run ends."""

    def __init__(self, where: tuple):
        super().__init__("task period exceeded")
        self.where = where  # (pou, file, line, col) of the loop (or program) that ran out


class StopRun(Exception):
    """A fault was recorded with stop_on_fault set: the run ends now."""

    def __init__(self, record: "FaultRecord"):
        super().__init__(record.render())
        self.record = record


@dataclass(frozen=True, slots=True)
class FaultRecord:
    code: str
    message: str
    pou: str
    file: str
    line: int
    col: int
    scan: int

    def render(self) -> str:
        from .diagnostics import shown

        return f"{shown(self.file)}:{self.line}:{self.col}: fault[{self.code}]: {shown(self.message)} (scan {self.scan})"

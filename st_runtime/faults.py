"""Runtime faults: what an NJ controller reports as an instruction error.

Library code raises `STFault(code, message)`; the controller catches it,
abandons the faulting statement, records a `FaultRecord` with the POU, file,
line and scan number, and goes on scanning (unless told to stop at the first
fault).  Codes are stable strings registered in `FAULT_CODES`.
"""

from __future__ import annotations

from dataclasses import dataclass

FAULT_CODES: dict[str, str] = {
    "F-DIV-ZERO": "integer division or MOD by zero",
    "F-INDEX": "array index out of range",
    "F-PERIOD": "task period exceeded (scan budget of loop iterations used up)",
    "F-MATH": "math error in a standard function (e.g. SQRT of a negative value)",
    "F-CONVERT": "value cannot be converted (out of range or not finite)",
}


class STFault(Exception):
    """Raised by compiled code or library code; caught by the controller."""

    def __init__(self, code: str, message: str, line: int | None = None):
        super().__init__(message)
        self.code = code
        self.message = message
        self.line = line  # filled in by the compiled code's fault handler when known


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
        return f"{self.file}:{self.line}:{self.col}: fault[{self.code}]: {self.message} (scan {self.scan})"

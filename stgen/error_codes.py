"""Status codes shared by the NumPy reference and the generated ST.

One table, used in two places:

* the reference returns an :class:`ErrorCode` as ``status`` (``0`` means ok);
* the templates render each member as a named ST constant
  (``ERR_SINGULAR_JACOBIAN : WORD := 16#1001;``) and the function blocks report
  it through their ``ErrorID`` output (PLCopen style: ``Error`` BOOL plus
  ``ErrorID`` WORD).

The WORD an FB reports is ``ERROR_ID_BASE + code`` for every error and
``16#0000`` for ok, so ``ErrorID`` and ``status`` always tell the same story:

======  ======================  =========  ==========================================
code    member                  ErrorID    meaning
======  ======================  =========  ==========================================
0       OK                      16#0000    converged / every leg inside its stroke
1       SINGULAR_JACOBIAN       16#1001    FK: abs(det J) <= Ktol (docs/mathematics.md section 3, step 1)
2       NOT_CONVERGED           16#1002    FK: total iteration limit reached (docs/mathematics.md section 3)
3       NON_FINITE              16#1003    a NaN or infinity appeared in the numbers
4       UNREACHABLE             16#1004    IK: a leg lies outside the stroke (docs/mathematics.md section 2)
======  ======================  =========  ==========================================

Never renumber a member: the numbers are part of the PLC interface.
"""

from __future__ import annotations

from enum import IntEnum

#: Added to a non-zero code to form the PLC ``ErrorID`` WORD.
ERROR_ID_BASE = 0x1000


class ErrorCode(IntEnum):
    """Outcome of a kinematics computation; ``0`` is success.

    Each member carries a one-line ``description`` (used for ST comments and
    messages) next to its integer value.
    """

    description: str

    def __new__(cls, value: int, description: str) -> "ErrorCode":
        member = int.__new__(cls, value)
        member._value_ = value
        member.description = description
        return member

    OK = (0, "no error")
    SINGULAR_JACOBIAN = (1, "singular Jacobian: abs(det J) <= Ktol")
    NOT_CONVERGED = (2, "Newton-Raphson did not converge within the iteration limit")
    NON_FINITE = (3, "a non-finite value (NaN or infinity) appeared")
    UNREACHABLE = (4, "a cylinder position lies outside the stroke")

    @property
    def error_id(self) -> int:
        """The WORD reported through an FB's ``ErrorID`` (0 for :attr:`OK`)."""
        return 0 if self is ErrorCode.OK else ERROR_ID_BASE + int(self)

    @property
    def st_literal(self) -> str:
        """The ErrorID as an IEC 61131-3 WORD literal, e.g. ``16#1001``."""
        return f"16#{self.error_id:04X}"

    @property
    def st_constant_name(self) -> str:
        """Name of the ST constant holding :attr:`error_id`, e.g. ``ERR_NOT_CONVERGED``."""
        return "ERR_OK" if self is ErrorCode.OK else f"ERR_{self.name}"

"""Helpers the generated Python code calls: the operations that need more
than one Python operator (IEC integer division, MOD, float32 rounding)
and the raisers of runtime faults.  (`**` is the library's EXPT.)

Everything here is bound into the namespace of the generated code under a
name starting with `_` (ST names are mangled to `v_...`, so they never meet).
"""

from __future__ import annotations

from ..faults import STFault, ScanOverrun
from ..values import real_div

# IEC store rules (REAL rounding, integer wrapping), shared with st_runtime.objects.
from ..store_rules import f32, wrap_int  # noqa: E402,F401


def idiv(a: int, b: int, where: tuple) -> int:
    """Integer `/`: truncates toward zero; division by zero is F-DIV-ZERO."""
    if b == 0:
        raise STFault("F-DIV-ZERO", "integer division by zero", where[2], where[3])
    q = a // b
    if q < 0 and q * b != a:
        q += 1
    return q


def imod(a: int, b: int, where: tuple) -> int:
    """MOD: the remainder takes the sign of the dividend (a = b*(a/b) + a MOD b)."""
    if b == 0:
        raise STFault("F-DIV-ZERO", "MOD by zero", where[2], where[3])
    r = abs(a) % abs(b)
    return -r if a < 0 else r


# Real `/` with IEEE 754 results for a zero divisor (inf, -inf, nan): the one
# implementation in values, shared with the constant folders.
rdiv = real_div


def index_fault(value: int, lo: int, hi: int, name: str, where: tuple):
    raise STFault(
        "F-INDEX",
        f"index {value} of '{name}' out of bounds {lo}..{hi}",
        where[2], where[3],
    )


def index_fault_n(values: tuple, dims: tuple, name: str, where: tuple):
    """A multi-dimensional index out of range: name the first bad one."""
    for n, (value, (lo, hi)) in enumerate(zip(values, dims), start=1):
        if not lo <= value <= hi:
            raise STFault(
                "F-INDEX",
                f"index {value} (dimension {n}) of '{name}' out of bounds {lo}..{hi}",
                where[2], where[3],
            )
    raise AssertionError("index_fault_n called with indices in range")


def overrun(where: tuple):
    raise ScanOverrun(where)


#: The ranges of a FOR of step 1 from 0 and from 1 to each end below SMALL_END, made once:
#: `FROM_1[end] == range(1, end + 1)`.  A FOR whose end is known only at run time takes its
#: range from here (statements `_for_range`), where `range()` would make one each time
#: (about 800 machine instructions in CPython 3.11: its length is computed with int objects).
#: A range is immutable, so a shared one iterates, measures and compares as a new one.
SMALL_END = 64
FROM_0 = tuple(range(0, end + 1) for end in range(SMALL_END))
FROM_1 = tuple(range(1, end + 1) for end in range(SMALL_END))


def for_range(start: int, end: int, step: int, where: tuple) -> range:
    """The iterations of FOR with a step known only at run time."""
    if step > 0:
        return range(start, end + 1, step)
    if step < 0:
        return range(start, end - 1, step)
    raise ScanOverrun(where)  # BY 0 loops forever on a PLC: period exceeded


def subrange(value: int, lo: int, hi: int) -> int:
    """A value stored in a subrange variable: F-SUBRANGE outside its limits."""
    if lo <= value <= hi:
        return value
    raise STFault("F-SUBRANGE", f"{value} is outside the subrange {lo}..{hi}")


def bound_method(instance, attr: str):
    """A method of the instance an interface variable refers to; F-NULL-REF
    when it refers to none."""
    if instance is None:
        raise STFault("F-NULL-REF", "method call through an interface variable that "
                      "refers to no instance")
    return getattr(instance, attr)


def deref(reference):
    """`r^`: what a reference refers to; F-NULL-REF for NULL."""
    if reference is None:
        raise STFault("F-NULL-REF", "dereference of NULL (the reference refers to nothing)")
    return reference


def set_bit(word: int, shift: int, width: int, value, bits: int, signed: bool) -> int:
    """`x.3 := v` / `x.%B1 := v`: the integer with `width` bits at `shift`
    replaced by v, in its type's range."""
    mask = (1 << width) - 1
    word &= (1 << bits) - 1
    word = word & ~(mask << shift) | (int(value) & mask) << shift
    if signed and word >= 1 << (bits - 1):
        word -= 1 << bits
    return word


class ArrayView:
    """An array passed to an ARRAY[*] in-out: the caller's flat list and its bounds."""

    __slots__ = ("seq", "dims")

    def __init__(self, seq: list, dims: tuple):
        self.seq = seq
        self.dims = dims

    def offset(self, indices: tuple, name: str, where) -> int:
        flat = 0
        for i, (lo, hi) in zip(indices, self.dims):
            if not lo <= i <= hi:
                return index_fault_n(indices, self.dims, name, where) if len(indices) > 1 \
                    else index_fault(i, lo, hi, name, where)
            flat = flat * (hi - lo + 1) + (i - lo)
        return flat

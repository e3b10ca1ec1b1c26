"""Checker details that mutation testing found unchecked (issue 16).

The standard functions' signatures are built at import time
(`builtins._table`), so a changed builder is never seen by the programs the
checker tests check: the table is built afresh here and compared with the
signatures of IEC 61131-3 (3rd ed. tables 22-29: formal parameter names IN,
IN1, IN2, MN, MX, G, K, N, L, P; `T` marks the generic type the result takes).
"""

from st_runtime.checker import builtins

G = True     # generic: every generic argument and the result share one type T


def sig(*params, result="T", extensible=False):
    return tuple((name, category, generic) for name, category, generic in params), result, extensible


EXPECTED = {
    "ABS": sig(("IN", "ANY_NUM", G)),
    **{name: sig(("IN", "ANY_REAL", G))
       for name in ("SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN")},
    "EXPT": sig(("IN1", "ANY_REAL", G), ("IN2", "ANY_NUM", False)),
    "MIN": sig(("IN1", "ANY_ELEMENTARY", G), ("IN2", "ANY_ELEMENTARY", G), extensible=True),
    "MAX": sig(("IN1", "ANY_ELEMENTARY", G), ("IN2", "ANY_ELEMENTARY", G), extensible=True),
    "LIMIT": sig(("MN", "ANY_ELEMENTARY", G), ("IN", "ANY_ELEMENTARY", G), ("MX", "ANY_ELEMENTARY", G)),
    "SEL": sig(("G", "BOOL", False), ("IN0", "ANY", G), ("IN1", "ANY", G)),
    "MUX": sig(("K", "ANY_INT", False), ("IN0", "ANY", G), ("IN1", "ANY", G), extensible=True),
    "MOVE": sig(("IN", "ANY", G)),
    "TRUNC": sig(("IN", "ANY_REAL", False), result="ANY_INT"),
    **{name: sig(("IN", "ANY_BITS", G), ("N", "ANY_INT", False)) for name in ("SHL", "SHR", "ROL", "ROR")},
    **{name: sig(("IN1", "ANY_BIT", G), ("IN2", "ANY_BIT", G), extensible=True) for name in ("AND", "OR", "XOR")},
    "NOT": sig(("IN", "ANY_BIT", G)),
    "LEN": sig(("IN", "STRING", False), result="INT"),
    "CONCAT": sig(("IN1", "STRING", False), ("IN2", "STRING", False), result="STRING", extensible=True),
    "LEFT": sig(("IN", "STRING", False), ("L", "ANY_INT", False), result="STRING"),
    "RIGHT": sig(("IN", "STRING", False), ("L", "ANY_INT", False), result="STRING"),
    "MID": sig(("IN", "STRING", False), ("L", "ANY_INT", False), ("P", "ANY_INT", False), result="STRING"),
    "INSERT": sig(("IN1", "STRING", False), ("IN2", "STRING", False), ("P", "ANY_INT", False), result="STRING"),
    "DELETE": sig(("IN", "STRING", False), ("L", "ANY_INT", False), ("P", "ANY_INT", False), result="STRING"),
    "REPLACE": sig(("IN1", "STRING", False), ("IN2", "STRING", False), ("L", "ANY_INT", False),
                   ("P", "ANY_INT", False), result="STRING"),
    "FIND": sig(("IN1", "STRING", False), ("IN2", "STRING", False), result="INT"),
}

# BCD (2nd ed. BCD_TO_<int> / <int>_TO_BCD, 3rd ed. table 23 <bits>_BCD_TO_<uint> / <uint>_TO_BCD_<bits>).
BITS = {"SINT": "BYTE", "USINT": "BYTE", "INT": "WORD", "UINT": "WORD",
        "DINT": "DWORD", "UDINT": "DWORD", "LINT": "LWORD", "ULINT": "LWORD"}
for _int, _bits in BITS.items():
    EXPECTED[f"BCD_TO_{_int}"] = sig(("IN", "ANY_BITS", False), result=_int)
    EXPECTED[f"{_int}_TO_BCD"] = sig(("IN", "ANY_INT", False), result=_bits)
for _bits, _uint in (("BYTE", "USINT"), ("WORD", "UINT"), ("DWORD", "UDINT"), ("LWORD", "ULINT")):
    EXPECTED[f"{_bits}_BCD_TO_{_uint}"] = sig(("IN", _bits, False), result=_uint)
    EXPECTED[f"{_uint}_TO_BCD_{_bits}"] = sig(("IN", _uint, False), result=_bits)


def test_standard_function_signatures_built_afresh():
    table = builtins._table()
    got = {name: (tuple((p.name, p.category, p.generic) for p in fn.params), fn.result, fn.extensible)
           for name, fn in table.items()}
    assert got == EXPECTED
    assert all(fn.name == name for name, fn in table.items())

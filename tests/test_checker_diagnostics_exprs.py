"""Every diagnostic of the checker's expressions, calls and standard functions in
full, one table row per site (issue 16, docs/mutation.md, checker, session 12).

Fresh mutation samples of the checker stayed near 80 % because most survivors
are code that runs but whose result no test looks at in full: a diagnostic's
words, code or place matched in part, a rule's boundary tested on one side.
So each row here is one `ctx.error`/`ctx.warning` site of
st_runtime/checker/expressions.py and calls.py (every branch that gives another
code or message is its own row): an ST snippet and its one diagnostic, code,
line, column and message all compared with ==.  The line and column are those
of the token named in the row (`mark`, found in the snippet's text: counted
from the snippet, not from the checker); the words are the site's, reviewed,
with the snippet's names put in.  Each rule's boundary is tested on both sides
(IEC 61131-3 3rd ed. 2013 table 10 for the integer ranges; IEEE 754 binary32
for REAL's largest magnitude).  Then the results that are not diagnostics but
that a user sees through the compiler: folded constants and the types the
calls give.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import NamedTuple

import pytest

from checker_helpers import body, checked, diagnostics, program, walk
from st_runtime import ast
from st_runtime import types as T
from st_runtime.loader import load_texts
from test_checker_mutants_third import after_one_scan


class Row(NamedTuple):
    text: str
    code: str
    line: int
    mark: str           # the diagnostic's place: where this occurs in its line
    message: str
    dialect: str = "iec"
    nth: int = 1        # ... the nth time


def expected(r: Row) -> tuple[str, int, int, str]:
    source_line = r.text.splitlines()[r.line - 1]
    col = -1
    for _ in range(r.nth):
        col = source_line.index(r.mark, col + 1)
    return r.code, r.line, col + 1, r.message


def row(code: str, mark: str, message: str, decls: str = "", body: str = "", dialect: str = "iec",
        prefix: str = "", nth: int = 1) -> Row:
    """A row whose snippet is `prefix` (TYPEs, POUs) then `PROGRAM Main` with
    these declarations and one line of body, the line of the diagnostic."""
    text = prefix + program(decls, body)
    return Row(text, code, text.splitlines().index(body) + 1, mark, message, dialect, nth)


def _r(code, mark, message, prefix, decls, body, dialect="iec", nth=1) -> Row:
    return row(code, mark, message, decls, body, dialect, prefix, nth)


# Declarations shared by rows: a TYPE block, a user FUNCTION and FB, placed
# before PROGRAM Main.
COLOR = "TYPE\n    Color : (Red, Green);\n    Pt : STRUCT x : INT; y : INT; END_STRUCT;\nEND_TYPE\n"
F2 = ("FUNCTION F : INT\nVAR_INPUT\n    a : INT;\n    b : INT;\nEND_VAR\nF := a + b;\nEND_FUNCTION\n")
G0 = "FUNCTION G : INT\nG := 1;\nEND_FUNCTION\n"
H_INOUT = ("FUNCTION_BLOCK H\nVAR_IN_OUT\n    v : INT;\nEND_VAR\nv := v + 1;\nEND_FUNCTION_BLOCK\n")


# ------------------------------------------------------------------ expressions.py

EXPRESSION_ROWS = {
    # check_value: a string literal longer than the STRING it is stored in
    "string truncated (characters)": row(
        "W-TYPE-001", "'abcd'", "assignment: string of 4 characters is truncated to STRING[3]",
        decls="    s : STRING[3];", body="s := 'abcd';"),
    "string truncated (bytes, nj)": row(
        "W-TYPE-001", "'äbc'", "assignment: string of 4 bytes is truncated to STRING[3]",
        decls="    s : STRING[3];", body="s := 'äbc';", dialect="nj"),
    # require_assignable
    "value for a REF_TO": row(
        "E-TYPE-004", "i;", "assignment: expected REF_TO INT, found INT; take a reference with REF(...)",
        decls="    r : REF_TO INT; i : INT;", body="r := i;"),
    "reference of another type": row(
        "E-TYPE-004", "q;", "assignment: expected REF_TO INT, found REF_TO DINT",
        decls="    r : REF_TO INT; q : REF_TO DINT;", body="r := q;"),
    "reference to a STRING of another length": row(
        "E-TYPE-004", "q;", "assignment: expected REF_TO STRING[20], found REF_TO STRING[4]",
        decls="    r : REF_TO STRING[20]; q : REF_TO STRING[4];", body="r := q;"),
    "FB that does not implement the interface": _r(
        "E-TYPE-004", "g;", "assignment: expected an instance of an FB that implements I, found G",
        "INTERFACE I\nEND_INTERFACE\nFUNCTION_BLOCK F IMPLEMENTS I\nEND_FUNCTION_BLOCK\n"
        "FUNCTION_BLOCK G\nEND_FUNCTION_BLOCK\n", "    it : I; f : F; g : G;", "it := g;"),
    "FB instance copied": row(
        "E-TYPE-016", "g;", "assignment: function block instances cannot be copied (found TON, expected TON)",
        decls="    f : TON; g : TON;", body="f := g;"),
    "narrowing without a conversion": row(
        "E-TYPE-004", "d;", "assignment: expected INT, found DINT; convert explicitly with DINT_TO_INT",
        decls="    i : INT; d : DINT;", body="i := d;"),
    "number into a STRING": row(
        "E-TYPE-004", "i;", "assignment: expected STRING[10], found INT; convert explicitly with INT_TO_STRING",
        decls="    s : STRING[10]; i : INT;", body="s := i;"),
    "STRING into a number": row(
        "E-TYPE-004", "s;", "assignment: expected INT, found STRING[10]; convert explicitly with STRING_TO_INT",
        decls="    s : STRING[10]; i : INT;", body="i := s;"),
    "signed into unsigned (iec)": row(
        "E-TYPE-004", "i;", "assignment: expected UINT, found INT; convert explicitly with INT_TO_UINT",
        decls="    u : UINT; i : INT;", body="u := i;"),
    "signed into a narrower unsigned (nj)": row(
        "E-TYPE-004", "d;", "assignment: expected UINT, found DINT; convert explicitly with DINT_TO_UINT",
        decls="    u : UINT; d : DINT;", body="u := d;", dialect="nj"),
    "unsigned into signed (nj)": row(
        "E-TYPE-004", "u;", "assignment: expected INT, found UINT; convert explicitly with UINT_TO_INT",
        decls="    u : UINT; i : INT;", body="i := u;", dialect="nj"),
    "TIME_OF_DAY short name in the hint": row(
        "E-TYPE-004", "t;", "assignment: expected DATE_AND_TIME, found TIME_OF_DAY; convert explicitly with TOD_TO_DT",
        decls="    t : TOD; d : DT;", body="d := t;"),
    # settle: untyped constants
    "2 is no BOOL literal": row(
        "E-TYPE-004", "2;", "assignment: expected BOOL, found SINT; convert explicitly with SINT_TO_BOOL",
        decls="    b : BOOL;", body="b := 2;"),
    "1 - 0 is no BOOL literal": row(
        "E-TYPE-004", "1 - 0", "assignment: expected BOOL, found SINT; convert explicitly with SINT_TO_BOOL",
        decls="    b : BOOL;", body="b := 1 - 0;"),
    "untyped division by zero": row(
        "E-TYPE-017", "/", "division by zero in a constant expression", decls="    x : INT;", body="x := 1 / 0;"),
    "untyped MOD by zero": row(
        "E-TYPE-017", "MOD", "division by zero in a constant expression",
        decls="    x : INT;", body="x := 7 MOD 0;"),
    "constant beyond REAL": row(
        "E-TYPE-005", "3.4028236E38",
        "constant 3.4028236e+38 does not fit REAL (largest magnitude 3.4028235e+38)",
        decls="    r : REAL;", body="r := 3.4028236E38;"),
    "folded constant beyond REAL": row(
        "E-TYPE-005", "*",
        "constant 4e+38 does not fit REAL (largest magnitude 3.4028235e+38)",
        decls="    r : REAL;", body="r := 2.0E38 * 2.0;"),
    "literal beyond LREAL": row(
        "E-TYPE-005", "1.0E309", "a real literal does not fit LREAL (largest magnitude 1.7976931348623157e+308)",
        decls="    l : LREAL;", body="l := 2.0 * 1.0E309;"),
    "literal beyond every real, into a REAL": row(
        "E-TYPE-005", "1.0E309", "a real literal does not fit REAL (largest magnitude 3.4028235e+38)",
        decls="    r : REAL;", body="r := 1.0E309;"),
    "constant beyond INT": row(
        "E-TYPE-005", "32768", "constant 32768 does not fit INT (range -32768..32767)",
        decls="    x : INT;", body="x := 32768;"),
    "folded constant beyond USINT": row(
        "E-TYPE-005", "+", "constant 256 does not fit USINT (range 0..255)",
        decls="    x : USINT;", body="x := 200 + 56;"),
    "constant beyond every integer type": row(
        "E-TYPE-005", "18446744073709551616",
        "integer constant 18446744073709551616 is larger than any integer type (ULINT holds up to "
        "18446744073709551615)", decls="    b : BOOL;", body="b := 18446744073709551616 > 0;"),
    "constant widens an INT sum": row(
        "E-TYPE-004", "i +", "assignment: expected INT, found DINT; convert explicitly with DINT_TO_INT",
        decls="    i : INT;", body="i := i + 32768;"),
    # literals
    "typed literal beyond its type": row(
        "E-TYPE-005", "INT#", "literal 32768 does not fit INT (range -32768..32767)",
        decls="    x : INT;", body="x := INT#32768;"),
    "an initial value of a typed literal folded (nj)": Row(
        program("    r : LREAL := LREAL#5 * 2.0;", "r := r;"), "E-NJ-008", 3, "LREAL#5",
        "initial value of 'r': 'LREAL#5.0 * 2.0' is not a literal; a variable table in Sysmac Studio takes "
        "literals: write 10.0 (* LREAL#5.0 * 2.0 *)", "nj"),
    "typed literal beyond BYTE": row(
        "E-TYPE-005", "BYTE#", "literal 256 does not fit BYTE (range 0..255)",
        decls="    x : BYTE;", body="x := BYTE#256;"),
    "integer literal with a TIME prefix": row(
        "E-TYPE-004", "DATE#", "integer literal with prefix DATE#: expected a numeric or bit-string type, "
        "found DATE", decls="    t : DATE;", body="t := DATE#5;"),
    "unknown prefix": row(
        "E-DECL-004", "FOO#", "unknown type prefix FOO# on a literal", decls="    x : INT;", body="x := FOO#5;"),
    "typed literal below its type": row(
        "E-TYPE-005", "SINT#", "literal -129 does not fit SINT (range -128..127)",
        decls="    x : SINT;", body="x := SINT#-129;"),
    # enumerations
    "unknown enumeration type": _r(
        "E-DECL-004", "Shade#", "unknown enumeration type 'Shade'", COLOR, "    c : Color;", "c := Shade#Red;"),
    "a struct before #": _r(
        "E-TYPE-015", "Pt#", "'Pt#Red': expected an enumeration type before '#', found Pt",
        COLOR, "    c : Color;", "c := Pt#Red;"),
    "no such enumeration value": _r(
        "E-TYPE-015", "Color#", "'Blue' is not a value of Color (values: Red, Green)",
        COLOR, "    c : Color;", "c := Color#Blue;"),
    "no such enumeration value, written with a dot": _r(
        "E-TYPE-015", "Color.", "'Blue' is not a value of Color (values: Red, Green)",
        COLOR, "    c : Color;", "c := Color.Blue;", "codesys"),
    "enumeration value with a dot (iec)": _r(
        "E-DIALECT-001", "Color.", "an enumeration value written Type.Value is not accepted by --dialect iec; "
        "--dialect codesys accepts it", COLOR, "    c : Color;", "c := Color.Red;"),
    "ambiguous enumeration value": _r(
        "E-TYPE-015", "Red;", "enumeration value 'Red' is ambiguous: write Color#Red or Light#Red",
        "TYPE\n    Color : (Red, Green);\n    Light : (Red, Amber);\nEND_TYPE\n", "    i : INT;", "i := Red;"),
    # names that are not values
    "a FUNCTION read as a variable": _r(
        "E-TYPE-016", "G;", "'G' is a FUNCTION, not a variable; call it as G(...)", G0, "    x : INT;", "x := G;"),
    "a FUNCTION_BLOCK read as a variable": _r(
        "E-TYPE-016", "H;", "'H' is a FUNCTION_BLOCK, not a variable", H_INOUT, "    x : INT;", "x := H;"),
    "a type read as a variable": _r(
        "E-TYPE-016", "Pt;", "'Pt' is a type, not a variable", COLOR, "    x : INT;", "x := Pt;"),
    "undeclared, with a suggestion": row(
        "E-DECL-001", "countr", "undeclared name 'countr' (did you mean 'counter'?)",
        decls="    counter : INT;", body="counter := countr;"),
    "undeclared": row(
        "E-DECL-001", "zzz", "undeclared name 'zzz'", decls="    counter : INT;", body="counter := zzz;"),
    # members
    "struct without the member": _r(
        "E-TYPE-009", "p.z", "struct Pt has no member 'z' (members: x, y)", COLOR,
        "    p : Pt; x : INT;", "x := p.z;"),
    "another dialect's pin name": row(
        "E-PIN-001", "c.Reset", "CTU has no pin 'Reset' under --dialect iec: that is the nj dialect's name; "
        "here the pin is 'R' (st_runtime/dialects.py)", decls="    c : CTU; b : BOOL;", body="b := c.Reset;"),
    "FB without the variable": row(
        "E-TYPE-009", "t.foo", "function block TON has no variable 'foo'",
        decls="    t : TON; b : BOOL;", body="b := t.foo;"),
    "an FB's internal variable read outside": _r(
        "E-TYPE-009", "h.n", "'n' is a VAR of K: only inputs, outputs and in-outs are visible outside the instance",
        "FUNCTION_BLOCK K\nVAR\n    n : INT;\nEND_VAR\nn := n + 1;\nEND_FUNCTION_BLOCK\n",
        "    h : K; x : INT;", "x := h.n;"),
    "member of an INT": row(
        "E-TYPE-009", "i.y", "'.y': expected a struct or function block instance, found INT",
        decls="    i : INT; x : INT;", body="x := i.y;"),
    "undeclared, with a global's name suggested": row(
        "E-DECL-001", "countr", "undeclared name 'countr' (did you mean 'counter'?)",
        prefix="VAR_GLOBAL\n    counter : INT;\nEND_VAR\n", decls="    x : INT;", body="x := countr;"),
    "TOD + TOD": row(
        "E-TYPE-001", "+", "+: expected numeric operands (ANY_NUM), found TIME_OF_DAY",
        decls="    a : TOD;", body="a := a + a;"),
    "DATE + TIME": row(
        "E-TYPE-001", "+", "+: expected numeric operands (ANY_NUM), found DATE; TIME allows TIME + TIME, "
        "TIME - TIME, TIME * number, TIME / number", decls="    d : DATE; t : TIME;", body="d := d + t;"),
    "TIME - DATE": row(
        "E-TYPE-001", "-", "-: expected numeric operands (ANY_NUM), found TIME; TIME allows TIME + TIME, "
        "TIME - TIME, TIME * number, TIME / number", decls="    d : DATE; t : TIME;", body="t := t - d;"),
    # dereference, bits, direct addresses, indexes
    "dereference of an INT": row(
        "E-TYPE-001", "i^", "^: expected a reference (REF_TO or POINTER TO), found INT",
        decls="    i : INT; x : INT;", body="x := i^;"),
    "bit 8 of a BYTE": row(
        "E-TYPE-009", "b.8", ".8: expected an integer or bit string holding part 8 of 1 bit(s), found BYTE",
        decls="    b : BYTE; x : BOOL;", body="x := b.8;", dialect="nj"),
    "byte 2 of a WORD": row(
        "E-TYPE-009", "w.%B2", ".%B2: expected an integer or bit string holding part 2 of 8 bit(s), found WORD",
        decls="    w : WORD; x : BYTE;", body="x := w.%B2;", dialect="codesys"),
    "bit of a REAL": row(
        "E-TYPE-009", "r.0", ".0: expected an integer or bit string holding part 0 of 1 bit(s), found REAL",
        decls="    r : REAL; x : BOOL;", body="x := r.0;", dialect="nj"),
    "bit 8 of a byte address": row(
        "E-DECL-015", "%IX0.8", "'%IX0.8': a bit address is <byte>.<bit> with bit 0..7",
        decls="    x : BOOL;", body="x := %IX0.8;"),
    "indexing an INT": row(
        "E-TYPE-006", "i[", "indexing: expected an array, found INT", decls="    i : INT; x : INT;", body="x := i[1];"),
    "two indexes of one dimension": row(
        "E-TYPE-006", "a[", "ARRAY[1..3] OF INT has 1 dimension(s), found 2 index(es)",
        decls="    a : ARRAY[1..3] OF INT; x : INT;", body="x := a[1, 2];"),
    "BOOL index": row(
        "E-TYPE-007", "TRUE", "array index: expected an integer, found BOOL",
        decls="    a : ARRAY[1..3] OF INT; x : INT;", body="x := a[TRUE];"),
    "real index": row(
        "E-TYPE-007", "1.5", "array index: expected an integer, found LREAL",
        decls="    a : ARRAY[1..3] OF INT; x : INT;", body="x := a[1.5];"),
    "index below the bounds": row(
        "E-TYPE-008", "0]", "index 0 is out of bounds 1..3",
        decls="    a : ARRAY[1..3] OF INT; x : INT;", body="x := a[0];"),
    "index above the bounds": row(
        "E-TYPE-008", "4]", "index 4 is out of bounds 1..3",
        decls="    a : ARRAY[1..3] OF INT; x : INT;", body="x := a[4];"),
    "index above the bounds of dimension 2": row(
        "E-TYPE-008", "5]", "index 5 is out of bounds 0..4 of dimension 2",
        decls="    m : ARRAY[1..2, 0..4] OF INT; x : INT;", body="x := m[2, 5];"),
    # operators
    "NOT of an INT": row(
        "E-TYPE-001", "NOT", "NOT: expected BOOL or a bit string, found INT", decls="    x : INT;", body="x := NOT x;"),
    "minus of a BOOL": row(
        "E-TYPE-001", "-", "unary -: expected a number or TIME, found BOOL", decls="    b : BOOL;", body="b := -b;"),
    "typed division by zero": row(
        "E-TYPE-017", "/", "division by zero in a constant expression",
        decls="    x : INT;", body="x := INT#1 / INT#0;"),
    "variable divided by zero": row(
        "E-TYPE-017", "0;", "division by zero in a constant expression", decls="    x : INT;", body="x := x / 0;"),
    "variable MOD zero": row(
        "E-TYPE-017", "0;", "division by zero in a constant expression", decls="    x : INT;", body="x := x MOD 0;"),
    "AND of an INT": row(
        "E-TYPE-001", "AND", "AND: expected BOOL or bit-string operands, found INT",
        decls="    b : BOOL; x : INT;", body="b := b AND x;"),
    "& of an INT is named AND": row(
        "E-TYPE-001", "&", "AND: expected BOOL or bit-string operands, found INT",
        decls="    b : BOOL; x : INT;", body="b := x & b;"),
    "XOR of a REAL": row(
        "E-TYPE-001", "XOR", "XOR: expected BOOL or bit-string operands, found REAL",
        decls="    b : BOOL; r : REAL;", body="b := b XOR r;"),
    "integer base of **": row(
        "E-TYPE-001", "**", "**: expected a REAL or LREAL base, found INT; convert explicitly with INT_TO_LREAL",
        decls="    r : LREAL; i : INT;", body="r := i ** 2.0;"),
    "BOOL exponent": row(
        "E-TYPE-001", "**", "**: expected a numeric exponent, found BOOL",
        decls="    r : LREAL; b : BOOL;", body="r := r ** b;"),
    "MOD of reals": row(
        "E-TYPE-001", "MOD", "MOD: expected integer operands, found LREAL",
        decls="    r : LREAL;", body="r := r MOD 2.0;"),
    "sum with a BOOL": row(
        "E-TYPE-001", "+", "+: expected numeric operands (ANY_NUM), found BOOL",
        decls="    b : BOOL; x : INT;", body="x := x + b;"),
    "TIME plus a number": row(
        "E-TYPE-001", "+", "+: expected numeric operands (ANY_NUM), found TIME; TIME allows TIME + TIME, "
        "TIME - TIME, TIME * number, TIME / number", decls="    t : TIME; x : INT;", body="t := t + x;"),
    "number times... a TIME divided": row(
        "E-TYPE-001", "/", "/: expected numeric operands (ANY_NUM), found TIME; TIME allows TIME + TIME, "
        "TIME - TIME, TIME * number, TIME / number", decls="    t : TIME; x : INT;", body="t := x / t;"),
    "LINT + ULINT": row(
        "E-TYPE-002", "+", "+: operands LINT and ULINT have no common type; convert one explicitly "
        "(e.g. LINT_TO_ULINT)", decls="    l : LINT; u : ULINT;", body="l := l + u;"),
    "comparison of arrays": row(
        "E-TYPE-001", "=", "=: expected elementary, string or enumeration operands, found ARRAY[1..2] OF INT",
        decls="    a : ARRAY[1..2] OF INT; b : BOOL;", body="b := a = a;", nth=2),
    "reference ordered": row(
        "E-TYPE-001", "<", "<: expected elementary, string or enumeration operands, found REF_TO INT",
        decls="    r : REF_TO INT; b : BOOL;", body="b := r < r;"),
    "enumeration compared with INT": _r(
        "E-TYPE-002", "=", "=: cannot compare Color with INT", COLOR, "    c : Color; i : INT; b : BOOL;",
        "b := c = i;", nth=2),
    "LINT compared with ULINT": row(
        "E-TYPE-002", "<", "<: cannot compare LINT with ULINT; convert one explicitly (e.g. LINT_TO_ULINT)",
        decls="    l : LINT; u : ULINT; b : BOOL;", body="b := l < u;"),
    "STRING compared with WSTRING": row(
        "E-TYPE-002", "=", "=: cannot compare STRING[8] with WSTRING[8]",
        decls="    s : STRING[8]; w : WSTRING[8]; b : BOOL;", body="b := s = w;", nth=2),
    # what a direct address, a date, a subrange and an array are
    "a whole area read": row(
        "E-DECL-015", "%IW*", "%IW*: %I* has no place in the process image to read",
        decls="    x : WORD;", body="x := %IW*;"),
    "an address beyond the area": row(
        "E-DECL-015", "%IW70000", "'%IW70000' lies beyond the 65536-byte %I area",
        decls="    x : WORD;", body="x := %IW70000;"),
    "a word address is a WORD": row(
        "E-TYPE-004", "%IW0", "assignment: expected INT, found WORD; convert explicitly with WORD_TO_INT",
        decls="    x : INT;", body="x := %IW0;"),
    "a date is no TIME": row(
        "E-TYPE-004", "D#", "assignment: expected TIME, found DATE; convert explicitly with DATE_TO_TIME",
        decls="    t : TIME;", body="t := D#2020-01-01;"),
    "a time of day is no DATE": row(
        "E-TYPE-004", "TOD#", "assignment: expected DATE, found TIME_OF_DAY; convert explicitly with TOD_TO_DATE",
        decls="    d : DATE;", body="d := TOD#12:00:00;"),
    "a reference to a subrange is no REF_TO its base": row(
        "E-TYPE-004", "REF", "assignment: expected REF_TO INT, found REF_TO INT (1..5)",
        decls="    r : REF_TO INT; s : INT(1..5);", body="r := REF(s);"),
    "a reference to an array of other bounds": row(
        "E-TYPE-004", "REF", "assignment: expected REF_TO ARRAY[1..3] OF INT, found REF_TO ARRAY[0..2] OF INT",
        decls="    r : REF_TO ARRAY[1..3] OF INT; a : ARRAY[0..2] OF INT;", body="r := REF(a);"),
    "a PROGRAM read as a variable": _r(
        "E-TYPE-016", "Other", "'Other' is a PROGRAM, not a variable", "PROGRAM Other\nEND_PROGRAM\n",
        "    x : INT;", "x := Other;"),
    # the type of a sum: IEC's common type, the NJ's higher-ranked operand
    "INT + UINT is a DINT (iec)": row(
        "E-TYPE-004", "i +", "assignment: expected INT, found DINT; convert explicitly with DINT_TO_INT",
        decls="    i : INT; u : UINT;", body="i := i + u;"),
    "INT + UINT is a UINT (nj)": row(
        "E-TYPE-004", "i +", "assignment: expected INT, found UINT; convert explicitly with UINT_TO_INT",
        decls="    i : INT; u : UINT;", body="i := i + u;", dialect="nj"),
}


# ------------------------------------------------------------------ calls.py

CALL_ROWS = {
    "a FUNCTION_BLOCK type called": _r(
        "E-CALL-001", "H(", "'H' is a FUNCTION_BLOCK type: declare an instance (inst : H;) and call the instance",
        H_INOUT, "    x : INT;", "H();"),
    "a PROGRAM called": _r(
        "E-CALL-001", "Other(", "'Other' is a PROGRAM: programs are run by tasks, not called",
        "PROGRAM Other\nEND_PROGRAM\n", "    x : INT;", "Other();"),
    "a type called": _r(
        "E-CALL-001", "Pt(", "'Pt' is a type, not a function", COLOR, "    x : INT;", "x := Pt(1);"),
    "__NEW": row(
        "E-CALL-013", "__NEW", "__NEW: dynamic memory (CODESYS __NEW / __DELETE) is not supported; declare the "
        "instance or array as a variable instead", decls="    x : INT;", body="x := __NEW(x);", dialect="codesys"),
    "undeclared function": row(
        "E-DECL-001", "Foo", "undeclared function 'Foo'", decls="    x : INT;", body="x := Foo(1);"),
    "a variable called": row(
        "E-CALL-001", "i(", "call: expected a function or a function block instance, found a variable of type INT",
        decls="    i : INT;", body="i();"),
    # LOWER_BOUND / UPPER_BOUND
    "UPPER_BOUND with one argument": row(
        "E-CALL-009", "UPPER_BOUND", "UPPER_BOUND: expected an array and a dimension number, found 1 argument(s)",
        decls="    a : ARRAY[1..3] OF INT; d : DINT;", body="d := UPPER_BOUND(a);"),
    "LOWER_BOUND with three arguments": row(
        "E-CALL-006", "LOWER_BOUND", "LOWER_BOUND: expected an array and a dimension number, found 3 argument(s)",
        decls="    a : ARRAY[1..3] OF INT; d : DINT;", body="d := LOWER_BOUND(a, 1, 1);"),
    "UPPER_BOUND with an output": row(
        "E-CALL-006", "UPPER_BOUND", "UPPER_BOUND: expected an array and a dimension number, found 2 argument(s)",
        decls="    a : ARRAY[1..3] OF INT; d : DINT;", body="d := UPPER_BOUND(a, Q => d);"),
    "UPPER_BOUND of a DINT": row(
        "E-TYPE-006", "d,", "UPPER_BOUND: expected an array, found DINT",
        decls="    a : ARRAY[1..3] OF INT; d : DINT;", body="d := UPPER_BOUND(d, 1);"),
    "dimension 0": row(
        "E-TYPE-008", "0)", "UPPER_BOUND: expected a constant dimension 1..2, found 0",
        decls="    a : ARRAY[1..3, 1..2] OF INT; d : DINT;", body="d := UPPER_BOUND(a, 0);"),
    "dimension 3 of 2": row(
        "E-TYPE-008", "3)", "LOWER_BOUND: expected a constant dimension 1..2, found 3",
        decls="    a : ARRAY[1..3, 1..2] OF INT; d : DINT;", body="d := LOWER_BOUND(a, 3);"),
    "dimension not constant": row(
        "E-TYPE-008", "d)", "UPPER_BOUND: expected a constant dimension 1..1, found a non-constant value",
        decls="    a : ARRAY[1..3] OF INT; d : DINT;", body="d := UPPER_BOUND(a, d);"),
    # REF / ADR
    "REF of nothing": row(
        "E-CALL-009", "REF", "REF: expected one variable, found 0 argument(s)",
        decls="    r : REF_TO INT; i : INT;", body="r := REF();"),
    "REF of two": row(
        "E-CALL-006", "REF", "REF: expected one variable, found 2 argument(s)",
        decls="    r : REF_TO INT; i : INT;", body="r := REF(i, i);"),
    "REF of an output": row(
        "E-CALL-006", "REF", "REF: expected one variable, found 1 argument(s)",
        decls="    r : REF_TO INT; i : INT;", body="r := REF(Q => i);"),
    "REF of a bit": row(
        "E-TYPE-014", "w.3", "REF(...): expected a variable, found a bit access",
        decls="    r : REF_TO BOOL; w : WORD;", body="r := REF(w.3);", dialect="codesys"),
    "ADR under iec": row(
        "E-DIALECT-001", "ADR", "ADR() is not accepted by --dialect iec; --dialect codesys accepts it",
        decls="    r : REF_TO INT; i : INT;", body="r := ADR(i);"),
    # NAMESPACE
    "namespace without the function": _r(
        "E-DECL-001", "NS.G", "NAMESPACE NS declares no POU 'G'",
        "NAMESPACE NS\nFUNCTION F : INT\nF := 1;\nEND_FUNCTION\nEND_NAMESPACE\n", "    x : INT;", "x := NS.G();"),
    # methods
    "SUPER outside an FB": row(
        "E-DECL-016", "SUPER", "SUPER.M: SUPER is only valid inside a FUNCTION_BLOCK or its methods",
        decls="    x : INT;", body="SUPER.M();"),
    "SUPER.M where the parent has no M": Row(
        "FUNCTION_BLOCK A\nEND_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENDS A\nSUPER.M();\nEND_FUNCTION_BLOCK\n",
        "E-DECL-016", 4, "SUPER", "SUPER.M: B extends no FB with a method M"),
    "PRIVATE method called outside": _r(
        "E-CALL-012", "a.M", "method A.M is PRIVATE: it may be called only inside A",
        "FUNCTION_BLOCK A\nMETHOD PRIVATE M : INT\nM := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n",
        "    a : A; x : INT;", "x := a.M();"),
    "PROTECTED method called outside": _r(
        "E-CALL-012", "a.M", "method A.M is PROTECTED: it may be called only inside A and the FBs extending it",
        "FUNCTION_BLOCK A\nMETHOD PROTECTED M : INT\nM := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n",
        "    a : A; x : INT;", "x := a.M();"),
    "method without a result in an expression": _r(
        "E-TYPE-016", "a.M", "method A.M returns no value and cannot be used in an expression",
        "FUNCTION_BLOCK A\nMETHOD PUBLIC M\nEND_METHOD\nEND_FUNCTION_BLOCK\n", "    a : A; x : INT;", "x := a.M();"),
    "FB instance in an expression": row(
        "E-CALL-010", "t(", "function block instance of TON called inside an expression: call it as a statement, "
        "then read its outputs", decls="    t : TON; b : BOOL;", body="b := t(IN := TRUE, PT := T#1s);"),
    # binding the arguments of a user POU
    "positional after formal": _r(
        "E-CALL-008", "2)", "call of F: positional argument after a formal (name := value) argument",
        F2, "    x : INT;", "x := F(a := 1, 2);"),
    "three positional for two": _r(
        "E-CALL-006", "3)", "call of F: expected at most 2 positional argument(s), found 3",
        F2, "    x : INT;", "x := F(1, 2, 3);"),
    "no such parameter": _r(
        "E-CALL-002", "c :=", "F has no parameter 'c' (parameters: a, b)", F2, "    x : INT;", "x := F(c := 1);"),
    "no parameters at all": _r(
        "E-CALL-002", "c :=", "G has no parameter 'c' (parameters: none)", G0, "    x : INT;", "x := G(c := 1);"),
    "a local variable is no parameter": _r(
        "E-CALL-002", "n :=", "K has no parameter 'n' (parameters: q)",
        "FUNCTION_BLOCK K\nVAR_OUTPUT\n    q : INT;\nEND_VAR\nVAR\n    n : INT;\nEND_VAR\nEND_FUNCTION_BLOCK\n",
        "    k : K;", "k(n := 1);"),
    "parameter given twice": _r(
        "E-CALL-003", "a := 2", "call of F: parameter 'a' is given twice", F2, "    x : INT;", "x := F(a := 1, a := 2);"),
    "positional then the same formal": _r(
        "E-CALL-003", "a := 2", "call of F: parameter 'a' is given twice", F2, "    x : INT;", "x := F(1, a := 2);"),
    "in-out missing": _r(
        "E-CALL-004", "h(", "call of H: VAR_IN_OUT 'v' (INT) is missing; in-out parameters are required at every call",
        H_INOUT, "    h : H;", "h();"),
    "one argument of two": _r(
        "E-CALL-009", "F(", "call of F: expected 2 argument(s), found 1", F2, "    x : INT;", "x := F(1);"),
    "another dialect's pin in a call": row(
        "E-PIN-001", "Reset", "CTU has no pin 'Reset' under --dialect iec: that is the nj dialect's name; here the "
        "pin is 'R' (st_runtime/dialects.py)", decls="    c : CTU;", body="c(CU := TRUE, Reset := FALSE, PV := 3);"),
    "an IEC pin name under nj": row(
        "E-PIN-001", "R :=", "CTU has no pin 'R' under --dialect nj: that is the iec dialect's name; here the "
        "pin is 'Reset' (st_runtime/dialects.py)", decls="    c : CTU;", body="c(CU := TRUE, R := FALSE, PV := 3);",
        dialect="nj"),
    "an input read with =>": row(
        "E-CALL-005", "IN =>", "'IN' is a VAR_INPUT of TON: pass it with :=, not =>",
        decls="    t : TON; b : BOOL;", body="t(IN => b, PT := T#1s);"),
    "an output given with :=": row(
        "E-CALL-005", "Q :=", "'Q' is an output of TON: read it with =>, not :=",
        decls="    t : TON; b : BOOL;", body="t(IN := TRUE, PT := T#1s, Q := b);"),
    "NOT on a TIME output": row(
        "E-TYPE-001", "NOT", "NOT on output 'ET': expected BOOL, found TIME",
        decls="    t : TON; b : BOOL;", body="t(IN := TRUE, PT := T#1s, NOT ET => b);"),
    "an argument of another type": _r(
        "E-TYPE-004", "d)", "argument 'a' of F: expected INT, found DINT; convert explicitly with DINT_TO_INT",
        F2, "    x : INT; d : DINT;", "x := F(b := 1, a := d);"),
    "a string argument truncated": _r(
        "W-TYPE-001", "'abcdef'", "argument 's' of T3: string of 6 characters is truncated to STRING[3]",
        "FUNCTION T3 : INT\nVAR_INPUT\n    s : STRING[3];\nEND_VAR\nT3 := 1;\nEND_FUNCTION\n",
        "    x : INT;", "x := T3(s := 'abcdef');"),
    "an output into a narrower variable": row(
        "E-TYPE-004", "i)", "output 'CV' of CTU: expected SINT, found INT; convert explicitly with INT_TO_SINT",
        decls="    c : CTU; i : SINT;", body="c(CU := TRUE, PV := 3, CV => i);"),
    "in-out given an expression": _r(
        "E-CALL-007", "i + 1", "VAR_IN_OUT 'v' of H: expected a variable, found an expression",
        H_INOUT, "    h : H; i : INT;", "h(v := i + 1);"),
    "in-out given a CONSTANT": _r(
        "E-CALL-007", "k)", "VAR_IN_OUT 'v' of H: expected a writable variable, found CONSTANT 'k'",
        H_INOUT, "    h : H;\nEND_VAR\nVAR CONSTANT\n    k : INT := 1;", "h(v := k);"),
    "in-out given the FOR variable": _r(
        "E-CALL-007", "i);", "VAR_IN_OUT 'v' of H: expected a writable variable, found 'i', the control variable "
        "of an enclosing FOR loop", H_INOUT, "    h : H; i : INT;", "FOR i := 1 TO 2 DO h(v := i); END_FOR;"),
    "in-out given an enumeration value": _r(
        "E-CALL-007", "Red)", "VAR_IN_OUT 'v' of H: expected a variable, found an enumeration value",
        "TYPE\n    Color : (Red, Green);\nEND_TYPE\nFUNCTION_BLOCK H\nVAR_IN_OUT\n    v : Color;\nEND_VAR\n"
        "END_FUNCTION_BLOCK\n", "    h : H;", "h(v := Red);"),
    "in-out given a bit": _r(
        "E-CALL-007", "w.3", "VAR_IN_OUT 'v' of H: expected a variable, found a bit access",
        "FUNCTION_BLOCK H\nVAR_IN_OUT\n    v : BOOL;\nEND_VAR\nEND_FUNCTION_BLOCK\n",
        "    h : H; w : WORD;", "h(v := w.3);", "codesys"),
    "in-out of another type": _r(
        "E-CALL-011", "d)", "VAR_IN_OUT 'v' of H: expected a variable of type INT, found DINT (in-out parameters "
        "are passed by reference, without conversion)", H_INOUT, "    h : H; d : DINT;", "h(v := d);"),
    "ARRAY[*] in-out of another element type": _r(
        "E-CALL-011", "a)", "VAR_IN_OUT 'v' of S: expected a variable of type ARRAY[*] OF INT, found "
        "ARRAY[1..3] OF DINT (in-out parameters are passed by reference, without conversion)",
        "FUNCTION S : INT\nVAR_IN_OUT\n    v : ARRAY[*] OF INT;\nEND_VAR\nS := 1;\nEND_FUNCTION\n",
        "    a : ARRAY[1..3] OF DINT; x : INT;", "x := S(a);"),
    # operators in call form
    "SUB of three": row(
        "E-CALL-006", "SUB", "SUB: expected 2 argument(s), found 3", decls="    x : INT;", body="x := SUB(1, 2, 3);"),
    "NE of three": row(
        "E-CALL-006", "NE", "NE: expected 2 argument(s), found 3", decls="    b : BOOL;", body="b := NE(1, 2, 3);"),
    "GT of one": row(
        "E-CALL-009", "GT", "GT: expected at least 2 argument(s), found 1", decls="    b : BOOL;", body="b := GT(1);"),
    "DIV of one": row(
        "E-CALL-009", "DIV", "DIV: expected 2 argument(s), found 1", decls="    x : INT;", body="x := DIV(1);"),
    "MUL_TIME by a BOOL": row(
        "E-TYPE-004", "TRUE", "MUL_TIME: argument IN2: expected a number (ANY_NUM), found BOOL",
        decls="    t : TIME;", body="t := MUL_TIME(t, TRUE);"),
    "ADD_TIME of a number": row(
        "E-TYPE-004", "5)", "ADD_TIME: argument IN2: expected TIME, found SINT",
        decls="    t : TIME;", body="t := ADD_TIME(t, 5);"),
    "SUB_DATE_DATE of a TOD": row(
        "E-TYPE-004", "d,", "SUB_DATE_DATE: argument IN1: expected DATE, found TIME_OF_DAY",
        decls="    t : TIME; d : TOD; e : DATE;", body="t := SUB_DATE_DATE(d, e);"),
    # standard functions
    "output of ABS": row(
        "E-CALL-005", "Q =>", "ABS has no outputs: 'Q' cannot be read with =>", decls="    x : INT;",
        body="x := ABS(Q => x);"),
    "positional after formal (LIMIT)": row(
        "E-CALL-008", "5,", "call of LIMIT: positional argument after a formal argument", decls="    x : INT;",
        body="x := LIMIT(MN := 0, 5, MX := 10);"),
    "ABS of two": row(
        "E-CALL-006", "2)", "ABS: expected 1 argument(s), found 2", decls="    x : INT;", body="x := ABS(1, 2);"),
    "ABS with no parameter X": row(
        "E-CALL-002", "X :=", "ABS has no parameter 'X' (parameters: IN)", decls="    x : INT;",
        body="x := ABS(X := 1);"),
    "MAX with no parameter X": row(
        "E-CALL-002", "X :=", "MAX has no parameter 'X' (parameters: IN1, IN2, ...)", decls="    x : INT;",
        body="x := MAX(X := 1, IN1 := 2, IN2 := 3);"),
    "ABS given IN twice": row(
        "E-CALL-003", "IN := 2", "call of ABS: parameter 'IN' is given twice", decls="    x : INT;",
        body="x := ABS(IN := 1, IN := 2);"),
    "MAX of LINT and ULINT": row(
        "E-TYPE-002", "u)", "MAX: arguments of types LINT and ULINT have no common type",
        decls="    l : LINT; u : ULINT;", body="l := MAX(l, u);"),
    "SQRT of an INT": row(
        "E-TYPE-004", "i)", "SQRT: expected REAL or LREAL (ANY_REAL), found INT; convert explicitly with INT_TO_LREAL",
        decls="    r : LREAL; i : INT;", body="r := SQRT(i);"),
    "SHL of an INT": row(
        "E-TYPE-004", "i,", "SHL: expected a bit string BYTE, WORD, DWORD or LWORD, found INT; convert explicitly "
        "with INT_TO_WORD", decls="    w : WORD; i : INT;", body="w := SHL(i, 1);"),
    "SHL of a LINT": row(
        "E-TYPE-004", "i,", "SHL: expected a bit string BYTE, WORD, DWORD or LWORD, found LINT; convert explicitly "
        "with LINT_TO_LWORD", decls="    w : LWORD; i : LINT;", body="w := SHL(i, 1);"),
    "SHL of a REAL": row(
        "E-TYPE-004", "r,", "SHL: expected a bit string BYTE, WORD, DWORD or LWORD, found REAL",
        decls="    w : WORD; r : REAL;", body="w := SHL(r, 1);"),
    "ABS of a BOOL": row(
        "E-TYPE-004", "b)", "ABS: expected a number (ANY_NUM), found BOOL", decls="    b : BOOL;", body="b := ABS(b);"),
    "AND of an INT in call form": row(
        "E-TYPE-004", "i,", "AND: expected BOOL or a bit string (ANY_BIT), found INT",
        decls="    i : INT;", body="i := AND(i, i);"),
    "AND of an INT and a BOOL in call form": row(
        "E-TYPE-002", "b)", "AND: arguments of types INT and BOOL have no common type",
        decls="    i : INT; b : BOOL;", body="b := AND(i, b);"),
    "LEN of an INT": row(
        "E-TYPE-004", "i)", "LEN: argument IN: expected a STRING, found INT", decls="    i : INT;", body="i := LEN(i);"),
    "SEL's G an INT": row(
        "E-TYPE-004", "i,", "SEL: argument G: expected BOOL, found INT", decls="    i : INT;", body="i := SEL(i, 1, 2);"),
    "SEL's G the constant 2": row(
        "E-TYPE-004", "2,", "SEL: argument G: expected BOOL, found SINT", decls="    i : INT;", body="i := SEL(2, 1, 2);"),
    "MUX's K a REAL": row(
        "E-TYPE-004", "r,", "MUX: argument K: expected an integer (ANY_INT), found REAL",
        decls="    i : INT; r : REAL;", body="i := MUX(r, 1, 2);"),
    "TRUNC of an INT": row(
        "E-TYPE-004", "i)", "TRUNC: argument IN: expected REAL or LREAL (ANY_REAL), found INT",
        decls="    i : INT;", body="i := TRUNC(i);"),
    "EXPT's exponent a BOOL": row(
        "E-TYPE-004", "b)", "EXPT: argument IN2: expected a number (ANY_NUM), found BOOL",
        decls="    r : LREAL; b : BOOL;", body="r := EXPT(r, b);"),
    # conversions
    "conversion's input named X": row(
        "E-CALL-002", "X :=", "INT_TO_DINT has one input, IN; found 'X'", decls="    i : INT; d : DINT;",
        body="d := INT_TO_DINT(X := i);"),
    "conversion of nothing": row(
        "E-CALL-009", "INT_TO_DINT", "INT_TO_DINT: expected 1 argument, found 0", decls="    d : DINT;",
        body="d := INT_TO_DINT();"),
    "conversion of two": row(
        "E-CALL-006", "TIME_OF_DAY_TO_DT", "TOD_TO_DT: expected 1 argument, found 2", decls="    t : TOD; d : DT;",
        body="d := TIME_OF_DAY_TO_DT(t, t);"),
    "conversion of the wrong type": row(
        "E-TYPE-004", "r)", "argument of INT_TO_DINT: expected INT, found REAL; use REAL_TO_DINT",
        decls="    r : REAL; d : DINT;", body="d := INT_TO_DINT(r);"),
    "conversion of the target type": row(
        "E-TYPE-004", "d)", "argument of INT_TO_DINT: expected INT, found DINT; the value is a DINT already: "
        "no conversion is needed", decls="    d : DINT;", body="d := INT_TO_DINT(d);"),
    "a conversion's result is its target type": row(
        "E-TYPE-004", "INT_TO_DINT", "assignment: expected INT, found DINT; convert explicitly with DINT_TO_INT",
        decls="    i : INT;", body="i := INT_TO_DINT(i);"),
    "a constant widens MAX's type": row(
        "E-TYPE-004", "MAX", "assignment: expected INT, found DINT; convert explicitly with DINT_TO_INT",
        decls="    i : INT;", body="i := MAX(i, 40000);"),
    "MAX of enumeration values": _r(
        "E-TYPE-004", "c,", "MAX: expected an elementary value (ANY_ELEMENTARY), found Color",
        COLOR, "    c : Color;", "c := MAX(c, c);"),
    "ARRAY[*] in-out of another rank": _r(
        "E-CALL-011", "m)", "VAR_IN_OUT 'v' of S: expected a variable of type ARRAY[*] OF INT, found "
        "ARRAY[1..2, 1..2] OF INT (in-out parameters are passed by reference, without conversion)",
        "FUNCTION S : INT\nVAR_IN_OUT\n    v : ARRAY[*] OF INT;\nEND_VAR\nS := 1;\nEND_FUNCTION\n",
        "    m : ARRAY[1..2, 1..2] OF INT; x : INT;", "x := S(m);"),
    "a function calling itself": Row(
        "FUNCTION F : INT\nF := F() + 1;\nEND_FUNCTION\n", "E-REC-001", 2, "F()",
        "recursion: F calls F; IEC 61131-3 and OMRON NJ forbid recursion"),
    "two functions calling each other": Row(
        "FUNCTION F : INT\nF := G();\nEND_FUNCTION\nFUNCTION G : INT\nG := F();\nEND_FUNCTION\n",
        "E-REC-001", 2, "G()", "recursion: F calls G, G calls F; IEC 61131-3 and OMRON NJ forbid recursion"),
    "a PRIVATE property read outside": _r(
        "E-CALL-012", "k.P", "property K.P is PRIVATE",
        "FUNCTION_BLOCK K\nPROPERTY PRIVATE P : INT\nGET\n    P := 1;\nEND_GET\nEND_PROPERTY\n"
        "END_FUNCTION_BLOCK\n", "    k : K; x : INT;", "x := k.P;", "codesys"),
    "a variable spelled like an enumeration type": _r(
        "E-TYPE-009", "color.", "'.Red': expected a struct or function block instance, found INT",
        "TYPE\n    Color : (Red, Green);\nEND_TYPE\n", "    color : INT; x : INT;", "x := color.Red;", "codesys"),
    "a conversion's output": row(
        "E-CALL-002", "Q =>", "INT_TO_DINT has one input, IN; found 'Q'", decls="    d : DINT;",
        body="d := INT_TO_DINT(Q => d);"),
    "MAX of two literals in a SINT": row(
        "E-TYPE-004", "MAX", "assignment: expected SINT, found INT; convert explicitly with INT_TO_SINT",
        decls="    s : SINT;", body="s := MAX(1, 300);"),
    "1.5 MOD 2 typed operator by operator": row(
        "E-TYPE-001", "MOD", "MOD: expected integer operands, found LREAL", decls="    x : INT;", body="x := 1.5 MOD 2;"),
    "too few arguments, the result not used": row(
        "E-CALL-009", "LIMIT", "LIMIT: expected 3 argument(s), found 2", decls="    s : STRING[5];",
        body="s := LIMIT(5, 7);"),
    "a constant beyond a conversion's source type": row(
        "E-TYPE-005", "40000", "constant 40000 does not fit INT (range -32768..32767)", decls="    d : DINT;",
        body="d := INT_TO_DINT(40000);"),
    "a STRING conversion's input named X": row(
        "E-CALL-002", "X :=", "STRING_TO_INT has one input, IN; found 'X'", decls="    s : STRING[4]; i : INT;",
        body="i := STRING_TO_INT(X := s);"),
    "ENO into a CONSTANT": row(
        "E-ASSIGN-001", "k)", "ENO: 'k' is CONSTANT and cannot be written",
        decls="    i : INT;\nEND_VAR\nVAR CONSTANT\n    k : BOOL := TRUE;", body="i := ABS(IN := 1, ENO => k);"),
    # EN / ENO
    "EN an INT": row(
        "E-TYPE-004", "i,", "EN: expected BOOL, found INT; convert explicitly with INT_TO_BOOL",
        decls="    i : INT;", body="i := ABS(EN := i, IN := 1);"),
    "ENO into an INT": row(
        "E-TYPE-004", "i)", "ENO: expected INT, found BOOL; convert explicitly with BOOL_TO_INT",
        decls="    i : INT;", body="i := ABS(IN := 1, ENO => i);"),
}

ROWS = {**EXPRESSION_ROWS, **CALL_ROWS}


@pytest.mark.parametrize("name", list(ROWS))
def test_the_one_diagnostic_of_each_site_in_full(name):
    r = ROWS[name]
    assert diagnostics(r.text, r.dialect) == [expected(r)]


# ------------------------------------------------------------------ boundaries, both sides

# IEC 61131-3 3rd ed. table 10: the ranges of the integer and bit-string types.
RANGES = {
    "SINT": (-2**7, 2**7 - 1), "INT": (-2**15, 2**15 - 1), "DINT": (-2**31, 2**31 - 1),
    "LINT": (-2**63, 2**63 - 1), "USINT": (0, 2**8 - 1), "UINT": (0, 2**16 - 1),
    "UDINT": (0, 2**32 - 1), "ULINT": (0, 2**64 - 1), "BYTE": (0, 2**8 - 1),
    "WORD": (0, 2**16 - 1), "DWORD": (0, 2**32 - 1), "LWORD": (0, 2**64 - 1),
}


@pytest.mark.parametrize("name", list(RANGES))
def test_an_untyped_constant_fits_its_type_up_to_each_end(name):
    """The ends of the range are accepted (and stored as written), one beyond each
    end refused at the constant (E-TYPE-005, with the range)."""
    lo, hi = RANGES[name]
    decls = f"    x : {name}; y : {name};"
    main = after_one_scan(program(decls, f"x := {lo};\ny := {hi};"))
    assert (main["x"], main["y"]) == (lo, hi)
    for value in (lo - 1, hi + 1):
        body = f"x := {value};"
        assert diagnostics(program(decls, body)) == [
            ("E-TYPE-005", 5, 6, f"constant {value} does not fit {name} (range {lo}..{hi})")]


@pytest.mark.parametrize("name", list(RANGES))
def test_a_typed_literal_fits_its_type_up_to_each_end(name):
    lo, hi = RANGES[name]
    decls = f"    x : {name}; y : {name};"
    main = after_one_scan(program(decls, f"x := {name}#{lo};\ny := {name}#{hi};"))
    assert (main["x"], main["y"]) == (lo, hi)
    for value in (lo - 1, hi + 1):
        assert diagnostics(program(decls, f"x := {name}#{value};")) == [
            ("E-TYPE-005", 5, 6, f"literal {value} does not fit {name} (range {lo}..{hi})")]


def test_real_constants_up_to_the_largest_real():
    """binary32's largest finite value is 3.4028234664e38; a constant rounds to
    infinity as a REAL from half an ulp above it (3.40282357e38), so 3.4028235E38
    is a REAL and 3.4028236E38 (either sign) is not.  An LREAL holds up to
    1.7976931348623157e308; 1.8E308 is no double at all (an infinite literal)."""
    main = after_one_scan(program("    r : REAL; l : LREAL;", "r := -3.4028235E38;\nl := 1.7976931348623157E308;"))
    # (a REAL reads back as the shortest decimal of its binary32 value)
    assert (main["r"], main["l"]) == (-3.4028235e38, 1.7976931348623157e308)
    assert diagnostics(program("    r : REAL;", "r := -3.4028236E38;")) == [
        ("E-TYPE-005", 5, 6, "constant -3.4028236e+38 does not fit REAL (largest magnitude 3.4028235e+38)")]
    assert diagnostics(program("    l : LREAL;", "l := 1.8E308;")) == [
        ("E-TYPE-005", 5, 6, "a real literal does not fit LREAL (largest magnitude 1.7976931348623157e+308)")]


def test_the_sides_of_the_other_rules_that_are_accepted():
    """The value just inside each refused row of the table above: accepted, and
    where the value is seen, the value the standard gives."""
    cases = [
        ("    s : STRING[3];", "s := 'abc';", "iec"),                     # 3 characters fit STRING[3]
        ("    s : STRING[3];", "s := 'äb';", "nj"),                       # 3 bytes
        ("    u : UINT; i : INT;", "u := i;", "nj"),                      # the NJ casts INT to UINT
        ("    u : UDINT; d : DINT;", "u := d;", "nj"),                    # ... and DINT to UDINT
        ("    i : INT;", "i := i + 32767;", "iec"),
        ("    b : BOOL;", "b := 18446744073709551615 > 0;", "iec"),
        ("    x : INT;", "x := x / 1 + x MOD 1;", "iec"),
        ("    r : REF_TO INT; i : INT;", "r := REF(i); r := NULL;", "iec"),
        ("    b : BYTE; x : BOOL;", "x := b.7;", "nj"),
        ("    w : WORD; x : BYTE;", "x := w.%B1;", "codesys"),
        ("    w : LWORD; x : DWORD;", "x := w.%D1;", "codesys"),
        ("    a : ARRAY[1..3] OF INT; x : INT;", "x := a[1] + a[3];", "iec"),
        ("    m : ARRAY[1..2, 0..4] OF INT; x : INT;", "x := m[2, 4] + m[1, 0];", "iec"),
        ("    t : TIME; x : INT;", "t := t * x + x * t - t / x;", "iec"),
        ("    r : REF_TO INT; b : BOOL;", "b := r = NULL AND r <> r;", "iec"),
    ]
    for decls, body, dialect in cases:
        assert diagnostics(program(decls, body), dialect) == [], body


def test_boolean_zero_and_one_and_the_index_and_dimension_ends():
    main = after_one_scan(program(
        "    b0, b1 : BOOL; a : ARRAY[1..3, 5..9] OF INT; lo1, hi2 : DINT; s0, s1 : INT;",
        "b0 := 0; b1 := 1;\nlo1 := LOWER_BOUND(a, 1); hi2 := UPPER_BOUND(a, 2);\n"
        "s0 := SEL(0, 10, 20); s1 := SEL(1, 10, 20);"))
    assert (main["b0"], main["b1"]) == (False, True)
    assert (main["lo1"], main["hi2"]) == (1, 9)
    assert (main["s0"], main["s1"]) == (10, 20)


# ------------------------------------------------------------------ results the compiler reads

def test_calls_compute_what_the_standard_says():
    """Each kind of call the checker records a target (and a lowering) for, run:
    the values by hand (3rd ed. 6.6.2.5, tables 22-31)."""
    text = (
        "NAMESPACE NS\nFUNCTION Twice : INT\nVAR_INPUT\n    v : INT;\nEND_VAR\nTwice := 2 * v;\n"
        "END_FUNCTION\nEND_NAMESPACE\n"
        + F2 + program(
            "    i : INT := -5; d : DINT; r : REF_TO INT; x, y, z : INT; b1, b2, b3, e1, e2 : BOOL;"
            " w : WORD; t : TIME; k, q : INT;",
            "d := INT_TO_DINT(i);\nr := REF(i); x := r^ + 1;\ny := NS.Twice(21);\nz := F(b := 3, a := 4);\n"
            "b1 := GT(3, 2, 1); b2 := GT(3, 1, 2); b3 := NE(1, 2);\nk := ADD(1, 2, 3) + MUL(2, 3, 4) - SUB(10, 4);\n"
            "w := SHL(WORD#1, 4);\nt := MUL_TIME(T#1s, 3);\n"
            "i := ABS(EN := TRUE, IN := i, ENO => e1);\nq := q + ABS(EN := FALSE, IN := -7, ENO => e2);"))
    main = after_one_scan(text)
    assert (main["d"], main["x"], main["y"], main["z"]) == (-5, -4, 42, 7)
    assert (main["b1"], main["b2"], main["b3"]) == (True, False, True)
    assert main["k"] == 6 + 24 - 6
    assert main["w"] == 16
    assert main["t"] == "T#3s"
    assert (main["i"], main["e1"]) == (5, True)
    assert main["e2"] is False     # (the result of a call not executed is the implementation's: not read)


def test_folded_constants_are_recorded_with_their_values():
    """An expression of constants carries its folded value (`constants`: the
    compiler emits it instead of the expression): NOT of a bit string within its
    width, unary minus, a folded comparison, TIME scaled."""
    program_ = checked(program(
        "    w : WORD; y : BYTE; b : BOOL; i : INT; t : TIME;",
        "w := NOT WORD#0;\ny := NOT BYTE#5;\nb := NOT TRUE;\ni := -INT#5;\nb := 2 < 3;\nt := T#10s / 4;"))
    values = [program_.constants.get(id(s.value)) for s in body(program_)]
    assert values == [0xFFFF, 0xFA, False, -5, True, 2_500_000_000]
    assert [str(program_.expr_types[id(s.value)]) for s in body(program_)] == \
        ["WORD", "BYTE", "BOOL", "INT", "BOOL", "TIME"]


def test_a_call_refused_still_types_its_arguments():
    """One diagnostic per root cause, and none lost: the arguments of a call that is
    refused (an undeclared function, an unknown parameter, an argument too many)
    are still checked, so their own errors show."""
    assert diagnostics(program("    x : INT;", "x := Foo(zzz);")) == [
        ("E-DECL-001", 5, 6, "undeclared function 'Foo'"), ("E-DECL-001", 5, 10, "undeclared name 'zzz'")]
    assert diagnostics(F2 + program("    x : INT;", "x := F(c := zzz);")) == [
        ("E-CALL-002", 12, 8, "F has no parameter 'c' (parameters: a, b)"),
        ("E-DECL-001", 12, 13, "undeclared name 'zzz'")]
    assert diagnostics(program("    x : INT;", "x := ABS(1, zzz);")) == [
        ("E-CALL-006", 5, 13, "ABS: expected 1 argument(s), found 2"), ("E-DECL-001", 5, 13, "undeclared name 'zzz'")]
    assert diagnostics(program("    x : INT;", "x := SUB(1, zzz, 3);")) == [
        ("E-CALL-006", 5, 6, "SUB: expected 2 argument(s), found 3"), ("E-DECL-001", 5, 13, "undeclared name 'zzz'")]


def test_the_sides_of_the_call_rules_that_are_accepted():
    cases = [
        (F2, "    x : INT;", "x := F(1, 2) + F(b := 1, a := 2) + F(1, b := 2);", "iec"),
        ("FUNCTION S : INT\nVAR_IN_OUT\n    v : ARRAY[*] OF INT;\nEND_VAR\nS := 1;\nEND_FUNCTION\n",
         "    a : ARRAY[1..3] OF INT; b : ARRAY[0..9] OF INT; x : INT;", "x := S(a) + S(b);", "iec"),
        ("", "    i : INT; s : SINT; d : DINT; l : LREAL;",
         "d := INT_TO_DINT(s) + INT_TO_DINT(IN := i) + INT_TO_DINT(32767); l := REAL_TO_LREAL(1.5);", "iec"),
        ("", "    i : INT;", "i := MAX(i, 32767) + MAX(IN1 := 1, IN2 := 5, IN3 := 9);", "iec"),
        ("TYPE\n    Color : (Red, Green);\n    Light : (Red, Amber);\nEND_TYPE\n",
         "    c : Color; b : BOOL;", "b := c = Red; c := SEL(b, c, Red);", "iec"),
        ("", "    t : TON; b : BOOL; e : TIME;", "t(IN := TRUE, PT := T#1s, NOT Q => b, ET => e);", "iec"),
        ("", "    c : CTU;", "c(CU := TRUE, Reset := FALSE, PV := 3);", "nj"),
        ("", "    r : REAL;", "r := ADD(1.5, 2.5); r := MUL(IN1 := 2.0, IN2 := 0.5);", "iec"),   # the REALs of r
        ("", "    it : I; b : BOOL;", "it := NULL; b := it = NULL;", "iec"),
    ]
    for prefix, decls, body_, dialect in cases:
        prefix = "INTERFACE I\nEND_INTERFACE\n" if "it : I" in decls else prefix
        assert diagnostics(prefix + program(decls, body_), dialect) == [], body_


def test_what_standard_functions_give():
    """MUX's inputs after K are IN0, IN1, ... (3rd ed. table 31); TRUNC gives the
    integer type its context wants (a LINT holds 10^12); SHL of an untyped literal
    is in the smallest bit string holding it (1 << 9 leaves a BYTE), in a WORD
    where a WORD is wanted; a function or FB that declares its own EN runs its
    body with EN FALSE (it is an ordinary input then, 6.6.1.2)."""
    text = ("FUNCTION P : INT\nVAR_INPUT\n    EN : BOOL;\n    v : INT;\nEND_VAR\n"
            "IF EN THEN P := v; ELSE P := -v; END_IF;\nEND_FUNCTION\n"
            "FUNCTION_BLOCK Q\nVAR_INPUT\n    EN : BOOL;\nEND_VAR\nVAR_OUTPUT\n    y : INT;\nEND_VAR\n"
            "IF EN THEN y := 1; ELSE y := 2; END_IF;\nEND_FUNCTION_BLOCK\n"
            + program("    m1, m2, neg : INT; l : LINT; b : BOOL; w : WORD; q : Q; r : REAL; x : LREAL;",
                      "m1 := MUX(K := 1, IN0 := 10, IN1 := 20, IN2 := 30); m2 := MUX(2, 10, 20, 30);\n"
                      "l := TRUNC(1.0E12);\nb := SHL(1, 9) = 0; w := SHL(1, 9);\nneg := P(EN := FALSE, v := 3);\n"
                      "q(EN := FALSE);\nx := MAX(r, 0.1);"))
    main = after_one_scan(text)
    assert (main["m1"], main["m2"], main["l"]) == (20, 30, 10**12)
    assert (main["b"], main["w"]) == (True, 512)
    assert (main["neg"], main["q.y"]) == (-3, 2)
    # MAX(r, 0.1): the literal takes r's type REAL (6.6.2.5), widened to LREAL after
    assert main["x"] == 0.10000000149011612


def test_folding_follows_the_dialect():
    """`(C + 1) / 2` with C = INT#32767: IEC computes the expression exactly and
    wraps where it is stored (16384); the NJ wraps inside the expression (W501:
    an expression is evaluated in its operands' type): 32768 wraps to -32768, /2
    is -16384.  Likewise `(RC + 1.0) - RC` with RC = REAL#1.0E8: exact in a double
    (1.0), but on the NJ each REAL operation rounds to binary32 (1e8 + 1 is 1e8): 0.0.
    The NJ divides UDINT by DINT as UDINT (its ranking): DINT#-1 is 4294967295 there."""
    decls = ("    x : INT; r : REAL; u, v : UDINT;\nEND_VAR\nVAR CONSTANT\n    C : INT := 32767;"
             " RC : REAL := 1.0E8;")
    body_ = "x := (C + 1) / 2;\nr := (RC + 1.0) - RC;\nu := UDINT#10 / DINT#-1; v := UDINT#4294967295 / DINT#-1;"
    iec = after_one_scan(program(decls, body_.replace("u := UDINT#10 / DINT#-1; v := UDINT#4294967295 / DINT#-1;",
                                                      "")))
    assert (iec["x"], iec["r"]) == (16384, 1.0)
    nj = after_one_scan(program(decls, body_), "nj")
    assert (nj["x"], nj["r"], nj["u"], nj["v"]) == (-16384, 0.0, 0, 1)


def test_time_arithmetic_of_constants():
    """TIME * number rounds to the nearest ns, ties to even (T#10ns * 0.25 is 2.5 ns:
    T#2ns), number * TIME is the same, TIME / number truncates like the run time."""
    main = after_one_scan(program("    a, b, c, d, f : TIME; e : BOOL;",
                                  "a := T#10ns * 0.25; b := 3 * T#1s; c := T#1s / 4; d := -T#1s;\n"
                                  "e := T#10ns * 0.25 = T#2ns; f := T#10ns * 0.27;"))
    assert (main["a"], main["b"], main["c"], main["d"]) == ("T#2ns", "T#3s", "T#250ms", "T#-1s")
    assert (main["e"], main["f"]) == (True, "T#3ns")


def test_strings_take_the_length_of_their_literal():
    """A string literal is a STRING of its length (at least 1), a "..." literal a
    WSTRING; STRING lengths count bytes under --dialect nj (UTF-8)."""
    found = checked(program("    s : STRING[10]; w : WSTRING[10];", "s := '';\ns := 'abc';\nw := \"äbc\";"))
    assert [str(found.expr_types[id(st.value)]) for st in body(found)] == ["STRING[1]", "STRING[3]", "WSTRING[3]"]
    nj = checked(program("    s : STRING[10];", "s := 'äbc';"), "nj")
    assert str(nj.expr_types[id(body(nj)[0].value)]) == "STRING[4]"


OO = ("INTERFACE I\nMETHOD M : INT\nEND_METHOD\nEND_INTERFACE\n"
      "FUNCTION_BLOCK A IMPLEMENTS I\nVAR\n    n : INT := 5;\nEND_VAR\n"
      "METHOD PUBLIC M : INT\nM := 7;\nEND_METHOD\n"
      "METHOD PUBLIC Twice : INT\nTwice := 2 * M();\nEND_METHOD\n"
      "METHOD PUBLIC Nothing\nn := n + 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
      "FUNCTION_BLOCK B EXTENDS A\nMETHOD PUBLIC M : INT\nM := SUPER.M() + 100;\nEND_METHOD\n"
      "END_FUNCTION_BLOCK\n")


def test_each_kind_of_method_call_runs_its_method():
    """3rd ed. 6.6.5: a method called on an instance (the most derived override), through
    an interface, on the instance itself inside another method (M() alone), and the
    parent's through SUPER; a method without a result as a statement."""
    main = after_one_scan(OO + program(
        "    a : A; b : B; it : I; x, y, z, w : INT;",
        "it := b; x := a.M(); y := b.M(); z := it.M(); w := b.Twice(); a.Nothing(); a.Nothing();"))
    assert (main["x"], main["y"], main["z"], main["w"]) == (7, 107, 107, 214)
    assert main["a.n"] == 7


def test_properties_and_this():
    """CODESYS: a property reads through its GET (a PRIVATE one inside its own FB); inside
    its FB, THIS.n reads a VAR that is not visible from outside; an enumeration variable spelled like its type
    takes the type's values with a dot."""
    text = ("TYPE\n    State : (Idle, Run);\nEND_TYPE\n"
            "FUNCTION_BLOCK K\nVAR\n    n : INT := 4;\nEND_VAR\nVAR_OUTPUT\n    q : INT;\nEND_VAR\n"
            "PROPERTY PUBLIC P : INT\nGET\n    P := THIS.n * 10;\nEND_GET\nEND_PROPERTY\n"
            "PROPERTY PRIVATE Hidden : INT\nGET\n    Hidden := 1;\nEND_GET\nEND_PROPERTY\n"
            "q := THIS.n + THIS.Hidden;\nEND_FUNCTION_BLOCK\n"
            + program("    k : K; x, y : INT; state : State := State.Run;", "k(); x := k.P; y := k.q;"))
    main = after_one_scan(text, "codesys")
    assert (main["x"], main["y"], main["state"]) == (40, 5, "Run")


def test_constants_given_in_call_form_are_constants():
    """ADD(1, 2) is the constant 3 wherever a constant is needed (an array bound);
    an undeclared argument is the call's one diagnostic."""
    main = after_one_scan(program("    a : ARRAY[0..ADD(1, 2)] OF INT; n : DINT;", "n := UPPER_BOUND(a, 1);"))
    assert main["n"] == 3
    assert diagnostics(program("    x : INT;", "x := ADD(zzz, 1) + MAX(zzz, 1);")) == [
        ("E-DECL-001", 5, 10, "undeclared name 'zzz'"), ("E-DECL-001", 5, 24, "undeclared name 'zzz'")]


def test_enable_runs_or_skips_a_function_block():
    """6.6.1.2: an FB called with EN FALSE does not run (its CV stays 0) and gives
    ENO FALSE; with EN TRUE it runs."""
    main = after_one_scan(program("    c, d : CTU; e1, e2 : BOOL;",
                                  "c(EN := FALSE, CU := TRUE, PV := 3, ENO => e1);\n"
                                  "d(EN := TRUE, CU := TRUE, PV := 3, ENO => e2);"))
    assert (main["c.CV"], main["e1"], main["d.CV"], main["e2"]) == (0, False, 1, True)


def test_codesys_adr_and_strings_of_max():
    main = after_one_scan(program("    i : INT := 41; p : POINTER TO INT; x : INT; s : STRING[5];",
                                  "p := ADR(i); x := p^ + 1; s := MAX('ab', 'b');"), "codesys")
    assert (main["x"], main["s"]) == (42, "b")


def test_an_untyped_constant_is_typed_to_hold_every_intermediate_value():
    """The module's rule: a folded `100 + 100 - 100` into a SINT is a SINT (100 fits)
    but its part `100 + 100` (200) is an INT, and carries its value 200."""
    found = checked(program("    s : SINT;", "s := 100 + 100 - 100;"))
    outer = body(found)[0].value
    inner = outer.left
    assert (str(found.expr_types[id(outer)]), str(found.expr_types[id(inner)])) == ("SINT", "INT")
    assert (found.constants[id(outer)], found.constants[id(inner)]) == (100, 200)


# ------------------------------------------------------------------ every expression typed

_EXPRESSIONS = (ast.IntLiteral, ast.RealLiteral, ast.BoolLiteral, ast.StringLiteral, ast.TimeLiteral,
                ast.DateTimeLiteral, ast.EnumLiteral, ast.Name, ast.Member, ast.Index, ast.Deref,
                ast.BitAccess, ast.DirectVar, ast.NullLiteral, ast.Unary, ast.Binary, ast.Call)
ACCEPT = sorted((Path(__file__).parent / "corpus" / "accept").glob("*.st"))


def test_every_expression_of_an_accepted_program_has_its_type():
    """The contract of expressions.py ("every expression node gets a type in
    CheckedProgram.expr_types"), which the compiler reads: over the accept
    corpus, every expression of a body and of what a call in operator form is
    lowered to has its type, but for what is no value: a callee (a POU's name),
    a call as a statement, and the type named before the dot of a CODESYS
    enumeration value (`Light.Red`)."""
    untyped = []
    for path in ACCEPT:
        text = path.read_text(encoding="utf-8")
        dialect = re.match(r"\(\* dialect (iec|nj|codesys)\b", text)
        program_ = load_texts({path.name: text}, dialect[1] if dialect else "iec").program
        roots = [[info.node.body for info in program_.pous.values()
                  if info.node is not None and info.node.pos.file == path.name], list(program_.lowered.values())]
        no_value = set()
        for node in walk(roots):
            if isinstance(node, ast.Call):
                no_value.update(id(n) for n in walk(node.callee))
            elif isinstance(node, ast.CallStmt):
                no_value.add(id(node.call))
            elif isinstance(node, ast.Member) and isinstance(node.base, ast.Name) \
                    and isinstance(program_.expr_types.get(id(node)), T.EnumType):
                no_value.add(id(node.base))
        untyped += [(path.name, n.pos.line, type(n).__name__) for n in walk(roots)
                    if isinstance(n, _EXPRESSIONS) and id(n) not in program_.expr_types and id(n) not in no_value]
    assert untyped == []


def test_a_variable_named_super_is_a_variable():
    """CODESYS: SUPER names the parent only where no variable has that name."""
    main = after_one_scan("FUNCTION_BLOCK A\nMETHOD PUBLIC M : INT\nM := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
                          + program("    SUPER : A; x : INT;", "x := SUPER.M();"), "codesys")
    assert main["x"] == 1


def test_time_and_date_arithmetic():
    """3rd ed. table 36 (ADD/SUB of TIME, TOD, DT, DATE): the result types, checked by
    comparing with literals of the expected type in the program itself."""
    main = after_one_scan(program(
        "    b : ARRAY[1..7] OF BOOL;",
        "b[1] := TOD#10:00:00 + T#1h = TOD#11:00:00;\n"
        "b[2] := DT#2020-01-01-00:00:00 + T#1d = DT#2020-01-02-00:00:00;\n"
        "b[3] := D#2020-01-02 - D#2020-01-01 = T#24h;\n"
        "b[4] := TOD#10:00:00 - TOD#09:30:00 = T#30m;\n"
        "b[5] := DT#2020-01-02-00:00:00 - DT#2020-01-01-00:00:00 = T#1d;\n"
        "b[6] := TOD#10:00:00 - T#1h = TOD#09:00:00;\n"
        "b[7] := DT#2020-01-01-01:00:00 - T#1h = DT#2020-01-01-00:00:00;"))
    assert [main[f"b[{i}]"] for i in range(1, 8)] == [True] * 7

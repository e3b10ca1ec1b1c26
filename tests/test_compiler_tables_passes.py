"""The optimiser passes' table (issue 16, session 13; docs/mutation.md, compiler, "Session 13,
optimise"): every pass x (on alone, off, every pass on) x a family of programs that reaches
each of its decisions, the observable result checked in full.

Each row is a PROGRAM Main (with the POUs it calls), the values of Main's variables after
its scans worked out by hand (IEC 61131-3's meaning of the statements; REAL arithmetic in
binary64 / float32 as Python's own float and NumPy's float32 give it, stated where it
matters), and its faults (code, line, scan).  A pass may change only speed, so the row
holds with the pass alone (with the passes it works inside of: `NEEDS`), with none and with
every pass; and the NJ time charged each scan is the same in the three.  Where the decision
is only a shortcut taken or not, the row also names the shape the pass's contract gives the
generated Python (`shape`: a pattern found in the POU's code with the pass on and not with
every pass off; `never`: one found in neither, where the pass must not take the shortcut).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller

EVERY, NONE = Optimisations(), Optimisations.none()

# the passes a pass works inside of (optimise/__init__.py): switched on with it when "alone"
NEEDS = {"finite": ("reuse",), "stores_read": ("reuse",), "spread": ("aliases", "stores"),
         "deferred": ("unused",), "chains": ("fastpath",), "cse": ("unroll",),
         "fuse": ("unroll", "cse"), "vector": ("unroll", "cse"), "shortcut": ("branches",)}


@dataclass
class Row:
    pass_: str
    name: str
    src: str
    expect: dict                     # Main's variable -> value after the scans
    faults: list = field(default_factory=list)      # (code, line, scan)
    scans: int = 1
    shape: tuple | None = None       # (POU, pattern) in the code with the pass, not without
    never: tuple | None = None       # (POU, pattern) in no build
    dialects: tuple = ("iec",)
    budget_ns: int | None = None
    with_: tuple = ()                # more passes the row's decision needs ("alone")
    gone: tuple | None = None        # (POU, pattern) in the code without the pass, not with it
    every_too: bool = True           # `shape` and `gone` hold with every pass on too (not where
                                     # a later pass keeps the code as before beside the new)

    @property
    def id(self) -> str:
        return f"{self.pass_}: {self.name}"


def modes(pass_: str, with_: tuple = ()) -> dict[str, Optimisations]:
    return {"alone": Optimisations.only(pass_, *NEEDS.get(pass_, ()), *with_), "none": NONE, "every": EVERY}


def outcome(row: Row, optimise: Optimisations, dialect: str):
    """(Main's values named in the row, faults, the budget left after each scan, the code)."""
    compiled = compile_program(api.load_text(row.src, "m.st", dialect).program, optimise=optimise)
    controller = Controller(compiled, time_limit_ns=row.budget_ns)
    main = controller.add_program("Main")
    left = []
    for _ in range(row.scans):
        controller.run(1)
        left.append(controller.ctx.budget)
    values = {}
    for name in row.expect:
        value = main
        for part in name.split("."):
            value = getattr(value, "v_" + part.upper())
        values[name] = list(value) if isinstance(value, list) else value
    return values, [(f.code, f.line, f.scan) for f in controller.faults], left, compiled.python_sources


def check(row: Row) -> None:
    for dialect in row.dialects:
        charged = {}
        for mode, optimise in modes(row.pass_, row.with_).items():
            values, faults, left, sources = outcome(row, optimise, dialect)
            assert (values, faults) == (row.expect, row.faults), (dialect, mode)
            charged[mode] = left
            if mode == "every" and not row.every_too:
                pass
            elif row.shape is not None:
                pou, pattern = row.shape
                assert bool(re.search(pattern, sources[pou])) == (mode != "none"), (dialect, mode, sources[pou])
            if row.gone is not None and (mode != "every" or row.every_too):
                pou, pattern = row.gone
                assert bool(re.search(pattern, sources[pou])) == (mode == "none"), (dialect, mode, sources[pou])
            if row.never is not None:
                pou, pattern = row.never
                assert not re.search(pattern, sources[pou]), (dialect, mode, sources[pou])
        assert charged["alone"] == charged["none"] == charged["every"], dialect


ROWS: list[Row] = []


def row(*args, **kwargs) -> None:
    ROWS.append(Row(*args, **kwargs))


def main(decls: str, body: str, before: str = "") -> str:
    return f"{before}\nPROGRAM Main\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n"


# ------------------------------------------------------------------------------------ sets
# `X = a OR X = b ...` -> `X in {a, b}`; `X <> a AND X <> b` -> `X not in {...}`: a run of
# at least two comparisons of one plain integer (or enumeration) variable with constants.

for t, x, hit in (("SINT", -128, 1), ("INT", 7, 1), ("DINT", 9, 0), ("LINT", -5, 1), ("USINT", 255, 1),
                  ("UINT", 3, 0), ("UDINT", 4294967295, 1), ("ULINT", 0, 1), ("BYTE", 16, 1),
                  ("WORD", 65535, 1), ("DWORD", 1, 0), ("LWORD", 2, 1)):
    values = {"SINT": (-128, 1), "INT": (7, 12), "DINT": (8, 10), "LINT": (3, -5), "USINT": (255, 4),
              "UINT": (4, 5), "UDINT": (4294967295, 0), "ULINT": (0, 1), "BYTE": (16, 32),
              "WORD": (65535, 1), "DWORD": (2, 3), "LWORD": (1, 2)}[t]
    row("sets", f"OR of two {t} tests", main(f"x : {t} := {x}; r, s : BOOL;",
        f"r := x = {values[0]} OR x = {values[1]};\ns := x <> {values[0]} AND x <> {values[1]};"),
        {"r": bool(hit), "s": not hit}, shape=("MAIN", r" in \{"))

row("sets", "the constant first", main("x : INT := 5; r : BOOL;", "r := 4 = x OR 5 = x OR 6 = x;"),
    {"r": True}, shape=("MAIN", r"v_X in \{4, 5, 6\}"))
row("sets", "a run inside a longer chain keeps the other operands in order",
    main("x : INT := 3; y : INT := 1; r, s, u : BOOL;",
         "r := y = 2 OR x = 1 OR x = 3 OR y = 7;\ns := y = 1 OR x = 1 OR x = 2;\n"
         "u := y <> 1 AND x <> 1 AND x <> 2;"),
    {"r": True, "s": True, "u": False}, shape=("MAIN", r"\(v_X in \{1, 3\}\)"))
row("sets", "two runs of two variables", main("x : INT := 3; y : INT := 8; r, s : BOOL;",
    "r := x = 1 OR x = 2 OR y = 8 OR y = 9;\ns := x <> 3 AND x <> 4 AND y <> 5 AND y <> 6;"),
    {"r": True, "s": False}, shape=("MAIN", r"v_Y not in \{5, 6\}"))
row("sets", "one comparison is no run", main("x : INT := 2; y : INT := 2; r : BOOL;",
    "r := x = 1 OR y = 2 OR x = 3;"), {"r": True}, never=("MAIN", r" in \{"))
row("sets", "a REAL is not tested by membership", main("x : REAL := 2.0; r : BOOL;",
    "r := x = 1.0 OR x = 2.0;"), {"r": True}, never=("MAIN", r" in \{"))
row("sets", "a named constant is no variable", main("r : BOOL; END_VAR VAR CONSTANT c : INT := 2;",
    "r := c = 1 OR c = 2;"), {"r": True}, never=("MAIN", r" in \{"))
row("sets", "an enumeration", main("s : State := Run; r, q : BOOL;",
    "r := s = Idle OR s = Run;\nq := s <> Idle AND s <> Run;", before="TYPE State : (Idle, Run, Stop); END_TYPE"),
    {"r": True, "q": False}, shape=("MAIN", r"v_S in \{"))
row("sets", "an FB's own slot", main("f : Fb; r : BOOL;", "f(); r := f.r;", before="""
FUNCTION_BLOCK Fb
VAR x : DINT := 40; END_VAR VAR_OUTPUT r : BOOL; END_VAR
r := x = 10 OR x = 20 OR x = 40;
END_FUNCTION_BLOCK"""), {"r": True}, shape=("FB", r"self\.v_X in \{10, 20, 40\}"))
row("sets", "a global", main("r : BOOL;", "r := g = 5 OR g = 6;",
    before="VAR_GLOBAL g : INT := 6; END_VAR"), {"r": True}, shape=("MAIN", r"_G\.v_G in \{5, 6\}"))
row("sets", "an in-out is read through its reference", main("x : INT := 3; r : BOOL;", "r := F(x);", before="""
FUNCTION F : BOOL
VAR_IN_OUT v : INT; END_VAR
F := v = 2 OR v = 3;
END_FUNCTION"""), {"r": True}, never=("F", r" in \{"))
row("sets", "a FUNCTION's local", main("r : BOOL;", "r := F(12);", before="""
FUNCTION F : BOOL
VAR_INPUT v : INT; END_VAR
F := v = 2 OR v = 12 OR v = 3;
END_FUNCTION"""), {"r": True}, shape=("F", r"v_V in \{2, 12, 3\}"))
row("sets", "in an IF condition", main("x : UINT := 9; y : INT;",
    "IF x = 8 OR x = 9 THEN y := 1; ELSE y := 2; END_IF;"), {"y": 1}, shape=("MAIN", r"v_X in \{8, 9\}"))
row("sets", "a comparison of one variable with another is no test",
    main("x : INT := 3; y : INT := 3; r : BOOL;", "r := x = y OR x = 1;"), {"r": True}, never=("MAIN", r" in \{"))
row("sets", "a mixed AND inside an OR", main("x : INT := 3; r : BOOL; b : BOOL := TRUE;",
    "r := (x = 1 OR x = 3) AND b;"), {"r": True}, shape=("MAIN", r"v_X in \{1, 3\}"))


# ----------------------------------------------------------------------------------- wraps
# A store of MIN/MAX of integers is not wrapped when the inputs' range lies in the target's
# type (with every pass, MIN/MAX of two is `(b if a > b else a)`: calls.py `_selected_pair`). IEC: `+ -` exact, the store wraps; nj (W501 6-5-3): each input wraps into its type
# first.  s = t = 32767, u = e = -32768, w : USINT = 255, d : DINT = 7.

WRAPS = main("s : INT := 32767; t : INT := 32767; u : INT := -32768; w : USINT := 255; "
             "e : INT := -32768; d : DINT := 7; i : INT := -20000; j : INT := 20000; m, n : INT; "
             "wide : DINT;",
             "s := MIN(s + 1, 2);\nt := MAX(t + 1, 2);\nu := MAX(u - 1, -3);\nw := MIN(w + 1, 10);\n"
             "e := MIN(e - 1, 0);\nd := MAX(d, 1);\nm := MIN(i * 2, 5);\nn := MAX(j * 2, 5);\n"
             "wide := MIN(j, 5) + MAX(i, -7);")
row("wraps", "iec: exact inputs, the store wraps", WRAPS,
    # MIN(32768, 2) = 2; MAX(32768, 2) = 32768 -> -32768; MAX(-32769, -3) = -3;
    # MIN(256, 10) = 10; MIN(-32769, 0) -> 32767; MAX(7, 1) = 7; MIN(-40000, 5) -> 25536;
    # MAX(40000, 5) -> -25536; 5 + -7 = -2
    {"s": 2, "t": -32768, "u": -3, "w": 10, "e": 32767, "d": 7, "m": 25536, "n": -25536, "wide": -2},
    shape=("MAIN", r"self\.v_S = (?:(?:_sf_MIN|min)\(\(self\.v_S \+ 1\), 2\)|\(2 if \(_t\d+ := \(self\.v_S \+ 1\)\) > 2 else _t\d+\))"),
    never=("MAIN", r"self\.v_T = (?:_sf_MAX|max|\(2 if)|self\.v_E = (?:_sf_MIN|min|\(0 if)|self\.v_M = (?:_sf_MIN|min|\(5 if)|self\.v_N = (?:_sf_MAX|max|\(5 if)"))
row("wraps", "iec: an input's declared range fits", WRAPS, {"u": -3, "w": 10, "d": 7},
    shape=("MAIN", r"self\.v_U = (?:(?:_sf_MAX|max)\(\(self\.v_U - 1\), -3\)|\(-3 if \(_t\d+ := \(self\.v_U - 1\)\) < -3 else _t\d+\))"))
row("wraps", "iec: a USINT sum", WRAPS, {"w": 10}, shape=("MAIN", r"self\.v_W = (?:(?:_sf_MIN|min)\(\(self\.v_W \+ 1\), 10\)|\(10 if \(_t\d+ := \(self\.v_W \+ 1\)\) > 10 else _t\d+\))"))
row("wraps", "iec: a DINT variable", WRAPS, {"d": 7}, shape=("MAIN", r"self\.v_D = (?:(?:_sf_MAX|max)\(self\.v_D, 1\)|\(1 if \(_t\d+ := self\.v_D\) < 1 else _t\d+\))"))
row("wraps", "nj: each input wraps first", WRAPS,
    # s + 1 -> -32768: MIN = -32768; t + 1 -> -32768: MAX = 2; u - 1 -> 32767; w + 1 -> 0;
    # e - 1 -> 32767: MIN = 0; i * 2 -> 25536: MIN = 5; j * 2 -> -25536: MAX = 5
    {"s": -32768, "t": 2, "u": 32767, "w": 0, "e": 0, "d": 7, "m": 5, "n": 5, "wide": -2}, dialects=("nj",),
    shape=("MAIN", r"self\.v_T = (?:(?:_sf_MAX|max)\(|\(2 if )"))

# ---------------------------------------------------------------------------------- halves
# A CASE of at least six clauses with integer labels and no ELSE tests `sel < P` first.
# One selector value a scan (n = 0, 1, ...), y kept where no clause matches.

HALVES = """CASE n OF
1: y := 10;
2, 3: y := 20;
4..6: y := 30;
8: y := 40;
9, 11: y := 50;
12..13: y := 60;
15: y := 70;
END_CASE;
out[n] := y; n := n + 1;"""
row("halves", "seven clauses, values 0..16", main("n, y : INT; out : ARRAY[0..16] OF INT;", HALVES),
    {"out": [0, 10, 20, 20, 30, 30, 30, 30, 40, 50, 50, 50, 60, 60, 60, 70, 70], "n": 17}, scans=17,
    shape=("MAIN", r"if _t\d+ < \d+:"))
row("halves", "negative labels", main("n, y : INT := -6; out : ARRAY[-6..6] OF INT;", """CASE n OF
-5: y := 1;
-4, -3: y := 2;
-2..-1: y := 3;
0: y := 4;
2: y := 5;
4..5: y := 6;
END_CASE;
out[n] := y; n := n + 1;"""), {"out": [-6, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 6], "n": 7}, scans=13,
    shape=("MAIN", r"if _t\d+ < -?\d+:"))
row("halves", "an ELSE keeps the clauses in a row", main("n, y : INT; out : ARRAY[0..16] OF INT;",
    HALVES.replace("END_CASE", "ELSE y := -1;\nEND_CASE")),
    {"out": [-1, 10, 20, 20, 30, 30, 30, -1, 40, 50, -1, 50, 60, 60, -1, 70, -1]}, scans=17,
    never=("MAIN", r"if _t\d+ < \d+:"))
row("halves", "five clauses are tested in a row", main("n, y : INT; out : ARRAY[0..6] OF INT;", """CASE n OF
1: y := 1; 2: y := 2; 3: y := 3; 4: y := 4; 5: y := 5;
END_CASE;
out[n] := y; n := n + 1;"""), {"out": [0, 1, 2, 3, 4, 5, 5]}, scans=7, never=("MAIN", r"if _t\d+ < \d+:"))
row("halves", "six clauses", main("n, y : INT; out : ARRAY[0..7] OF INT;", """CASE n OF
1: y := 1; 2: y := 2; 3: y := 3; 4: y := 4; 5: y := 5; 6: y := 6;
END_CASE;
out[n] := y; n := n + 1;"""), {"out": [0, 1, 2, 3, 4, 5, 6, 6]}, scans=8, shape=("MAIN", r"if _t\d+ < \d+:"))
row("halves", "labels written out of order", main("n, y : INT; out : ARRAY[0..9] OF INT;", """CASE n OF
8: y := 8; 1: y := 1; 6: y := 6; 3: y := 3; 5: y := 5; 2: y := 2; 7: y := 7;
END_CASE;
out[n] := y; n := n + 1;"""), {"out": [0, 1, 2, 3, 3, 5, 6, 7, 8, 8]}, scans=10)
row("halves", "a DWORD selector", main("n : INT; w : DWORD; y : INT; out : ARRAY[0..8] OF INT;", """w := INT_TO_DWORD(n);
CASE w OF
1: y := 1; 2: y := 2; 3: y := 3; 4: y := 4; 5: y := 5; 16#7: y := 7;
END_CASE;
out[n] := y; n := n + 1;"""), {"out": [0, 1, 2, 3, 4, 5, 5, 7, 7]}, scans=9, shape=("MAIN", r"if _t\d+ < \d+:"))

# -------------------------------------------------------------------------------- shortcut
# An IF condition tested in place: AND/OR of BOOLs as `and`/`or`; an AND/OR of comparisons
# whose right one cannot fault: `and`/`or` wherever it stands.

row("shortcut", "AND and OR in an IF", main("a, c : BOOL; b : BOOL := TRUE; y : INT;",
    "IF a AND b OR c THEN y := 1; ELSIF b OR a AND c THEN y := 2; END_IF;"), {"y": 2},
    shape=("MAIN", r"if \(?\(?self\.v_A and self\.v_B\)? or self\.v_C\)?:"))
row("shortcut", "comparisons in a store", main("x : LREAL := 2.0; s : LREAL := 3.0; r, q : BOOL;",
    "r := x >= 0.0 AND x <= s;\nq := x < 0.0 OR x > s;"), {"r": True, "q": False},
    shape=("MAIN", r"self\.v_R = \(True if \(\((?:self\.)?v_X >= 0\.0\) and \((?:self\.)?v_X <= self\.v_S\)\) else False\)"))
row("shortcut", "a right operand that may fault is evaluated", main("k : INT; x : REAL := -1.0; r : BOOL;",
    "r := (x > 0.0) AND (10 / k > 1);"), {"r": False}, faults=[("F-DIV-ZERO", 4, 1)],
    never=("MAIN", r" and "))
row("shortcut", "a call in the condition runs", main("a : BOOL; y, c : INT;",
    "IF a AND Count() THEN y := 1; END_IF;\nc := Calls;", before="""VAR_GLOBAL Calls : INT; END_VAR
FUNCTION Count : BOOL
Calls := Calls + 1; Count := TRUE;
END_FUNCTION"""), {"y": 0, "c": 1}, never=("MAIN", r" and "))
row("shortcut", "NOT and XOR", main("a : BOOL := TRUE; b, c : BOOL; y : INT;",
    "IF NOT a OR (b XOR a) AND NOT c THEN y := 3; END_IF;"), {"y": 3})
row("shortcut", "a bit string's AND is a bit operation", main("a : WORD := 6; b : WORD := 3; y : INT; w : WORD := 16#F0;",
    "IF (a AND b) = 2 THEN y := 1; END_IF;\nIF (w OR 16#0F) = 16#FF THEN y := y + 10; END_IF;"), {"y": 11},
    never=("MAIN", r" and | or "))

# -------------------------------------------------------------------------------- branches
# An IF whose conditions cannot fault is a plain if/elif; a CASE selector that cannot fault
# is read without a guard.  Conditions that may fault keep the guarded branch index.

row("branches", "conditions that cannot fault", main("x : INT := 5; y : INT; r : LREAL := 2.0;",
    "IF x < 3 THEN y := 1; ELSIF x * 2 = 10 AND r > 1.0 THEN y := 2; ELSE y := 3; END_IF;"), {"y": 2},
    shape=("MAIN", r"\n        elif \("))
row("branches", "a condition that faults runs no branch", main("x : INT := 5; k : INT; y : INT := 9;",
    "IF x < 3 THEN y := 1; ELSIF x / k = 1 THEN y := 2; ELSE y := 3; END_IF;"), {"y": 9},
    faults=[("F-DIV-ZERO", 4, 1)], never=("MAIN", r"elif \(self\.v_X // "))
row("branches", "an index that faults in a condition", main("i : INT := 4; a : ARRAY[1..3] OF INT; y : INT := 9;",
    "IF a[i] = 0 THEN y := 1; ELSE y := 2; END_IF;"), {"y": 9}, faults=[("F-INDEX", 4, 1)])
row("branches", "a CASE selector that cannot fault", main("x : INT := 2; y : INT;",
    "CASE x + 1 OF 1: y := 1; 3: y := 3; ELSE y := 4; END_CASE;"), {"y": 3}, shape=("MAIN", r"if True:"))
row("branches", "a CASE selector that faults runs no clause", main("i : INT := 4; a : ARRAY[1..3] OF INT; y : INT := 9;",
    "CASE a[i] OF 0: y := 1; ELSE y := 2; END_CASE;"), {"y": 9}, faults=[("F-INDEX", 4, 1)],
    never=("MAIN", r"if True:"))
row("branches", "an in-out read in a condition", main("x : INT := 4; y : INT;", "y := F(x);", before="""
FUNCTION F : INT
VAR_IN_OUT v : INT; END_VAR
IF v > 3 THEN F := 1; ELSE F := 2; END_IF;
END_FUNCTION"""), {"y": 1})
row("branches", "IF without ELSE, no branch taken", main("x : INT := 1; y : INT := 7;",
    "IF x > 1 THEN y := 1; ELSIF x > 2 THEN y := 2; END_IF;"), {"y": 7})

# --------------------------------------------------------------------------------- unguard
# No `try` around an assignment that cannot raise; kept where Python can raise.

row("unguard", "a local set from locals with + - *", main("a : LREAL := 1.5; b : LREAL := 2.0; c : LREAL;",
    "c := a * b - a + 0.25;"), {"c": 1.75}, shape=("MAIN", r"\n        self\.v_C = "))
row("unguard", "a division keeps its handler", main("a : INT := 1; k : INT; c : INT := 5;",
    "c := a / k;\nc := c + 1;"), {"c": 6}, faults=[("F-DIV-ZERO", 4, 1)], never=("MAIN", r"\n        self\.v_C = \(self"))
row("unguard", "a store at a literal index of an own array", main("a : ARRAY[1..3] OF INT; x : INT := 4;",
    "a[2] := x + 1;"), {"a": [0, 5, 0]}, shape=("MAIN", r"\n        v_A\[1\] = "))
row("unguard", "a store at a variable index keeps its handler", main("a : ARRAY[1..3] OF INT; i : INT := 4; y : INT;",
    "a[i] := 1;\ny := 2;"), {"a": [0, 0, 0], "y": 2}, faults=[("F-INDEX", 4, 1)])
row("unguard", "an INT sum wraps in the store", main("x : INT := 32767; y : INT;", "y := x + 1;"), {"y": -32768})
row("unguard", "a store through a reference keeps its handler", main("x : INT; p : REF_TO INT; y : INT;",
    "p^ := 5;\ny := 1;"), {"x": 0, "y": 1}, faults=[("F-NULL-REF", 4, 1)])
row("unguard", "an FB's own REAL slot, rounded to float32", main("f : Fb; r : REAL;", "f(); r := f.o;", before="""
FUNCTION_BLOCK Fb
VAR_OUTPUT o : REAL; END_VAR VAR a : REAL := 0.1; END_VAR
o := a * 3.0;
END_FUNCTION_BLOCK"""), {"r": float(__import__("numpy").float32(__import__("numpy").float32(0.1) * __import__("numpy").float32(3.0)))})

row("unguard", "a global's store keeps its handler", main("y : INT;", "g := g + 1;\ny := g;",
    before="VAR_GLOBAL g : INT := 4; END_VAR"), {"y": 5}, never=("MAIN", r"\n        _G\.v_G = "))
row("unguard", "a located variable's store keeps its handler", main("m AT %MW2 : INT; y : INT;",
    "m := 5;\ny := m + 1;"), {"m": 5, "y": 6}, never=("MAIN", r"\n        self\.v_M = 5"),
    shape=("MAIN", r"\n        (?:self\.)?v_Y = "))
row("unguard", "an array copy", main("a, b : ARRAY[1..3] OF INT; y : INT;",
    "b[2] := 7;\na := b;\ny := a[2];"), {"a": [0, 7, 0], "y": 7}, shape=("MAIN", r"\n        v_A\[_WHOLE\] = v_B"))
row("unguard", "a copy of a global array", main("a : ARRAY[1..3] OF INT;", "a := G;",
    before="VAR_GLOBAL G : ARRAY[1..3] OF INT := [4, 5, 6]; END_VAR"), {"a": [4, 5, 6]},
    shape=("MAIN", r"\n        v_A\[_WHOLE\] = v_G"))
row("unguard", "an element store of a division keeps its handler", main("a : ARRAY[1..3] OF INT; k : INT;",
    "a[1] := 6 / k;\na[2] := 6 - k;"), {"a": [0, 6, 0]}, faults=[("F-DIV-ZERO", 4, 1)],
    never=("MAIN", r"\n        v_A\[0\] = "), shape=("MAIN", r"\n        v_A\[1\] = "))
row("unguard", "a store with a conversion keeps its handler", main("i : INT := 3; x : LREAL; y : INT;",
    "x := INT_TO_LREAL(i);\ny := i * 2 - 1;"), {"x": 3.0, "y": 5},
    never=("MAIN", r"\n        self\.v_X = "), shape=("MAIN", r"\n        self\.v_Y = "))
row("unguard", "a FUNCTION's locals", main("y : LREAL;", "y := F(1.5);", before="""FUNCTION F : LREAL
VAR_INPUT a : LREAL; END_VAR VAR t : LREAL; END_VAR
t := a * a - 0.25;
F := t * 2.0 + a;
END_FUNCTION"""), {"y": 5.5}, shape=("F", r"\n        v_T = \("))

# ----------------------------------------------------------------------------------- reuse
# A float value computed again over unchanged operands is set once (`_cN = ...`) and read
# by name; anything that may change an operand between the two uses ends the value.
# a = 1.5, b = 2.0: a * b = 3.0 exactly.

AB = "a : LREAL := 1.5; b : LREAL := 2.0; x, y, z : LREAL; c : BOOL := TRUE; i, k, n : INT := 3; "
row("reuse", "a value computed twice", main(AB, "x := a * b + 1.0;\ny := a * b - 1.0;"), {"x": 4.0, "y": 2.0},
    shape=("MAIN", r"_c\d+ = \((?:self\.)?v_A \* (?:self\.)?v_B\)"))
row("reuse", "a value used once keeps its text", main(AB, "x := a * b + 1.0;\ny := a - b;"), {"x": 4.0, "y": -0.5},
    never=("MAIN", r"_c\d+ = "))
row("reuse", "a store between the uses", main(AB, "x := a * b;\na := 3.0;\ny := a * b;"), {"x": 3.0, "y": 6.0})
row("reuse", "a store of the other operand", main(AB, "x := a * b;\nb := 4.0;\ny := a * b;\nz := a * b;"),
    {"x": 3.0, "y": 6.0, "z": 6.0}, shape=("MAIN", r"_c\d+ = "))
row("reuse", "a store in an IF branch", main(AB, "x := a * b;\nIF c THEN a := 3.0; END_IF;\ny := a * b;"),
    {"x": 3.0, "y": 6.0})
row("reuse", "a store in a CASE clause", main(AB, "x := a * b;\nCASE k OF 1: y := 0.0; 3: a := 3.0; END_CASE;\ny := a * b;"),
    {"x": 3.0, "y": 6.0})
row("reuse", "a store in an ELSE", main(AB, "x := a * b;\nIF NOT c THEN y := 0.0; ELSE a := 3.0; END_IF;\ny := a * b;"),
    {"x": 3.0, "y": 6.0})
row("reuse", "a loop body that stores an operand after a use",
    # a * b = 3, 5, 7 in the three passes: y = 15; a ends at 4.5
    main(AB, "x := a * b;\nFOR i := 1 TO n DO y := y + a * b; a := a + 1.0; END_FOR;"),
    {"x": 3.0, "y": 15.0, "a": 4.5})
row("reuse", "a WHILE condition is computed each time",
    # a = 1.5, 2.5, 3.5, 4.5, 5.5: a * b = 3, 5, 7, 9, 11: four passes
    main(AB + "m : INT;", "x := a * b;\nWHILE a * b < 10.0 DO a := a + 1.0; m := m + 1; END_WHILE;"),
    {"x": 3.0, "m": 4, "a": 5.5})
row("reuse", "a REPEAT condition is computed each time",
    main(AB + "m : INT;", "x := a * b;\nREPEAT a := a + 1.0; m := m + 1; UNTIL a * b > 6.0 END_REPEAT;\ny := a * b;"),
    {"x": 3.0, "m": 2, "a": 3.5, "y": 7.0})
row("reuse", "an FB call that changes a global", main(AB + "f : Bump;", "x := g * a;\nf();\ny := g * a;",
    before="VAR_GLOBAL g : LREAL := 2.0; END_VAR\nFUNCTION_BLOCK Bump\ng := g + 1.0;\nEND_FUNCTION_BLOCK"),
    {"x": 3.0, "y": 4.5})
row("reuse", "a FUNCTION call in the expression that changes a global",
    main(AB, "x := g * a;\ny := Inc() + g * a;",
         before="VAR_GLOBAL g : LREAL := 2.0; END_VAR\nFUNCTION Inc : LREAL\ng := g + 1.0; Inc := 0.0;\nEND_FUNCTION"),
    {"x": 3.0, "y": 4.5})
row("reuse", "a store into a global", main(AB, "x := g * a;\ng := 5.0;\ny := g * a;",
    before="VAR_GLOBAL g : LREAL := 2.0; END_VAR"), {"x": 3.0, "y": 7.5})
row("reuse", "a store through a reference", main(AB + "r : REF_TO LREAL;", "r := REF(a);\nx := a * b;\nr^ := 3.0;\ny := a * b;"),
    {"x": 3.0, "y": 6.0})
row("reuse", "a store into an in-out", main(AB, "x := F(a);", before="""FUNCTION F : LREAL
VAR_IN_OUT v : LREAL; END_VAR VAR t : LREAL; END_VAR
t := v * 2.0;
v := 5.0;
F := t + v * 2.0;
END_FUNCTION"""), {"x": 13.0, "a": 5.0})
row("reuse", "an own array's element at a literal index",
    main(AB + "arr : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0];",
         "x := arr[2] * 2.0 + arr[2];\narr[2] := 4.0;\ny := arr[2] * 2.0;\nz := arr[3] + arr[3];"),
    {"x": 6.0, "y": 8.0, "z": 6.0}, shape=("MAIN", r"_c\d+ = v_ARR\[2\]"))
row("reuse", "an element store at a variable index ends the array's values",
    main(AB + "arr : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0];",
         "x := arr[2] * 2.0;\narr[k - 1] := 4.0;\ny := arr[2] * 2.0;"), {"x": 4.0, "y": 8.0})
row("reuse", "SIN of a value computed once", main(AB, "x := SIN(a) + 1.0;\ny := SIN(a) * 2.0;"),
    {"x": __import__("math").sin(1.5) + 1.0, "y": __import__("math").sin(1.5) * 2.0}, shape=("MAIN", r"_c\d+ = "),
    with_=("inline",))
row("reuse", "SQRT and COS of a sum", main(AB, "x := SQRT(a + b) + COS(a + b);\ny := SQRT(a + b);"),
    {"x": 3.5 ** 0.5 + __import__("math").cos(3.5), "y": 3.5 ** 0.5}, with_=("inline",))
row("reuse", "a value computed in a branch is not read after it",
    main(AB, "IF NOT c THEN x := a * b; y := a * b; END_IF;\nz := a * b;\nx := a * b + z;"),
    {"x": 6.0, "y": 0.0, "z": 3.0})
row("reuse", "a value of one CASE clause in another", main(AB, """CASE k OF
1: x := a * b; y := a * b;
3: z := a * b; y := a * b + z;
END_CASE;"""), {"x": 0.0, "y": 6.0, "z": 3.0})
row("reuse", "in the copies of an unrolled loop", main(AB, "FOR i := 1 TO 3 DO y := y + a * b; END_FOR;"),
    {"y": 9.0})
row("reuse", "a FUNCTION's input", main(AB, "x := F(a);", before="""FUNCTION F : LREAL
VAR_INPUT v : LREAL; END_VAR
F := v * v + v * v;
END_FUNCTION"""), {"x": 4.5}, shape=("F", r"_c\d+ = \(v_V \* v_V\)"))
row("reuse", "an FB's slots", main(AB + "f : Fb;", "f(); x := f.o;", before="""FUNCTION_BLOCK Fb
VAR_OUTPUT o : LREAL; END_VAR VAR p : LREAL := 0.5; q : LREAL := 6.0; END_VAR
o := p * q + p * q;
END_FUNCTION_BLOCK"""), {"x": 6.0}, shape=("FB", r"_c\d+ = \(self\.v_P \* self\.v_Q\)"))
_f32 = __import__("numpy").float32
row("reuse", "a REAL value, rounded to float32 once", main("r : REAL := 0.1; x, y : REAL;",
    "x := r * 3.0 + r * 3.0;\ny := r * 3.0;"),
    {"x": float(_f32(_f32(0.1) * _f32(3.0)) * _f32(2.0)), "y": float(_f32(_f32(0.1) * _f32(3.0)))})
row("reuse", "an integer sum is no value of the pass", main("p : INT := 30000; q : INT; r : DINT;",
    "q := p + p;\nr := INT_TO_DINT(p + p);"), {"q": -5536, "r": 60000}, never=("MAIN", r"_c\d+ = "))
row("reuse", "a named CONSTANT operand", main(AB + "END_VAR VAR CONSTANT two : LREAL := 2.0;",
    "x := a * two;\ny := a * two + 1.0;"), {"x": 3.0, "y": 4.0})
row("reuse", "a located variable another one at its address stores", main(
    "a AT %MD10 : REAL; b AT %MD10 : REAL; x, y, z : REAL;",
    # a and b are the same four bytes of %M: storing b stores a
    "a := 1.5;\nx := a * 2.0 + 1.0;\nb := 3.0;\ny := a * 2.0;\nz := a * 2.0 + x;"),
    {"x": 4.0, "y": 6.0, "z": 10.0, "a": 3.0}, never=("MAIN", r"_c\d+ = "))
row("reuse", "located LREAL and INT variables", main(
    "p AT %ML2 : LREAL; q AT %MW16 : INT := 7; w AT %MW16 : INT; x, y : LREAL; k : INT;",
    "p := 0.25;\nx := p * 4.0 - p * 4.0 + p * 4.0;\nw := 9;\nk := q + q;\nw := 1;\nk := k + q + q;\np := 2.0;\ny := p * 4.0;"),
    {"x": 1.0, "y": 8.0, "k": 20}, never=("MAIN", r"_c\d+ = "))
row("reuse", "a value inside another value", main(AB + "d : LREAL := 0.25;",
    "x := a * b + d;\ny := a * b + d;\nz := a * b;"), {"x": 3.25, "y": 3.25, "z": 3.0},
    shape=("MAIN", r"_c\d+ = \(_c\d+ \+ (?:self\.)?v_D\)"))
row("reuse", "a value first computed in an IF condition", main(AB,
    "IF a * b > 2.0 THEN x := a * b; END_IF;\nIF a * b > 5.0 THEN y := 1.0; ELSE y := a * b + 1.0; END_IF;"),
    {"x": 3.0, "y": 4.0}, shape=("MAIN", r"_c\d+ = "))
row("reuse", "values in the body of a loop over data", main(AB,
    "FOR i := 1 TO n DO x := x + a * b; y := a * b; END_FOR;\nz := a * b;"),
    {"x": 9.0, "y": 3.0, "z": 3.0})
row("reuse", "values in a WHILE body", main(AB + "m : INT;",
    "WHILE m < 2 DO x := x + a * b; y := y + a * b; m := m + 1; END_WHILE;"), {"x": 6.0, "y": 6.0})
row("reuse", "a value in a nested IF", main(AB,
    "IF c THEN IF a > 1.0 THEN x := a * b; y := a * b + 1.0; END_IF; z := a * b; END_IF;"),
    {"x": 3.0, "y": 4.0, "z": 3.0})
row("reuse", "an FB call between two uses of the FB's own output", main(AB + "f : Fb;",
    "f(); x := f.o * 2.0; f(); y := f.o * 2.0;", before="""FUNCTION_BLOCK Fb
VAR_OUTPUT o : LREAL; END_VAR
o := o + 1.0;
END_FUNCTION_BLOCK"""), {"x": 2.0, "y": 4.0})
row("reuse", "a METHOD storing its FB's variable between two uses", main("f : Fb; r : LREAL;", "r := f.Go();",
    before="""FUNCTION_BLOCK Fb
VAR_OUTPUT o : LREAL; END_VAR VAR a : LREAL := 1.5; b : LREAL := 2.0; END_VAR
METHOD Go : LREAL
VAR t : LREAL; END_VAR
t := a * b;
a := 3.0;
o := a * b + t;
Go := o;
END_METHOD
END_FUNCTION_BLOCK"""), {"r": 9.0, "f.o": 9.0, "f.a": 3.0})
row("stores_read", "an element stored and read back", main(AB + "arr : ARRAY[1..3] OF LREAL;",
    "arr[2] := a * b;\ny := arr[2] + 1.0;\nz := arr[2] * 2.0;"), {"arr": [0.0, 3.0, 0.0], "y": 4.0, "z": 6.0})
row("stores_read", "the stored value read the array", main(AB + "arr : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0];",
    "arr[2] := arr[2] * b;\ny := arr[2] + 1.0;\narr[2] := arr[2] * b;\nz := arr[2];"), {"arr": [1.0, 8.0, 3.0], "y": 5.0, "z": 8.0})
row("stores_read", "an operand of the stored value changes", main(AB + "arr : ARRAY[1..3] OF LREAL;",
    "arr[1] := a * b;\na := 0.5;\ny := arr[1] + a * b;"), {"arr": [3.0, 0.0, 0.0], "y": 4.0})
row("finite", "SIN and COS of one variable", main(AB, "x := SIN(a) + COS(a);\ny := SIN(a);"),
    {"x": __import__("math").sin(1.5) + __import__("math").cos(1.5), "y": __import__("math").sin(1.5)},
    shape=("MAIN", r"_c\d+ = \(True if \((?:self\.)?v_A < 1e309 and (?:self\.)?v_A > -1e309\) else False\)"), with_=("inline",))


# --------------------------------------------------------- aliases, spread, stores, unused
# Where an FB body loads its aggregates and cached variables.  Main calls the FB with
# Mode = 0, 1, 2, 3 in four scans and keeps each Out.


def modes_fb(body: str, extra: str = "", before: str = "") -> str:
    return f"""{before}
FUNCTION_BLOCK Fb
VAR_INPUT Mode : INT; END_VAR
VAR_OUTPUT Out : LREAL; END_VAR
VAR Arr : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0]; K : LREAL := 2.0; Q : LREAL := 5.0; Cnt : INT;
    Z : LREAL; i : INT; {extra} END_VAR
{body}
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Fb; n : INT; outs : ARRAY[0..3] OF LREAL; END_VAR
f(Mode := n); outs[n] := f.Out; n := n + 1;
END_PROGRAM
"""


IN_BRANCH = r"\n {12,}v_ARR = self\.v_ARR"
for name, body, outs in (
        ("one IF branch", "IF Mode = 1 THEN Out := Arr[2] * K; ELSE Out := Q; END_IF;", [5.0, 4.0, 5.0, 5.0]),
        ("an ELSIF branch", "IF Mode = 1 THEN Out := Q; ELSIF Mode = 2 THEN Out := Arr[3]; ELSE Out := -1.0; END_IF;",
         [-1.0, 5.0, 3.0, -1.0]),
        ("the ELSE", "IF Mode < 2 THEN Out := Q; ELSE Out := Arr[1] + Arr[3]; END_IF;", [5.0, 5.0, 4.0, 4.0]),
        ("a CASE clause", "CASE Mode OF 1: Out := Q; 2: Out := Arr[2]; END_CASE;", [0.0, 5.0, 2.0, 2.0]),
        ("the CASE's ELSE", "CASE Mode OF 0, 1: Out := Q; ELSE Out := Arr[1]; END_CASE;", [5.0, 5.0, 1.0, 1.0]),
        ("two branches of an inner IF",
         "IF Mode > 0 THEN IF Mode = 2 THEN Out := Arr[2]; ELSE Out := Arr[1]; END_IF; END_IF;", [0.0, 1.0, 2.0, 1.0]),
        ("a loop in a branch", "IF Mode = 3 THEN FOR i := 1 TO 3 DO Out := Out + Arr[i]; END_FOR; END_IF;",
         [0.0, 0.0, 0.0, 6.0])):
    row("aliases", name, modes_fb(body), {"outs": outs}, scans=4, shape=("FB", IN_BRANCH))
for name, body, outs in (
        ("a use in a condition", "IF Arr[1] > 0.5 THEN Out := Q; END_IF;", [5.0] * 4),
        ("a use in the branch and after it", "IF Mode = 1 THEN Out := Arr[2]; END_IF; Out := Out + Arr[1];",
         [1.0, 3.0, 4.0, 5.0]),
        ("uses in two IFs", "IF Mode = 1 THEN Out := Arr[1]; END_IF; IF Mode = 2 THEN Out := Arr[2]; END_IF;",
         [0.0, 1.0, 2.0, 2.0]),
        ("a use in a CASE selector", "CASE REAL_TO_INT(LREAL_TO_REAL(Arr[1])) + Mode OF 2: Out := Q; END_CASE;",
         [0.0, 5.0, 5.0, 5.0])):
    row("aliases", name, modes_fb(body), {"outs": outs}, scans=4, never=("FB", IN_BRANCH))
row("aliases", "a global aggregate", modes_fb("IF Mode = 2 THEN Out := G[2]; END_IF;",
    before="VAR_GLOBAL G : ARRAY[1..2] OF LREAL := [7.0, 8.0]; END_VAR"), {"outs": [0.0, 0.0, 8.0, 8.0]}, scans=4,
    shape=("FB", r"\n {12,}v_G = _G\.v_G"))
row("spread", "two branches of one IF", modes_fb(
    "IF Mode = 1 THEN Out := Arr[1]; ELSIF Mode = 2 THEN Out := Q; ELSE Out := Arr[3]; END_IF;"),
    {"outs": [3.0, 1.0, 5.0, 3.0]}, scans=4, shape=("FB", r"(?s)\n {12,}v_ARR = self\.v_ARR.*\n {12,}v_ARR = self\.v_ARR"))
row("spread", "clauses of one CASE", modes_fb(
    "CASE Mode OF 1: Out := Arr[1]; 2: Out := Q; 3: Out := Arr[2] + Arr[3]; END_CASE;"),
    {"outs": [0.0, 1.0, 5.0, 5.0]}, scans=4, shape=("FB", r"(?s)\n {12,}v_ARR = self\.v_ARR.*\n {12,}v_ARR = self\.v_ARR"))
row("spread", "branches of two IFs are not spread", modes_fb(
    "IF Mode = 1 THEN Out := Arr[1]; END_IF; IF Mode = 3 THEN Out := Arr[3]; ELSE Out := Out + 1.0; END_IF;"),
    {"outs": [1.0, 2.0, 3.0, 3.0]}, scans=4, never=("FB", IN_BRANCH))
row("spread", "an inner IF's branches in an outer branch", modes_fb(
    "IF Mode > 1 THEN IF Mode = 2 THEN Out := Arr[2]; ELSE Out := Arr[3]; END_IF; ELSE Out := Q; END_IF;"),
    {"outs": [5.0, 5.0, 2.0, 3.0]}, scans=4, shape=("FB", IN_BRANCH))
CNT = "Cnt := Cnt + 1; Cnt := Cnt * 2; Out := INT_TO_LREAL(Cnt);"
row("stores", "a cached variable stored in one clause", modes_fb(
    f"CASE Mode OF 1: Out := Q; 2: {CNT} END_CASE;"), {"outs": [0.0, 5.0, 2.0, 2.0], "f.Cnt": 2}, scans=4,
    shape=("FB", r"\n {12,}finally:\n {16,}self\.v_CNT = v_CNT"))
row("stores", "stored in one branch, read after it", modes_fb(
    f"IF Mode >= 2 THEN {CNT} END_IF; Out := Out + INT_TO_LREAL(Cnt);"),
    # Mode 2: Cnt = 2, Out = 2 + 2 = 4; Mode 3: Cnt = 6, Out = 6 + 6 = 12
    {"outs": [0.0, 0.0, 4.0, 12.0], "f.Cnt": 6}, scans=4)
row("stores", "stored in two IFs", modes_fb(
    f"IF Mode = 2 THEN {CNT} END_IF; IF Mode = 3 THEN Cnt := Cnt + 5; END_IF;"),
    {"outs": [0.0, 0.0, 2.0, 2.0], "f.Cnt": 7}, scans=4, never=("FB", r"\n {12,}finally:"))
row("stores", "a cached variable stored in the CASE's ELSE", modes_fb(
    f"CASE Mode OF 1: Out := Q; 3: Out := K; ELSE {CNT} END_CASE;"),
    # Mode 0: Cnt = 2, Out = 2; Mode 1: Out = 5; Mode 2: Cnt = 6, Out = 6; Mode 3: Out = 2
    {"outs": [2.0, 5.0, 6.0, 2.0], "f.Cnt": 6}, scans=4,
    shape=("FB", r"\n {12,}finally:\n {16,}self\.v_CNT = v_CNT"))
row("stores", "a cached variable stored in the IF's ELSE", modes_fb(
    f"IF Mode = 1 THEN Out := Q; ELSE {CNT} END_IF;"),
    {"outs": [2.0, 5.0, 6.0, 14.0], "f.Cnt": 14}, scans=4,
    shape=("FB", r"\n {12,}finally:\n {16,}self\.v_CNT = v_CNT"))


def _nested_loops(depth: int) -> str:
    names = ["i", "j1", "j2", "j3", "j4"][:depth]
    return "".join(f"FOR {v} := 1 TO n1 DO " for v in names) + "Out := Out + 1.0; " + "END_FOR; " * depth


for depth, where in ((4, "CASE"), (5, "CASE"), (4, "IF"), (5, "IF")):
    inner = (f"CASE Mode OF 1: Out := 1.0; ELSE {_nested_loops(depth)} END_CASE;" if where == "CASE"
             else f"IF Mode = 1 THEN Out := 1.0; ELSE {_nested_loops(depth)} END_IF;")
    check_ = {"shape" if depth <= 4 else "never":
              ("FB", r"\n {12,}finally:\n(?: {16,}self\.v_\w+ = v_\w+\n)* {16,}self\.v_CNT = v_CNT")}
    row("stores", f"loops {depth} deep in the {where}'s ELSE of the branch", modes_fb(
        f"IF Mode = 2 THEN Cnt := Cnt + 1; Cnt := Cnt * 2; {inner} Out := Out + INT_TO_LREAL(Cnt); END_IF;",
        extra="j1, j2, j3, j4 : INT; n1 : INT := 1;"),
        {"outs": [0.0, 0.0, 3.0, 3.0], "f.Cnt": 2}, scans=4, **check_)
row("spread", "a cached variable stored in two clauses", modes_fb(
    f"CASE Mode OF 1: {CNT} 2: Out := Q; 3: Cnt := Cnt - 7; Cnt := Cnt * Cnt; END_CASE;"),
    # Mode 1: Cnt = 2, Out = 2; Mode 2: Out = 5; Mode 3: Cnt = (2 - 7)^2 = 25
    {"outs": [0.0, 2.0, 5.0, 5.0], "f.Cnt": 25}, scans=4,
    shape=("FB", r"(?s)\n {12,}finally:\n {16,}self\.v_CNT = v_CNT.*\n {12,}finally:\n {16,}self\.v_CNT = v_CNT"))
row("unused", "a constant table every read of which is folded", modes_fb(
    "Out := T[2] * 2.0 + T[3];", extra="END_VAR VAR CONSTANT T : ARRAY[1..3] OF LREAL := [0.5, 1.5, 2.5];"),
    {"outs": [5.5] * 4}, scans=4, with_=("fold",), gone=("FB", r"v_T = self\.v_T"))
row("unused", "a constant table read at a variable index stays", modes_fb(
    "Out := T[Mode MOD 3 + 1];", extra="END_VAR VAR CONSTANT T : ARRAY[1..3] OF LREAL := [0.5, 1.5, 2.5];"),
    {"outs": [0.5, 1.5, 2.5, 0.5]}, scans=4, with_=("fold",))


# ------------------------------------------------------------------------------------ fold
# CONSTANT array elements at constant indices are literals; constant IF conditions choose
# their branch at compile time.

TABLE = "END_VAR VAR CONSTANT T : ARRAY[1..3] OF INT := [101, 102, 103]; " \
        "M : ARRAY[0..1, 2..4] OF INT := [11, 12, 13, 21, 22, 23]; " \
        "N : ARRAY[-1..1] OF LREAL := [0.25, 0.5, 0.75]; S : ARRAY[1..4] OF INT := [1, -1, -1, 1];"
row("fold", "an element of a one-dimensional table", main("y : INT; " + TABLE, "y := T[2] + 1;"), {"y": 103},
    shape=("MAIN", r"\b102\b"))
row("fold", "an element of a two-dimensional table (row-major)", main("y, z, w : INT; " + TABLE,
    "y := M[0, 3];\nz := M[1, 2];\nw := M[1, 4];"), {"y": 12, "z": 21, "w": 23},
    shape=("MAIN", r"v_Y = 12\b(?s:.*)v_Z = 21\b(?s:.*)v_W = 23\b"))
row("fold", "a table with a negative lower bound", main("x : LREAL; " + TABLE, "x := N[-1] + N[1];"),
    {"x": 1.0}, shape=("MAIN", r"0\.25 \+ 0\.75"))
row("fold", "a constant integer index expression", main("y : INT; " + TABLE, "y := T[1 + 1] * 2;"), {"y": 204})
row("fold", "an index at a variable stays a read", main("y : INT; i : INT := 3; " + TABLE, "y := T[i];"),
    {"y": 103}, never=("MAIN", r"\b103\b"))
row("fold", "an index in an unrolled loop", main("y : INT; k : INT; " + TABLE,
    "FOR k := 1 TO 3 DO y := y * 10 + T[k] - 100; END_FOR;"), {"y": 123, "k": 4}, with_=("unroll",),
    shape=("MAIN", r"\b101\b(?s:.*)\b102\b(?s:.*)\b103\b"))
row("fold", "a global CONSTANT table through VAR_EXTERNAL", main("y : INT; END_VAR VAR_EXTERNAL CONSTANT G : ARRAY[1..2] OF INT;",
    "y := G[2];", before="VAR_GLOBAL CONSTANT G : ARRAY[1..2] OF INT := [7, 9]; END_VAR"), {"y": 9})
row("fold", "a constant IF condition", main("y : INT; " + TABLE,
    "IF S[2] > 0 THEN y := 111; ELSE y := 222; END_IF;"), {"y": 222}, gone=("MAIN", r"\b111\b"))
for cond, taken in (("S[1] = 1", True), ("S[1] <> 1", False), ("S[2] < 0", True), ("S[2] <= -2", False),
                    ("S[3] >= -1", True), ("S[1] > 1", False), ("NOT (S[1] = 1)", False),
                    ("S[1] = 1 AND S[2] = 1", False), ("S[1] = 1 OR S[2] = 1", True),
                    ("S[1] = 1 XOR S[4] = 1", False), ("S[1] + S[2] * 3 - 1 = -3", True),
                    ("S[1] * S[2] = -1 AND NOT (S[3] > S[4])", True)):
    row("fold", f"IF {cond}", main("y : INT; " + TABLE, f"IF {cond} THEN y := 111; ELSE y := 222; END_IF;"),
        {"y": 111 if taken else 222}, gone=("MAIN", r"\b222\b" if taken else r"\b111\b"))
row("fold", "ELSIF of constants", main("y : INT; " + TABLE,
    "IF S[2] > 0 THEN y := 111; ELSIF S[4] > 0 THEN y := 333; ELSE y := 222; END_IF;"), {"y": 333},
    gone=("MAIN", r"\b222\b"))
row("fold", "a condition with a variable stays", main("y : INT; v : INT := 1; " + TABLE,
    "IF S[1] = v THEN y := 111; ELSE y := 222; END_IF;"), {"y": 111}, never=("MAIN", r"if True|if False"))

# ---------------------------------------------------------------------------------- unroll
# A FOR with constant bounds whose body cannot leave or skip, its variable a local of the
# body that the body does not assign, is written out copy by copy.  After the loop the
# variable holds the value the loop leaves (IEC 61131-3: the first value past the end).

UNROLLED = r"for v_K in"
for name, loop, expect in (
        ("step 1", "FOR k := 1 TO 4 DO s := s * 10 + k; END_FOR;", {"s": 1234, "k": 5}),
        ("step 2", "FOR k := 1 TO 7 BY 2 DO s := s * 10 + k; END_FOR;", {"s": 1357, "k": 9}),
        ("a negative step", "FOR k := 4 TO 1 BY -1 DO s := s * 10 + k; END_FOR;", {"s": 4321, "k": 0}),
        ("a step of -3", "FOR k := 9 TO 1 BY -3 DO s := s * 10 + k; END_FOR;", {"s": 963, "k": 0}),
        ("no iteration", "FOR k := 5 TO 1 DO s := s + 1; END_FOR;", {"s": 0, "k": 5}),
        ("one iteration", "FOR k := 3 TO 3 DO s := s + k; END_FOR;", {"s": 3, "k": 4}),
        ("a nested FOR", "FOR k := 1 TO 3 DO FOR j := 1 TO k DO s := s + j; END_FOR; END_FOR;", {"s": 10, "k": 4, "j": 4}),
        ("an IF in the body", "FOR k := 1 TO 4 DO IF k MOD 2 = 0 THEN s := s + k; ELSE s := s - 1; END_IF; END_FOR;",
         {"s": 4, "k": 5}),
        ("a CASE in the body", "FOR k := 1 TO 3 DO CASE k OF 1: s := 5; 2: s := s * 3; ELSE s := s - 1; END_CASE; END_FOR;",
         {"s": 14, "k": 4}),
        ("a WHILE in the body", "FOR k := 1 TO 3 DO j := 0; WHILE j < k DO s := s + 1; j := j + 1; END_WHILE; END_FOR;",
         {"s": 6, "k": 4, "j": 3})):
    # (with every pass, cse keeps the loop as before beside the copies: unroll.emit)
    row("unroll", name, main("s, k, j : INT;", loop), expect, gone=("MAIN", UNROLLED), every_too=False)
for name, loop, expect in (
        ("EXIT", "FOR k := 1 TO 9 DO s := s + k; IF s > 5 THEN EXIT; END_IF; END_FOR;", {"s": 6, "k": 3}),
        ("CONTINUE", "FOR k := 1 TO 4 DO IF k = 2 THEN CONTINUE; END_IF; s := s + k; END_FOR;", {"s": 8, "k": 5}),
        ("variable bounds", "FOR k := 1 TO n DO s := s + k; END_FOR;", {"s": 6, "k": 4}),
        ("a variable step", "FOR k := 1 TO 6 BY n DO s := s + k; END_FOR;", {"s": 5, "k": 7}),
        ("more statements than the cap", "FOR k := 1 TO 9000 DO s := s + 1; END_FOR;", {"s": 9000, "k": 9001})):
    row("unroll", f"not with {name}", main("s, k, j : INT; n : INT := 3;", loop), expect, never=("MAIN", r"s = \(*1\b"))
row("unroll", "an instance's variable is no local", main("f : Fb; s : INT;", "f(); s := f.s;", before="""
FUNCTION_BLOCK Fb
VAR k : INT; END_VAR VAR_OUTPUT s : INT; END_VAR
FOR k := 1 TO 3 DO s := s * 10 + k; END_FOR;
END_FUNCTION_BLOCK"""), {"s": 123})
row("unroll", "a RETURN in the body", main("y : INT;", "y := F(2);", before="""
FUNCTION F : INT
VAR_INPUT n : INT; END_VAR VAR k : INT; END_VAR
FOR k := 1 TO 5 DO
  F := F + k;
  IF k = n THEN RETURN; END_IF;
END_FOR;
F := -1;
END_FUNCTION"""), {"y": 3}, gone=("F", r"for v_K in"))
row("unroll", "a FUNCTION's loop", main("y : INT;", "y := F();", before="""
FUNCTION F : INT
VAR k : INT; END_VAR
FOR k := 2 TO 8 BY 3 DO F := F * 10 + k; END_FOR;
F := F + k;
END_FUNCTION"""), {"y": 258 + 11}, gone=("F", r"for v_K in"), every_too=False)


# ------------------------------------------------------------------------------- cse, fuse
# In an unrolled loop whose body stores only locals and calls nothing (and in a whole body
# with at least eight element reads at literal indices), each element is read once before
# the region and a `+ - *` of such values is computed once; fuse tidies the region's lines.


def dot(body: str, decls: str = "") -> str:
    return main("x : ARRAY[1..3] OF LREAL := [1.0, 2.0, 3.0]; y : ARRAY[1..3] OF LREAL := [0.5, 0.25, 2.0]; "
                "r : LREAL;", "r := Dot(x, y);", before=f"""FUNCTION Dot : LREAL
VAR_INPUT a, b : ARRAY[1..3] OF LREAL; END_VAR
VAR k : INT; s, t, u : LREAL; {decls} END_VAR
{body}
END_FUNCTION""")


REGION = ("DOT", r"_t\d+ = v_A\[0\]\n(?s:.*)_t\d+ = True\n\s*except _FAULTS:")
# products a[k] * b[k] = 0.5, 0.5, 6.0
row("cse", "a product used twice in a copy, an IF after it", dot("""FOR k := 1 TO 3 DO
  s := s + a[k] * b[k] + a[k] * b[k];
  IF a[k] > 1.5 THEN t := t + a[k] * b[k]; END_IF;
  t := t + a[k] * 2.0;
END_FOR;
Dot := s + t;"""), {"r": 32.5}, shape=REGION)
row("cse", "a product first met inside an IF", dot("""FOR k := 1 TO 3 DO
  IF a[k] > 1.5 THEN t := t + a[k] * b[k]; END_IF;
  s := s + a[k] * b[k];
END_FOR;
Dot := s * 10.0 + t;"""), {"r": 76.5}, shape=REGION)
row("cse", "a product first met inside a CASE", dot("""FOR k := 1 TO 3 DO
  CASE k OF 2: t := a[k] * b[k] + 1.0; ELSE u := u + a[k]; END_CASE;
  s := s + a[k] * b[k];
END_FOR;
Dot := s * 100.0 + t * 10.0 + u;"""), {"r": 700.0 + 15.0 + 4.0}, shape=REGION)
row("cse", "a call keeps the loop", dot("""FOR k := 1 TO 3 DO s := s + ABS(a[k] * b[k]) + a[k] * b[k]; END_FOR;
Dot := s;"""), {"r": 14.0}, never=REGION)
row("cse", "a store into an array keeps the loop", dot("""FOR k := 1 TO 3 DO c[k] := a[k] * b[k]; s := s + c[k] * 2.0; END_FOR;
Dot := s;""", "c : ARRAY[1..3] OF LREAL;"), {"r": 14.0}, never=REGION)
row("cse", "a store into a global keeps the loop", dot("""FOR k := 1 TO 3 DO G := G + a[k] * b[k]; END_FOR;
Dot := G;""").replace("FUNCTION Dot", "VAR_GLOBAL G : LREAL; END_VAR\nFUNCTION Dot"), {"r": 7.0}, never=REGION)
row("cse", "a nested FOR", dot("""FOR k := 1 TO 3 DO FOR i := 1 TO 3 DO s := s + a[k] * b[i]; END_FOR; END_FOR;
Dot := s;""", "i : INT;"), {"r": 6.0 * 2.75}, shape=REGION)
row("fuse", "a local stored in each copy keeps its last value", dot("""FOR k := 1 TO 3 DO u := a[k] * 2.0; s := s + u; END_FOR;
Dot := s * 10.0 + u;"""), {"r": 126.0})
row("fuse", "a run of sums into one variable", dot("""FOR k := 1 TO 3 DO s := s + a[k]; s := s - b[k]; s := s * 2.0; END_FOR;
Dot := s;"""), {"r": 13.0})     # s = (1 - 0.5) * 2 = 1; (1 + 2 - 0.25) * 2 = 5.5; (5.5 + 3 - 2) * 2 = 13
row("fuse", "a variable read before it is set again", dot("""FOR k := 1 TO 3 DO t := a[k] * b[k]; u := t + u; t := u * 2.0; s := s + t; END_FOR;
Dot := s * 100.0 + t;"""), {"r": (1.0 + 2.0 + 14.0) * 100.0 + 14.0})
row("cse", "a product used once is put back into its use", dot("""FOR k := 1 TO 3 DO s := s + a[k] * b[k]; END_FOR;
Dot := s;"""), {"r": 7.0}, shape=REGION, never=("DOT", r"_t\d+ = \(_t\d+ \* _t\d+\)"))
row("fuse", "temporaries of the copies share names", dot("""FOR k := 1 TO 3 DO
  s := s + a[k] * b[k] - a[k] * b[k] * 2.0;
END_FOR;
Dot := s;"""), {"r": -7.0}, shape=("DOT", r"(_t\d+) = \(_t\d+ \* _t\d+\)\n(?s:.*)\n\s*\1 = \(_t\d+ \* _t\d+\)\n"))
_BIG_TERMS = [(i, j) for i in range(1, 17) for j in range(i, 17)][:130]
row("vector", "a whole body of float products and sums is one NumPy call", main(
    "m : ARRAY[1..16] OF LREAL := [" + ", ".join(f"{0.5 + k / 8}" for k in range(16)) + "]; r : LREAL;",
    "r := Big(m);", before="FUNCTION Big : LREAL\nVAR_INPUT a : ARRAY[1..16] OF LREAL; END_VAR VAR s : LREAL; END_VAR\n"
    + "\n".join(f"s := s + a[{i}] * a[{j}];" for i, j in _BIG_TERMS) + "\nBig := s;\nEND_FUNCTION"),
    # the same sum in Python's floats, term by term in the ST's order
    {"r": __import__("functools").reduce(lambda s, t: s + (0.5 + (t[0] - 1) / 8) * (0.5 + (t[1] - 1) / 8),
                                          _BIG_TERMS, 0.0)},
    shape=("BIG", r"v_S, (?:v_BIG, )?= _k\d+\("), with_=("unguard", "charges", "fuse"))
DET = main("m : ARRAY[1..9] OF LREAL := [2.0, 0.0, 1.0, 1.0, 3.0, 2.0, 1.0, 1.0, 4.0]; d, s7, s8 : LREAL;",
           "d := Det3(m);\ns7 := Sum7(m);\ns8 := Sum8(m);", before="""FUNCTION Det3 : LREAL
VAR_INPUT a : ARRAY[1..9] OF LREAL; END_VAR
Det3 := a[1] * (a[5] * a[9] - a[6] * a[8]) - a[2] * (a[4] * a[9] - a[6] * a[7]) + a[3] * (a[4] * a[8] - a[5] * a[7]);
END_FUNCTION
FUNCTION Sum7 : LREAL
VAR_INPUT a : ARRAY[1..9] OF LREAL; END_VAR
Sum7 := a[1] + a[2] + a[3] + a[4] + a[5] + a[6] + a[7];
END_FUNCTION
FUNCTION Sum8 : LREAL
VAR_INPUT a : ARRAY[1..9] OF LREAL; END_VAR
Sum8 := a[1] + a[2] + a[3] + a[4] + a[5] + a[6] + a[7] + a[8];
END_FUNCTION""")
# det [[2, 0, 1], [1, 3, 2], [1, 1, 4]] = 2 (12 - 2) - 0 + 1 (1 - 3) = 18
row("cse", "a whole body of element reads", DET, {"d": 18.0, "s7": 10.0, "s8": 11.0},
    shape=("DET3", r"_t\d+ = True\n\s*except _FAULTS:"))
row("cse", "eight reads make a region", DET, {"s8": 11.0}, shape=("SUM8", r"_t\d+ = True\n\s*except _FAULTS:"))
row("cse", "seven reads do not", DET, {"s7": 10.0}, never=("SUM7", r"_t\d+ = True\n\s*except _FAULTS:"))


# ---------------------------------------------------------------------------- absolute
# `ABS(x) <= B` and `ABS(x) < B` (either side) as chained comparisons; `>` and `>=` keep
# the call; `ABS(x) <= ` the largest LREAL is x's finiteness.  One x a scan: 0, -0, 1.5,
# -1.5, 2, -2, 3, +inf; b = 2 and nb = -1 locals.  Python's abs and comparisons are the
# reference (IEC 61131-3 ABS: the magnitude; a comparison of LREALs: IEEE 754's).

XS = [0.0, -0.0, 1.5, -1.5, 2.0, -2.0, 3.0, float("inf")]


def _abs_table():
    big = 1.7976931348623157e308
    rows = []
    for x in XS:
        b, nb = 2.0, -1.0
        rows.append([abs(x) <= b, abs(x) < b, b >= abs(x), b > abs(x), abs(x) <= 2.0, abs(x) < 2.0,
                     abs(x) >= b, abs(x) <= big, abs(x) <= nb, abs(x) < -0.0, abs(x) <= -0.0, abs(x) > 1.5,
                     abs(x) <= b + 0.0])
    return [v for r in rows for v in r]


row("inline", "ABS against a bound, each form", main(
    "xs : ARRAY[0..7] OF LREAL := [0.0, -0.0, 1.5, -1.5, 2.0, -2.0, 3.0, 1.0E308]; n : INT; x : LREAL; "
    "b : LREAL := 2.0; nb : LREAL := -1.0; r : ARRAY[0..7, 0..12] OF BOOL;",
    """x := xs[n];
IF n = 7 THEN x := x * 10.0; END_IF;
r[n, 0] := ABS(x) <= b; r[n, 1] := ABS(x) < b; r[n, 2] := b >= ABS(x); r[n, 3] := b > ABS(x);
r[n, 4] := ABS(x) <= 2.0; r[n, 5] := ABS(x) < 2.0; r[n, 6] := ABS(x) >= b;
r[n, 7] := ABS(x) <= 1.7976931348623157E308; r[n, 8] := ABS(x) <= nb; r[n, 9] := ABS(x) < -0.0;
r[n, 10] := ABS(x) <= -0.0; r[n, 11] := ABS(x) > 1.5; r[n, 12] := ABS(x) <= b + 0.0;
n := n + 1;"""), {"r": _abs_table()}, scans=8, shape=("MAIN", r"\(-v_B <= v_X <= v_B\)"))
row("inline", "ABS of a local against the largest LREAL is its finiteness", main("r : BOOL; s : BOOL;",
    "r := F(1.0E308 * 10.0);\ns := F(-3.5);", before="""FUNCTION F : BOOL
VAR_INPUT x : LREAL; END_VAR
F := ABS(x) <= 1.7976931348623157E308;
END_FUNCTION"""), {"r": False, "s": True}, shape=("F", r"\(v_X < 1e309 and v_X > -1e309\)"))
row("inline", "ABS of an element and of a sum against the largest LREAL", main(
    "arr : ARRAY[1..3] OF LREAL := [1.0, 1.0E308, -2.0]; a : LREAL := 1.0E308; r, q, u, w : BOOL;",
    "arr[2] := arr[2] * 10.0;\nr := ABS(arr[2]) <= 1.7976931348623157E308;\nq := ABS(arr[3]) <= 1.7976931348623157E308;\n"
    "u := ABS(a + a) <= 1.7976931348623157E308;\nw := ABS(a - a) <= 1.7976931348623157E308;"),
    # 1e308 * 10 and 1e308 + 1e308 overflow to inf (IEEE 754): not finite
    {"r": False, "q": True, "u": False, "w": True})
row("inline", "ABS of an INT", main("i : INT := -7; r, q : BOOL;", "r := ABS(i) <= 7;\nq := ABS(i) < 7;"),
    {"r": True, "q": False}, shape=("MAIN", r"\(-7 <= (?:self\.)?v_I <= 7\)"))

# ---------------------------------------------------------------------------------- ranges
# A bounds check is left out only where the index can never be out of range; where it can,
# F-INDEX comes on the same line, and the statement is abandoned.

ARR = "arr : ARRAY[1..5] OF INT; i, c : INT; y : INT; x : INT := 1; count : INT := 7; "
row("ranges", "a FOR whose end is data, past the array", main(ARR, "FOR c := 1 TO count DO arr[c] := c; END_FOR;"),
    {"arr": [1, 2, 3, 4, 5], "c": 8}, faults=[("F-INDEX", 4, 1), ("F-INDEX", 4, 1)])
row("ranges", "a FOR whose end is data, inside the array", main(ARR.replace("count : INT := 7", "count : INT := 4"),
    "FOR c := 1 TO count DO arr[c] := c * 2; END_FOR;"), {"arr": [2, 4, 6, 8, 0], "c": 5})
row("ranges", "a FOR from 0", main(ARR.replace("count : INT := 7", "count : INT := 2"),
    "FOR c := 0 TO count DO arr[c + 1] := c; arr[c] := 9; END_FOR;"),
    {"arr": [9, 9, 2, 0, 0]}, faults=[("F-INDEX", 4, 1)])
row("ranges", "the union of an IF's branches", main(ARR,
    "IF x > 0 THEN i := 7; ELSE i := 2; END_IF;\ny := arr[i];\ni := 3;\ny := arr[i] + 1;"),
    {"y": 1}, faults=[("F-INDEX", 5, 1)])
row("ranges", "an IF that takes no branch", main(ARR + "j : INT := 9;",
    "i := j;\nIF x > 5 THEN i := 2; END_IF;\ny := arr[i];"), {"y": 0}, faults=[("F-INDEX", 6, 1)])
row("ranges", "a CASE's clauses and its ELSE", main(ARR,
    "CASE x OF 1: i := 3; 2: i := 4; ELSE i := 6; END_CASE;\narr[i] := 5;\nx := 3;\n"
    "CASE x OF 1: i := 3; 2: i := 4; ELSE i := 6; END_CASE;\narr[i] := 7;"),
    {"arr": [0, 0, 5, 0, 0]}, faults=[("F-INDEX", 8, 1)])
row("ranges", "a store that may fault keeps the old range too", main(ARR + "k : INT;",
    "i := 2;\ni := 10 / k;\narr[i] := 4;"), {"arr": [0, 4, 0, 0, 0], "i": 2}, faults=[("F-DIV-ZERO", 5, 1)])
row("ranges", "a sum that wraps leaves the range", main(ARR + "s : SINT := 120;",
    # 120 + 10 wraps to -126 in the SINT store: i = -126 + 130 = 4
    "s := s + 10;\ni := SINT_TO_INT(s) + 130;\narr[i] := 1;"), {"arr": [0, 0, 0, 1, 0]})
row("ranges", "a WHILE body's stores are unknown after it", main(ARR,
    "i := 1;\nWHILE i < 6 DO i := i + 1; END_WHILE;\narr[i] := 1;"), {"i": 6}, faults=[("F-INDEX", 6, 1)])
row("ranges", "a REPEAT body's stores", main(ARR,
    "i := 1;\nREPEAT i := i * 3; UNTIL i > 5 END_REPEAT;\narr[i] := 1;"), {"i": 9}, faults=[("F-INDEX", 6, 1)])
row("ranges", "a FUNCTION's local through an unrolled loop", main("y : INT;", "y := F(4);", before="""FUNCTION F : INT
VAR_INPUT n : INT; END_VAR
VAR t : ARRAY[1..3] OF INT := [10, 20, 30]; k, p : INT; END_VAR
p := 1;
FOR k := 1 TO 3 DO IF k = n THEN p := k; END_IF; END_FOR;
F := t[p];
p := n;
F := F + t[p];
END_FUNCTION"""), {"y": 10}, faults=[("F-INDEX", 8, 1)])


@pytest.mark.parametrize("r", ROWS, ids=lambda r: r.id)
def test_row(r: Row):
    check(r)


# ---------------------------------------------------------------- the switches (__init__.py)

SWITCHES = ["fold", "unroll", "cse", "unguard", "fuse", "gather", "inline", "vector", "ranges", "branches",
            "aliases", "fastpath", "chains", "sets", "stores", "unused", "offsets", "reuse", "charges", "settle",
            "spread", "halves", "shortcut", "finite", "deferred", "wraps", "stores_read", "temps", "seal",
            "scalars", "sums", "pivots", "native", "kernels", "loops", "elements", "dormant",
            "threads", "early"]


def _switches(o: Optimisations) -> dict[str, bool]:
    return {name: getattr(o, name) for name in SWITCHES}


@pytest.mark.parametrize("value, on", [
    (None, set(SWITCHES) - {"gather"}),           # unset: every pass but gather
    ("", set(SWITCHES) - {"gather"}),
    ("all", set(SWITCHES) - {"gather"}),
    (" ALL ", set(SWITCHES) - {"gather"}),
    ("none", set()),
    ("None", set()),
    ("fold", {"fold"}),
    ("Fold, UNROLL", {"fold", "unroll"}),
    (" cse ,, vector ,", {"cse", "vector"}),
    ("gather", {"gather"}),
])
def test_the_environment_picks_the_passes(monkeypatch, value, on):
    if value is None:
        monkeypatch.delenv("ST_RUNTIME_OPTIMISE", raising=False)
    else:
        monkeypatch.setenv("ST_RUNTIME_OPTIMISE", value)
    assert _switches(Optimisations.from_environment()) == {name: name in on for name in SWITCHES}


def test_the_switches_and_their_defaults():
    assert sorted(_switches(Optimisations())) == sorted(SWITCHES)
    assert _switches(Optimisations()) == {name: name != "gather" for name in SWITCHES}
    assert _switches(Optimisations.none()) == {name: False for name in SWITCHES}
    assert _switches(Optimisations.only("reuse", "finite")) == {name: name in ("reuse", "finite") for name in SWITCHES}
    assert _switches(Optimisations.only()) == _switches(Optimisations.none())


@pytest.mark.parametrize("names", [("folding",), ("fold", "Unroll"), ("x", "all")])
def test_an_unknown_pass_is_named_with_the_known_ones(names):
    known = sorted(SWITCHES)
    unknown = sorted(set(names) - set(SWITCHES))
    with pytest.raises(ValueError) as raised:
        Optimisations.only(*names)
    assert str(raised.value) == f"unknown optimisation(s) {unknown}; known: {known}"


def test_an_unknown_pass_in_the_environment(monkeypatch):
    monkeypatch.setenv("ST_RUNTIME_OPTIMISE", "fold,bogus")
    with pytest.raises(ValueError) as raised:
        Optimisations.from_environment()
    assert str(raised.value).startswith("unknown optimisation(s) ['bogus']; known: ['aliases', 'branches',")


# ----------------------------------------------- F-PERIOD at every budget (speed-only passes)
# fastpath, chains, charges, unroll, cse, fuse and reuse change only how the time is
# charged and checked: the scan must stop on the same statement (F-PERIOD's code, line and
# scan), leave the same state and charge the same time at every budget, in steps finer
# than a statement's charge, from far below the program's time to past the fast path's
# worst case.  The reference is the program with every pass off.

WORK = """FUNCTION Work : LREAL
VAR_IN_OUT x : ARRAY[1..6] OF LREAL; END_VAR
VAR k, j : INT; s : LREAL; END_VAR
FOR k := 1 TO 6 DO
  FOR j := k TO 6 DO
    x[j] := x[j] + x[k] * 0.5;
    x[j] := x[j] * 0.75;
  END_FOR;
  IF x[k] > 3.0 THEN s := s + 1.0; ELSIF x[k] < -1.0 THEN s := s - 1.0; END_IF;
  CASE k OF 1: s := s + 2.0; 2, 3: s := s * 2.0; END_CASE;
END_FOR;
FOR k := 6 TO 1 BY -1 DO
  FOR j := 1 TO k DO s := s + x[j] * x[k]; END_FOR;
END_FOR;
FOR k := 1 TO 3 DO
  FOR j := 1 TO 2 DO x[k * 2 - 2 + j] := x[k * 2 - 2 + j] - s * 0.01; END_FOR;
END_FOR;
FOR k := 2 TO 6 BY 2 DO
  FOR j := k - 1 TO k DO s := s - x[j]; END_FOR;
END_FOR;
Work := s;
END_FUNCTION
FUNCTION Search : INT
VAR_INPUT limit : LREAL; n : INT; END_VAR
VAR k, j : INT; s : LREAL; END_VAR
FOR k := 1 TO n DO
  FOR j := 1 TO 4 DO s := s + INT_TO_LREAL(j * k); END_FOR;
  Search := k;
  IF s > limit THEN EXIT; END_IF;
END_FOR;
END_FUNCTION
PROGRAM Main
VAR a : ARRAY[1..6] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, -6.0]; r : LREAL; n, found : INT; END_VAR
r := Work(a);
found := Search(35.0 + INT_TO_LREAL(n), 9);
n := n + 1;
END_PROGRAM
"""

SWEEP = {"fastpath": Optimisations.only("fastpath"), "chains": Optimisations.only("fastpath", "chains"),
         "charges": Optimisations.only("charges"), "unroll": Optimisations.only("unroll"),
         "cse, fuse": Optimisations.only("unroll", "cse", "fuse"), "reuse": Optimisations.only("reuse"),
         "every": EVERY}


def _landings(src: str, optimise: Optimisations, budgets, scans: int = 2, stop: bool = False) -> list:
    from test_optimiser_equivalence import snapshot

    compiled = compile_program(api.load_text(src, "m.st").program, optimise=optimise)
    found = []
    for budget in budgets:
        controller = Controller(compiled, time_limit_ns=budget, stop_on_fault=stop)
        main = controller.add_program("Main")
        left = []
        for _ in range(scans):
            controller.run(1)
            left.append(controller.ctx.budget)
        found.append((budget, [(f.code, f.line, f.scan) for f in controller.faults], snapshot(main), left))
    return found


@pytest.fixture(scope="module")
def work_reference():
    program = api.load_text(WORK, "m.st").program
    controller = Controller(compile_program(program, optimise=NONE), time_limit_ns=10_000_000)
    controller.add_program("Main")
    controller.run(1)
    spent_ns = 10_000_000 - controller.ctx.budget // 1000
    budgets = sorted({max(1, spent_ns * p // 200) for p in range(10, 241, 3)} | set(range(890, 1000, 2)))
    return budgets, _landings(WORK, NONE, budgets)


@pytest.mark.parametrize("name", SWEEP, ids=SWEEP.keys())
def test_f_period_lands_the_same_at_every_budget(name: str, work_reference):
    budgets, reference = work_reference
    assert any(faults for _, faults, _, _ in reference) and not all(faults for _, faults, _, _ in reference)
    assert _landings(WORK, SWEEP[name], budgets) == reference


def _work_by_hand(x: list[float]) -> float:
    """Work's statements in Python's floats, in the ST's order (x 1-based in the ST)."""
    s = 0.0
    for k in range(1, 7):
        for j in range(k, 7):
            x[j - 1] = x[j - 1] + x[k - 1] * 0.5
            x[j - 1] = x[j - 1] * 0.75
        if x[k - 1] > 3.0:
            s = s + 1.0
        elif x[k - 1] < -1.0:
            s = s - 1.0
        if k == 1:
            s = s + 2.0
        elif k in (2, 3):
            s = s * 2.0
    for k in range(6, 0, -1):
        for j in range(1, k + 1):
            s = s + x[j - 1] * x[k - 1]
    for k in range(1, 4):
        for j in range(1, 3):
            x[k * 2 - 2 + j - 1] = x[k * 2 - 2 + j - 1] - s * 0.01
    for k in range(2, 7, 2):
        for j in range(k - 1, k + 1):
            s = s - x[j - 1]
    return s


@pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])
def test_the_work_program_s_values_by_hand(optimise):
    # Search: s after k passes = 10 * (1 + ... + k) = 10, 30, 60: passes 35 (scan 1) and 36
    # (scan 2) at k = 3
    x = [1.0, 2.0, 3.0, 4.0, 5.0, -6.0]
    _work_by_hand(x)
    r = _work_by_hand(x)
    _, faults, state, _ = _landings(WORK, optimise, [10_000_000])[0]
    values = dict(state[1:])
    assert faults == [] and values["v_FOUND"] == 3 and values["v_N"] == 2
    assert values["v_R"] == ("f", r.hex()) and values["v_A"] == tuple(("f", v.hex()) for v in x)


# ------------------------------------------------------------------- unroll: the POU's cap
# A FOR is unrolled while the statements its copies make (count x the body's size, the size
# counted with every constant inner FOR unrolled) fit the POU's cap.  With the cap set to
# exactly that number the loop is unrolled, one less and it is not: each compound
# statement's size by hand (a statement 1; IF/CASE 1 + its bodies; WHILE/REPEAT 1 + body;
# FOR 1 + count x body, or 1 + body when its bounds are data).

CAPPED = {
    "one statement": ("s := s + 1;", 1),
    "IF, ELSIF, ELSE": ("IF c THEN s := s + 1; s := s + 2; ELSIF d THEN s := 0; ELSE s := 1; s := 2; s := 3; END_IF;", 7),
    "CASE and ELSE": ("CASE k OF 1: s := 1; 2: s := 2; s := 3; ELSE s := 4; END_CASE;", 5),
    "WHILE": ("WHILE s < 0 DO s := s + 1; s := s + 1; END_WHILE;", 3),
    "REPEAT": ("REPEAT s := s + 1; UNTIL s > 0 END_REPEAT;", 2),
    "an inner FOR by 3": ("FOR j := 1 TO 10 BY 3 DO s := s + j; END_FOR;", 5),
    "an inner FOR by -4": ("FOR j := 10 TO 1 BY -4 DO s := s + j; s := s - 1; END_FOR;", 7),
    "an inner FOR over data": ("FOR j := 1 TO n DO s := s + 1; s := s + 2; END_FOR;", 3),
    "an inner FOR of no pass": ("FOR j := 1 TO 0 DO s := 1; END_FOR;", 1),
    "an IF in an inner FOR": ("FOR j := 1 TO 2 DO IF c THEN s := 1; END_IF; END_FOR; s := 0;", 6),
}


@pytest.mark.parametrize("body, size", CAPPED.values(), ids=CAPPED.keys())
def test_the_cap_counts_each_statement_of_the_copies(monkeypatch, body: str, size: int):
    from st_runtime.compiler.optimise import unroll

    src = main("s, k, j : INT; n : INT := 2; c, d : BOOL;", f"FOR k := 1 TO 3 DO {body} END_FOR;")
    program = api.load_text(src, "m.st").program
    for cap, unrolled in ((3 * size, True), (3 * size - 1, False)):
        monkeypatch.setattr(unroll, "UNROLL_CAP", cap)
        code = compile_program(program, optimise=Optimisations.only("unroll")).python_sources["MAIN"]
        assert ("for v_K in" not in code) == unrolled, (cap, code)


# ---------------------------------------------------------------- fastpath: which bodies
# A body gets its fast copy when its worst case is bounded (FOR loops with constant bounds
# that leave their variable alone, callees in ST bounded too, no METHOD) and its exact code
# has at least `WORTH` budget checks.  Eight constant loops give eight checks.

LOOPS8 = "\n".join(f"FOR k := 1 TO {n} DO s := s + k; END_FOR;" for n in range(2, 10))
FAST = r"if _ctx\.budget >= \d+"


def fast_src(extra: str, loops: str = LOOPS8, before: str = "") -> str:
    return main("r : INT;", "r := F(2);", before=f"""{before}
FUNCTION F : INT
VAR_INPUT n : INT; END_VAR VAR s, k, j : INT; t : LREAL; END_VAR
{loops}
{extra}
F := s;
END_FUNCTION""")


# s = (1 + 2) + (1 + 2 + 3) + ... + (1 + ... + 9) = 3 + 6 + 10 + 15 + 21 + 28 + 36 + 45 = 164
# G(m) = 2 m - m = m, bounded (a constant FOR); W(m) = m by a WHILE, not bounded.
CALLEES = """FUNCTION G : INT
VAR_INPUT m : INT; END_VAR VAR i : INT; END_VAR
FOR i := 1 TO 2 DO G := G + m; END_FOR;
G := G - m;
END_FUNCTION
FUNCTION W : INT
VAR_INPUT m : INT; END_VAR
WHILE W < m DO W := W + 1; END_WHILE;
END_FUNCTION"""
for name, extra, more, fast in (
        ("eight constant loops", "", 0, True),
        ("seven are too few", None, 0, False),
        ("a WHILE", "WHILE j < n DO j := j + 1; END_WHILE;", 0, False),
        ("a REPEAT", "REPEAT j := j + 1; UNTIL j >= n END_REPEAT;", 0, False),
        ("a FOR over data", "FOR j := 1 TO n DO s := s + 1; END_FOR;", 2, False),
        ("a FOR with a variable step", "FOR j := 1 TO 4 BY n DO s := s + 1; END_FOR;", 2, False),
        ("an IF and a CASE", "IF n > 1 THEN s := s + 1; ELSE s := 0; END_IF; CASE n OF 2: s := s + 1; END_CASE;", 2, True),
        ("a bounded FUNCTION call", "s := s + G(3);", 3, True),
        ("a FUNCTION with a WHILE", "s := s + W(3);", 3, False),
        ("a standard function", "t := SQRT(INT_TO_LREAL(s)); s := s + LREAL_TO_INT(t);", 13, True),
        ("an EXIT", "FOR j := 1 TO 3 DO s := s + 1; IF s > 160 THEN EXIT; END_IF; END_FOR;", 1, True)):
    loops = LOOPS8 if extra is not None else "\n".join(LOOPS8.split("\n")[1:])
    total = 164 + more if extra is not None else 164 - 3
    row("fastpath", name, fast_src(extra or "", loops, before=CALLEES), {"r": total}, **({"shape": ("F", FAST)} if fast else {"never": ("F", FAST)}))
row("fastpath", "an FB's body with a bounded FB call", main("f : Outer; r : INT;", "f(); r := f.s;", before="""
FUNCTION_BLOCK Inner
VAR_OUTPUT o : INT; END_VAR VAR i : INT; END_VAR
FOR i := 1 TO 3 DO o := o + i; END_FOR;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Outer
VAR_OUTPUT s : INT; END_VAR VAR k : INT; g : Inner; END_VAR
""" + LOOPS8 + """
g();
s := s + g.o;
END_FUNCTION_BLOCK"""), {"r": 170}, shape=("OUTER", FAST))
row("fastpath", "a METHOD call", main("f : Outer; r : INT;", "f(); r := f.s;", before="""
FUNCTION_BLOCK Outer
VAR_OUTPUT s : INT; END_VAR VAR k : INT; END_VAR
METHOD Two : INT
Two := 2;
END_METHOD
""" + LOOPS8 + """
s := s + THIS.Two();
END_FUNCTION_BLOCK"""), {"r": 166}, never=("OUTER", FAST))


# A fault inside a fast copy, with stop_on_fault: the scan ends there, and the time charged
# (what a fault handler takes back of the charges made ahead) is the exact path's.

FAULTY = """FUNCTION Divide : LREAL
VAR_IN_OUT x : ARRAY[1..6] OF LREAL; END_VAR
VAR_INPUT d : ARRAY[1..6] OF INT; END_VAR
VAR k, j : INT; s : LREAL; q : INT; END_VAR
FOR k := 1 TO 6 DO
  FOR j := 1 TO 2 DO s := s + x[k] * INT_TO_LREAL(j); END_FOR;
  q := 12 / d[k];
  x[k] := x[k] + INT_TO_LREAL(q);
  FOR j := 1 TO 2 DO s := s - 0.5; END_FOR;
END_FOR;
FOR k := 1 TO 2 DO FOR j := 1 TO 2 DO s := s * 1.5; END_FOR; END_FOR;
FOR k := 1 TO 2 DO s := s + 0.25; END_FOR;
Divide := s;
END_FUNCTION
PROGRAM Main
VAR a : ARRAY[1..6] OF LREAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]; d : ARRAY[1..6] OF INT := [1, 2, 3, 0, 4, 6];
    r : LREAL; n : INT; END_VAR
r := Divide(a, d);
n := n + 1;
END_PROGRAM
"""


@pytest.mark.parametrize("name", ["fastpath", "chains", "charges", "every"])
def test_a_fault_that_stops_the_scan_in_a_fast_copy(name: str):
    budgets = [10_000_000] + list(range(100, 1400, 37))
    reference = _landings(FAULTY, NONE, budgets, stop=True)
    assert reference[0][1] == [("F-DIV-ZERO", 7, 1)]
    assert _landings(FAULTY, SWEEP[name], budgets, stop=True) == reference

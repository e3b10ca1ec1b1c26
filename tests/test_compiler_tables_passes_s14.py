"""The optimiser passes' table, session 14 (issue 16; docs/mutation.md, compiler, "Session 14,
optimise"): rows for the lines and branches of optimise/ that the compiler's mutation test
selection never ran (coverage.py, branch mode), and for session 13's leftovers.  The rows
are `Row`s of test_compiler_tables_passes (the values after the scans worked out by hand,
held with the pass alone, with none and with every pass, the NJ time charged the same);
the helpers that only rewrite text are held to their contract written out by hand.
"""

from __future__ import annotations

import re
from types import SimpleNamespace

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.compiler.optimise import chains, cse, fuse
from st_runtime.controller import Controller

from test_compiler_tables_passes import CALLEES, EVERY, FAST, LOOPS8, NONE, Row, _landings, check, fast_src, main, modes_fb

ROWS: list[Row] = []


def row(*args, **kwargs) -> None:
    ROWS.append(Row(*args, **kwargs))


# ------------------------------------------------------------------------------- absolute
# A one-argument call that is not the standard ABS keeps its call.  `NS.F(x)`: the checker
# lowers the namespaced call to `F(x)` (its target recorded under the inner call, none under
# the outer): F(1.0) = 11.0 by hand, 11.0 < 2.0 FALSE, 11.0 <= 11.0 TRUE.

row("inline", "a namespaced one-argument call beside a bound", main(
    "r, s : BOOL; x : LREAL := 1.0;", "r := NS.F(x) < 2.0;\ns := NS.F(x) <= 11.0;", before="""
NAMESPACE NS
FUNCTION F : LREAL
VAR_INPUT x : LREAL; END_VAR
F := x + 10.0;
END_FUNCTION
END_NAMESPACE"""), {"r": False, "s": True}, never=("MAIN", r"< v_X <|<= v_X <="))

# ----------------------------------------------------------------------------------- fold
# A CONSTANT array with fewer initial values than elements: the rest hold their type's
# initial value (IEC 61131-3 2.4.2: 0 for INT).  t[2] = 4, t[4] = 0, t[5] = 0.

row("fold", "a CONSTANT array's elements past its initial values", main(
    "r, q : INT; END_VAR VAR CONSTANT t : ARRAY[1..5] OF INT := [3, 4];", "r := t[2] + t[4];\nq := t[5];"),
    {"r": 4, "q": 0})

# ------------------------------------------------------------------------------- fastpath
# (fast_src: the eight constant loops give s = 164 and the eight budget checks of WORTH.)

for name, extra, more, fast in (
        ("an empty statement in a loop", "FOR j := 1 TO 2 DO ; s := s + 1; END_FOR;", 2, True),
        ("two calls of one FUNCTION", "s := s + G(3) + G(1);", 4, True),
        ("a FOR with a constant step", "FOR j := 1 TO 6 BY 2 DO s := s + 1; END_FOR;", 3, True),
        ("a FOR with a constant step down", "FOR j := 6 TO 1 BY -2 DO s := s + j; END_FOR;", 12, True),
        ("a FUNCTION with a WHILE in an IF condition", "IF W(3) > 2 THEN s := s + 1; END_IF;", 1, False),
        ("a FUNCTION with a WHILE in a CASE selector", "CASE W(3) OF 3: s := s + 1; END_CASE;", 1, False),
        ("a WHILE in an IF's ELSE", "IF n > 5 THEN s := s + 1; ELSE WHILE j < n DO j := j + 1; END_WHILE; END_IF;", 0, False),
        ("a WHILE in a CASE's ELSE", "CASE n OF 5: s := s + 1; ELSE WHILE j < n DO j := j + 1; END_WHILE; END_CASE;", 0, False),
        ("a WHILE in an ELSIF", "IF n > 5 THEN s := s + 1; ELSIF n > 1 THEN WHILE j < n DO j := j + 1; END_WHILE; END_IF;", 0, False),
        ("a loop over 64 values of an outer variable", "FOR j := 1 TO 64 DO FOR k := j TO j DO s := s + 1; END_FOR; END_FOR;", 64, True),
        ("a loop over 65 values of an outer variable", "FOR j := 1 TO 65 DO FOR k := j TO j DO s := s + 1; END_FOR; END_FOR;", 65, False)):
    row("fastpath", name, fast_src(extra, before=CALLEES), {"r": 164 + more}, **({"shape": ("F", FAST)} if fast else {"never": ("F", FAST)}))

# A PROPERTY's GET accessor runs ST code a body's bound does not see: no fast copy (CODESYS
# dialect, where PROPERTY is).  Box.Value GETs Raw = 5: s = 164 + 5, and 164 + 2 * 5.
BOX = """FUNCTION_BLOCK Box
VAR Raw : INT := 5; END_VAR
PROPERTY Value : INT
GET
    Value := Raw;
END_GET
END_PROPERTY
END_FUNCTION_BLOCK"""

for name, extra, more in (("a PROPERTY read", "s := s + b.Value;", 5),
                          ("a PROPERTY read in a loop", "FOR j := 1 TO 2 DO s := s + b.Value; END_FOR;", 10)):
    row("fastpath", name, main("f : Outer; r : INT;", "f();\nr := f.s;", before=BOX + f"""
FUNCTION_BLOCK Outer
VAR_OUTPUT s : INT; END_VAR VAR k, j : INT; b : Box; END_VAR
{LOOPS8}
{extra}
END_FUNCTION_BLOCK"""), {"r": 164 + more}, never=("OUTER", FAST), dialects=("codesys",))

# --------------------------------------------------------------------------------- vector
# A run's inputs that are elements of one list, at least MIN_ELEMENTS (8) of them, pass that
# list whole (`_kN(v_A, ...)`); seven elements, or elements of two lists, pass `None` and
# each input by name.  Runs of 147 and 128 sums `s := s + x[i] * y[j] * c` (3 operations
# each, above MIN_OPERATIONS); the value is the same sum in Python's floats, term by term in
# the ST's order (LREAL: binary64), with M and N different so a list taken for the other
# would show.
M = [0.5 + k / 8 for k in range(16)]
N = [2.0 - k / 16 for k in range(16)]


def products(terms) -> str:
    body = "\n".join(f"s := s + {x}[{i}] * {y}[{j}] * {c};" for x, i, y, j, c in terms)
    return main("m : ARRAY[1..16] OF LREAL := [" + ", ".join(map(str, M)) + "]; n : ARRAY[1..16] OF LREAL := ["
                + ", ".join(map(str, N)) + "]; r : LREAL;", "r := Big(m, n);",
                before="FUNCTION Big : LREAL\nVAR_INPUT a, b : ARRAY[1..16] OF LREAL; END_VAR VAR s : LREAL; END_VAR\n"
                + body + "\nBig := s;\nEND_FUNCTION")


def by_hand(terms) -> float:
    s = 0.0
    for x, i, y, j, c in terms:
        s = s + {"a": M, "b": N}[x][i - 1] * {"a": M, "b": N}[y][j - 1] * float(c)
    return s


for name, terms, whole in (
        ("seven elements of one list: each by name",
         [("a", i, "a", j, c) for c in ("1.5", "0.25", "3.0") for i in range(1, 8) for j in range(1, 8)], "None"),
        ("eight elements of one list: the list whole",
         [("a", i, "a", j, c) for c in ("1.5", "0.25") for i in range(1, 9) for j in range(1, 9)], "v_A"),
        ("elements of two lists: each by name",
         [("a", i, "b", j, c) for c in ("1.5", "0.25") for i in range(1, 9) for j in range(1, 9)], "None")):
    row("vector", name, products(terms), {"r": by_hand(terms)},
        shape=("BIG", rf"v_S, (?:v_BIG, )?= _k\d+\({whole}, "), with_=("unguard", "charges", "fuse"))

# ------------------------------------------------------------------------------- unguard
# `A := B` of two arrays loses its handler only when B is the POU's own array or a global's:
# an in-out's array keeps it (the contract names own and global storage only).  m = [1, 2, 3]
# copied: F = a[2] = 2; b[2] := 7 copied: a[2] = 7.

row("unguard", "a copy of an in-out's array keeps its handler", main(
    "m : ARRAY[1..3] OF INT := [1, 2, 3]; y : INT;", "y := F(m);", before="""FUNCTION F : INT
VAR_IN_OUT x : ARRAY[1..3] OF INT; END_VAR VAR a : ARRAY[1..3] OF INT; END_VAR
a := x;
F := a[2];
END_FUNCTION"""), {"m": [1, 2, 3], "y": 2}, never=("F", r"\n        v_A\[_WHOLE\] = v_X"))
row("unguard", "a copy between a FUNCTION's own arrays", main("y : INT;", "y := F(1);", before="""FUNCTION F : INT
VAR_INPUT n : INT; END_VAR VAR a, b : ARRAY[1..3] OF INT; END_VAR
b[2] := 7;
a := b;
F := a[2] + n;
END_FUNCTION"""), {"y": 8}, shape=("F", r"\n        v_A\[_WHOLE\] = v_B"))

# ----------------------------------------------------------------------------------- sets
# A TIME compared with TIME literals is no integer variable: no membership test (T#2s = 2 s).
row("sets", "a TIME is not tested by membership", main("t : TIME := T#2s; r, s : BOOL;",
    "r := t = T#1s OR t = T#2s;\ns := t <> T#1s AND t <> T#2s;"), {"r": True, "s": False}, never=("MAIN", r" in \{"))

# ----------------------------------------------------------------------------- spread, stores
# A clause that stores the cached Cnt only through an output (`q => Cnt`) stores it back as a
# clause with `:=` does.  Mode 0..3 a scan: Mode 1: Cnt = (0 + 1) * 2 = 2, Out = 2; Mode 2:
# Out = Q = 5; Mode 3: Inc gives q = x + 10 = 12 into Cnt, Out = 12.
INC = """FUNCTION_BLOCK Inc
VAR_INPUT x : INT; END_VAR VAR_OUTPUT q : INT; END_VAR
q := x + 10;
END_FUNCTION_BLOCK"""
for pass_ in ("spread", "stores"):
    row(pass_, "a cached variable stored through an output in one clause", modes_fb(
        "CASE Mode OF 1: Cnt := Cnt + 1; Cnt := Cnt * 2; Out := INT_TO_LREAL(Cnt); 2: Out := Q; "
        "3: g(x := Cnt, q => Cnt); Out := INT_TO_LREAL(Cnt); END_CASE;", extra="g : Inc;", before=INC),
        {"outs": [0.0, 2.0, 5.0, 12.0], "f.Cnt": 12}, scans=4)

# ---------------------------------------------------------------------------------- ranges
# A variable passed to an output (`q => i`) or an in-out is not followed past the call: the
# call may store any value of its type.  i := 1, then the call gives i = -1: arr[i] is out of
# ARRAY[1..3] (F-INDEX at the read's line, 14, scan 1; y keeps 0).
NEG = """FUNCTION_BLOCK Neg
VAR_OUTPUT q : INT; END_VAR
q := -1;
END_FUNCTION_BLOCK
FUNCTION SetNeg : INT
VAR_IN_OUT v : INT; END_VAR
v := -1;
SetNeg := 0;
END_FUNCTION"""
row("ranges", "an index stored through an output is not followed past the call", main(
    "arr : ARRAY[1..3] OF INT := [10, 20, 30]; i, y : INT; g : Neg;", "i := 1;\ng(q => i);\ny := arr[i];",
    before=NEG), {"i": -1, "y": 0}, faults=[("F-INDEX", 14, 1)])
row("ranges", "an index passed to an in-out is not followed past the call", main(
    "arr : ARRAY[1..3] OF INT := [10, 20, 30]; i, y, z : INT;", "i := 1;\nz := SetNeg(i);\ny := arr[i];",
    before=NEG), {"i": -1, "y": 0, "z": 0}, faults=[("F-INDEX", 14, 1)])

# ----------------------------------------------------------------------------------- fuse
# A region's lines are merged from its first: of the unrolled copies of `y := y + a * b` in
# the region (a * b = 3.0 exactly, y = 9.0 after three), the first two are one line,
# `((y + p) + p)`, and the next follows it.
row("fuse", "a region's first line merged with its second", main(
    "a : LREAL := 1.5; b : LREAL := 2.0; y : LREAL; i : INT;", "FOR i := 1 TO 3 DO y := y + a * b; END_FOR;"),
    {"y": 9.0}, with_=("unguard",),
    shape=("MAIN", r"\n {12}v_Y = \(\(v_Y \+ \(v_A \* v_B\)\) \+ \(v_A \* v_B\)\)\n {12}v_Y = \(v_Y \+ "))

# ------------------------------------------------------------------------------- branches
# A condition reading a REF_TO variable, or a structure's REF_TO member, keeps its handler
# (`_t1 = ...` in a try: comparing two reference objects runs Python code); the same
# comparison of INTs is tested in place (`if (...)`).  p := REF(x), q NULL: p <> q TRUE;
# both REF(x): FALSE.
for name, q, y in (("against NULL", "", 1), ("to one variable", "q := REF(x);\n", 2)):
    row("branches", f"a condition on two REF variables {name}", main("x : INT; p, q : REF_TO INT; y : INT;",
        f"p := REF(x);\n{q}IF p <> q THEN y := 1; ELSE y := 2; END_IF;"), {"y": y},
        never=("MAIN", r"if \(self\.v_P"))
    row("branches", f"a condition on two REF members {name}", main("s : S; x : INT; y : INT;",
        f"s.r := REF(x);\n{q.replace('q :=', 's.q :=')}IF s.r <> s.q THEN y := 1; ELSE y := 2; END_IF;",
        before="TYPE S : STRUCT r, q : REF_TO INT; END_STRUCT; END_TYPE"), {"y": y}, never=("MAIN", r"if \(v_S"))
row("branches", "a condition on two INTs is tested in place", main("p, q : INT; y : INT;",
    "p := 3;\nIF p <> q THEN y := 1; ELSE y := 2; END_IF;"), {"y": 1}, shape=("MAIN", r"if \(self\.v_P != self\.v_Q\):"))


@pytest.mark.parametrize("r", ROWS, ids=lambda r: r.id)
def test_row(r: Row):
    check(r)


# ------------------------------------------------------------------ text helpers, by hand
# chains._atom: an operand as it is when one pair of parentheses encloses it all, else
# parenthesised; fuse._enclosed: whether a text is one parenthesised group; cse._put_in:
# the first whole-word occurrence of a temporary replaced; cse.inline_single_uses: a shared
# temporary set once and read once is put back into its read, any other left as it is.

@pytest.mark.parametrize("code, atom", [
    ("a", "(a)"), ("(a + b)", "(a + b)"), ("(a) + (b)", "((a) + (b))"), ("((a) * b)", "((a) * b)"),
    ("(a) * b", "((a) * b)"), ("a * (b)", "(a * (b))"), ("(a)", "(a)")])
def test_chains_atom(code, atom):
    assert chains._atom(code) == atom


@pytest.mark.parametrize("text, enclosed", [
    ("(a + b)", True), ("((a) + b)", True), ("(a)", True), ("a", False), ("(a) + (b)", False),
    ("(a) * b", False), ("a * (b)", False), ("(a + (b - c))", True), ("((a)) - ((b))", False)])
def test_fuse_enclosed(text, enclosed):
    assert fuse._enclosed(text) is enclosed


@pytest.mark.parametrize("line, name, text, out", [
    ("    x = _t1 + _t12", "_t1", "(a * b)", "    x = (a * b) + _t12"),
    ("    x = _t12 + _t1", "_t1", "y", "    x = _t12 + y"),
    ("    x = _t1 * _t1", "_t1", "y", "    x = y * _t1"),
    ("    x = _t12 + v_t1", "_t1", "y", "    x = _t12 + v_t1"),
    ("    x = _t12", "_t1", "y", "    x = _t12")])
def test_cse_put_in(line, name, text, out):
    assert cse._put_in(line, name, text) == out


@pytest.mark.parametrize("lines, out", [
    (["    _t1 = (a * b)", "    x = _t1 + 1.0"], ["    x = (a * b) + 1.0"]),
    (["    _t1 = (a * b)", "    x = _t1 + 1.0", "    y = _t1"], None),        # read twice
    (["    x = _t1 + 1.0", "    y = _t1"], None),                              # no line sets it
    (["    z = 2.0", "    _t2 = (c * d)", "    _t1 = (a * b)", "    x = _t1 + _t2"],
     ["    z = 2.0", "    x = (a * b) + (c * d)"]),
    (["    _t3 = (e * f)", "    x = _t3"], None)])                              # not shared
def test_cse_inline_single_uses(lines, out):
    region = SimpleNamespace(shared={"(a * b)": "_t1", "(c * d)": "_t2"})
    got = list(lines)
    cse.inline_single_uses(region, got, 0)
    assert got == (lines if out is None else out)


def test_a_whole_list_s_run_takes_numpy_for_finite_inputs():
    """vector.py's contract at program level: a run passed its list whole (M's 16 finite
    elements) is computed by NumPy, not by its exact Python run (`exact`, for inputs that are
    not finite or may overflow); the value as the row gives it."""
    r = next(r for r in ROWS if r.name.startswith("eight elements"))
    compiled = compile_program(api.load_text(r.src, "m.st", "iec").program, optimise=Optimisations())
    name = re.search(r"= (_k\d+)\(v_A, ", compiled.python_sources["BIG"]).group(1)
    helper = compiled.namespace[name].__self__
    calls, exact = [], helper.exact
    helper.exact = lambda whole, inputs: calls.append(1) or exact(whole, inputs)
    helper.numpy_run()                     # (NumPy's arrays: made at a first call where a native kernel is on)
    helper._compile_run()                  # (the run binds exact when it is written)
    compiled.namespace[name] = helper.run
    controller = Controller(compiled)
    main_ = controller.add_program("Main")
    controller.run(1)
    assert (main_.v_R, controller.faults, calls) == (r.expect["r"], [], [])


# A project's own FUNCTION_BLOCK named like a native one (TON: W-DECL-001, it replaces the
# built-in) runs its ST body, here a WHILE of 200 iterations, inside a body with a fast copy.
# Every pass or fastpath alone: the scan lands the same as with none at every budget from
# 1 ns to past the scan's whole time, 5 ns apart (F-PERIOD's line and scan, the values, the
# budget left), and the value by hand: TON's Q = IN = TRUE, s = 164 + 1.
OWN_TON = """FUNCTION_BLOCK TON
VAR_INPUT IN : BOOL; PT : TIME; END_VAR VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR VAR n : INT; END_VAR
n := 0;
WHILE n < 200 DO n := n + 1; END_WHILE;
Q := IN;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Outer
VAR_OUTPUT s : INT; END_VAR VAR k : INT; t : TON; END_VAR
""" + LOOPS8 + """
t(IN := TRUE, PT := T#1s);
IF t.Q THEN s := s + 1; END_IF;
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Outer; r : INT; END_VAR
f();
r := f.s;
END_PROGRAM
"""


def test_a_project_s_own_ton_in_a_fast_body_lands_the_same_at_every_budget():
    controller = Controller(compile_program(api.load_text(OWN_TON, "m.st").program, optimise=NONE),
                            time_limit_ns=10_000_000)
    main_ = controller.add_program("Main")
    controller.run(1)
    assert (main_.v_R, controller.faults) == (165, [])
    spent_ns = 10_000_000 - controller.ctx.budget // 1000
    budgets = list(range(1, spent_ns + 20, 5))
    expected = _landings(OWN_TON, NONE, budgets, scans=1, stop=True)
    for optimise in (Optimisations.only("fastpath"), EVERY):
        assert _landings(OWN_TON, optimise, budgets, scans=1, stop=True) == expected


# ------------------------------------------------------------------------- unroll: one cap
# The POU's loops share one cap (`unroll_left`): two FORs of 3 copies of one statement each
# (3 statements each) both unroll under a cap of 6, the first alone under 5, neither under 2.
# s = 3 * 1 + 3 * 2 = 9 whichever unrolls.

@pytest.mark.parametrize("cap, first, second", [(6, True, True), (5, True, False), (2, False, False)])
def test_the_pou_s_loops_share_one_unroll_cap(monkeypatch, cap, first, second):
    from st_runtime.compiler.optimise import unroll

    src = main("s, k, j : INT;", "FOR k := 1 TO 3 DO s := s + 1; END_FOR;\nFOR j := 1 TO 3 DO s := s + 2; END_FOR;")
    monkeypatch.setattr(unroll, "UNROLL_CAP", cap)
    compiled = compile_program(api.load_text(src, "m.st").program, optimise=Optimisations.only("unroll"))
    code = compiled.python_sources["MAIN"]
    assert ("for v_K in" not in code, "for v_J in" not in code) == (first, second), code
    controller = Controller(compiled)
    main_ = controller.add_program("Main")
    controller.run(1)
    assert (main_.v_S, controller.faults) == (9, [])

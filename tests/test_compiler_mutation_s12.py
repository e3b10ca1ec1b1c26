"""Compiler behaviours that survivors of the mutation samples of seeds 25 and 27 left open,
pinned down as classes (issue 16, session 12; docs/mutation.md, "st_runtime/compiler/",
"Session 12").

Each test loads ST through the public entry point and takes its expected values from
IEC 61131-3, OMRON's manuals as docs/nj501.md cites them, NumPy, or a hand calculation
stated beside it; where a pass is named, the program runs with every pass and with none.
"""

from __future__ import annotations

import pytest

from st_runtime import api
from st_runtime.compiler import Optimisations, compile_program
from st_runtime.controller import Controller

EVERY, NONE = Optimisations(), Optimisations.none()


def run_with(src: str, optimise: Optimisations, scans: int = 1, dialect: str = "iec"):
    """PROGRAM Main of `src` after `scans` scans compiled with `optimise`; (instance, faults)."""
    controller = Controller(compile_program(api.load_text(src, "m.st", dialect).program, optimise=optimise))
    main = controller.add_program("Main")
    controller.run(scans)
    return main, [(f.code, f.line) for f in controller.faults]


# ------------------------------------ a loop's body stores what a value before the loop read

LOOPS = {
    "WHILE": "WHILE i < n DO z := z + x * 2.0; x := x + 1.0; i := i + 1; END_WHILE;",
    "REPEAT": "REPEAT z := z + x * 2.0; x := x + 1.0; i := i + 1; UNTIL i >= n END_REPEAT;",
    "FOR": "FOR i := 1 TO n DO z := z + x * 2.0; x := x + 1.0; END_FOR;",
    "IF around WHILE": "IF n > 0 THEN WHILE i < n DO z := z + x * 2.0; x := x + 1.0; i := i + 1; "
                       "END_WHILE; END_IF;",
    "CASE around FOR": "CASE n OF 3: FOR i := 1 TO n DO z := z + x * 2.0; x := x + 1.0; END_FOR; END_CASE;",
}


@pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])
@pytest.mark.parametrize("loop", LOOPS.values(), ids=LOOPS.keys())
def test_a_value_computed_before_a_loop_is_computed_again_after_the_body_stores_its_operand(
        loop: str, optimise: Optimisations):
    # `x * 2.0` is computed before the loop (y); the body uses it before it stores x, so each
    # pass of the body sees the x of that pass (IEC 61131-3: a loop runs its statements in
    # order, again): x = 1, 2, 3 gives z = 2 + 4 + 6 = 12, and x ends at 4. The reuse pass
    # may keep y's value for the body's first use only if the loop stored nothing it read;
    # the loop may be inside an IF or a CASE (n is a variable: the FOR is not unrolled).
    main, faults = run_with(f"""PROGRAM Main
VAR n : INT := 3; i : INT; x : LREAL := 1.0; y : LREAL; z : LREAL; END_VAR
y := x * 2.0;
{loop}
END_PROGRAM""", optimise)
    assert (main.v_Y, main.v_Z, main.v_X, faults) == (2.0, 12.0, 4.0, [])


def test_a_function_local_read_before_a_while_and_stored_in_it():
    # The same in a FUNCTION's locals (Python locals): x = 1, then 3; z = x + 1.0 is 2 in the
    # first pass and 4 in the second; F = z + y = 4 + 2 = 6.
    main, faults = run_with("""FUNCTION F : REAL
VAR_INPUT n : INT; END_VAR
VAR x : REAL := 1.0; y : REAL; z : REAL; i : INT; END_VAR
y := x + 1.0;
WHILE i < n DO
  z := x + 1.0;
  x := x + 2.0;
  i := i + 1;
END_WHILE
F := z + y;
END_FUNCTION
PROGRAM Main
VAR r : REAL; END_VAR
r := F(2);
END_PROGRAM""", EVERY)
    assert (main.v_R, faults) == (6.0, [])


# -------------------------------- a FOR inside every compound statement of a FOR's body

NESTED = {
    # Each: FOR i := 1 TO 3 around a body whose inner FOR j := 1 TO 2 adds i * j, so
    # s = (1 + 2 + 3) * (1 + 2) = 18 by hand, whichever statement holds the inner FOR.
    "IF ... ELSE": "IF c THEN s := s + 100; ELSE FOR j := 1 TO 2 DO s := s + i * j; END_FOR; END_IF;",
    "IF ... ELSIF": "IF c THEN s := s + 100; ELSIF NOT c THEN FOR j := 1 TO 2 DO s := s + i * j; END_FOR; "
                    "END_IF;",
    "CASE ... ELSE": "CASE i OF 9: s := s + 100; ELSE FOR j := 1 TO 2 DO s := s + i * j; END_FOR; END_CASE;",
    "CASE clause": "CASE i OF 1..3: FOR j := 1 TO 2 DO s := s + i * j; END_FOR; END_CASE;",
    "WHILE": "k := 0; WHILE k < 1 DO FOR j := 1 TO 2 DO s := s + i * j; END_FOR; k := k + 1; END_WHILE;",
    "REPEAT": "REPEAT FOR j := 1 TO 2 DO s := s + i * j; END_FOR; UNTIL TRUE END_REPEAT;",
    "IF in ELSE": "IF c THEN s := s + 100; ELSE IF NOT c THEN FOR j := 1 TO 2 DO s := s + i * j; END_FOR; "
                  "END_IF; END_IF;",
}


@pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])
@pytest.mark.parametrize("body", NESTED.values(), ids=NESTED.keys())
def test_a_for_nested_in_any_compound_statement_of_a_for(body: str, optimise: Optimisations):
    main, faults = run_with(f"""PROGRAM Main
VAR i : INT; j : INT; k : INT; c : BOOL; s : INT; END_VAR
FOR i := 1 TO 3 DO
  {body}
END_FOR;
END_PROGRAM""", optimise)
    assert (main.v_S, main.v_I, faults) == (18, 4, [])


# ------------------------------------- F-PERIOD in an unrolled FOR lands where the loop's does

UNROLLED = {
    # the body calls a FUNCTION: its charges reach the scan's budget in the middle of the loop
    "a call in a straight body": """FUNCTION Heavy : LREAL
VAR_INPUT x : LREAL; END_VAR
Heavy := SQRT(x) + SQRT(x + 1.0) + SQRT(x + 2.0);
END_FUNCTION
PROGRAM Main
VAR i : INT; s : LREAL; t : LREAL; END_VAR
FOR i := 1 TO 3 DO
  s := s + Heavy(INT_TO_LREAL(i));
END_FOR;
t := s + 1.0;
t := t + 2.0;
END_PROGRAM""",
    "an IF in the body": """PROGRAM Main
VAR i : INT; s : LREAL; t : LREAL; END_VAR
FOR i := 1 TO 4 DO
  IF i > 2 THEN s := s + SQRT(INT_TO_LREAL(i)); ELSE s := s - 1.0; END_IF;
END_FOR;
t := s + 1.0;
END_PROGRAM""",
    "a RETURN in the body": """FUNCTION G : INT
VAR_INPUT n : INT; END_VAR
VAR i : INT; s : INT; END_VAR
FOR i := 1 TO 4 DO
  IF i = n THEN G := s; RETURN; END_IF;
  s := s + i;
END_FOR;
G := s;
END_FUNCTION
PROGRAM Main
VAR r : INT; q : INT; END_VAR
r := G(3);
q := r + G(9);
END_PROGRAM""",
}


@pytest.mark.parametrize("src", UNROLLED.values(), ids=UNROLLED.keys())
def test_f_period_in_an_unrolled_for_lands_where_the_loops_does(src: str):
    # Unrolling is exact (optimise/unroll.py: "the charges are the loop's ... the final test
    # stays after it"): at every budget the scan ends with the same fault on the same line
    # and the same state as the loop compiled without any pass.
    program = api.load_text(src, "m.st").program

    def outcome(optimise: Optimisations, budget_ns: int):
        controller = Controller(compile_program(program, optimise=optimise), time_limit_ns=budget_ns)
        main = controller.add_program("Main")
        controller.run(1)
        state = {name: getattr(main, name) for name in main.__slots__}
        return [(f.code, f.line) for f in controller.faults], state, controller.ctx.budget

    for budget_ns in range(20, 400, 10):
        assert outcome(Optimisations.only("unroll"), budget_ns) == outcome(NONE, budget_ns), budget_ns


# ------------------------------------------- the shared prelude serves the standard FBs

def test_a_shared_prelude_made_again_serves_every_standard_function_block():
    # IEC 61131-3 (2013) 6.6.3.5, standard function blocks: bistables SR and RS, edge detection
    # R_TRIG and F_TRIG, counters CTU, CTD and CTUD, timers TP, TON and TOF; the runtime writes
    # them in Python (st_runtime/stdlib/fbs.py). A SharedPrelude made from the checked prelude
    # hands each compile the class of each, with its layout installed.
    from st_runtime.compiler import SharedPrelude
    from st_runtime.native import NATIVE_FBS

    base = api.load_text("PROGRAM Main\nVAR x : INT; END_VAR\nx := 1;\nEND_PROGRAM").program.prelude
    classes = SharedPrelude(base).install_layouts()
    outputs = {"SR": {"Q1"}, "RS": {"Q1"}, "R_TRIG": {"Q"}, "F_TRIG": {"Q"}, "CTU": {"Q", "CV"},
               "CTD": {"Q", "CV"}, "CTUD": {"QU", "QD", "CV"}, "TP": {"Q", "ET"}, "TON": {"Q", "ET"},
               "TOF": {"Q", "ET"}}        # the standard's output variables of each
    for name, names in outputs.items():
        assert classes[name] is NATIVE_FBS[name], name
        assert names <= set(classes[name]._st_vars), name


# ----------------------------------- a value over a named constant is computed once (reuse)

def test_a_value_over_a_named_constant_is_computed_once():
    # optimise/reuse.py: a `+ - *` of LREAL operands that are literals or plain variables,
    # computed again over unchanged operands, is computed once and read by name. K is a
    # CONSTANT, compiled as the literal 2.0: `x * K + 1.0` is one value for a and b.
    # By hand: x = 3.0, a = b = 3.0 * 2.0 + 1.0 = 7.0.
    src = """FUNCTION_BLOCK B
VAR_INPUT x : LREAL; END_VAR
VAR_OUTPUT a : LREAL; b : LREAL; END_VAR
VAR CONSTANT K : LREAL := 2.0; END_VAR
a := x * K + 1.0;
b := x * K + 1.0;
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : B; END_VAR
f(x := 3.0);
END_PROGRAM"""
    compiled = compile_program(api.load_text(src, "m.st").program, optimise=EVERY)
    assert compiled.python_sources["B"].count("self.v_X * 2.0") == 1
    for optimise in (EVERY, NONE):
        main, faults = run_with(src, optimise)
        assert (main.v_F.v_A, main.v_F.v_B, faults) == (7.0, 7.0, [])


# ---------------------------------------- a CONSTANT aggregate local of a FUNCTION or METHOD

@pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])
def test_constant_aggregate_locals_read_at_a_variable_index(optimise: Optimisations):
    # A CONSTANT array or structure local of a FUNCTION or a METHOD holds its initial values
    # in every call (IEC 61131-3 VAR CONSTANT); read at an index known only at run time:
    # T[3] = 30, T[1] = 10; P.b = 7; the METHOD's table W[2] = 2.5.
    main, faults = run_with("""TYPE Pair : STRUCT a : INT; b : INT; END_STRUCT; END_TYPE
FUNCTION Pick : INT
VAR_INPUT i : INT; END_VAR
VAR CONSTANT T : ARRAY[1..4] OF INT := [10, 20, 30, 40]; P : Pair := (a := 3, b := 7); END_VAR
Pick := T[i] + P.b * 0;
END_FUNCTION
FUNCTION Second : INT
VAR CONSTANT P : Pair := (a := 3, b := 7); END_VAR
Second := P.b;
END_FUNCTION
FUNCTION_BLOCK Box
METHOD Weight : LREAL
VAR_INPUT k : INT; END_VAR
VAR CONSTANT W : ARRAY[1..3] OF LREAL := [0.5, 2.5, 4.5]; END_VAR
Weight := W[k];
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR i : INT := 3; x : INT; y : INT; z : INT; w : LREAL; b : Box; two : INT := 2; END_VAR
x := Pick(i);
y := Pick(1);
z := Second();
w := b.Weight(two);
END_PROGRAM""", optimise)
    assert (main.v_X, main.v_Y, main.v_Z, main.v_W, faults) == (30, 10, 7, 2.5, [])


# ----------------------------- an aggregate named in several branches nested in one branch

BRANCHES = {
    "two IFs in an IF": "IF mode = 1 THEN IF a THEN n := arr[1]; END_IF; IF NOT a THEN n := arr[2]; END_IF; "
                        "END_IF;",
    "IF and ELSE in an IF": "IF mode = 1 THEN IF a THEN n := arr[1]; ELSE n := arr[2]; END_IF; END_IF;",
    "two IFs in a CASE clause": "CASE mode OF 1: IF a THEN n := arr[1]; END_IF; IF NOT a THEN n := arr[3]; "
                                "END_IF; 2: n := 9; END_CASE;",
    "an IF and a CASE in an ELSIF": "IF mode = 0 THEN n := 9; ELSIF mode = 1 THEN IF a THEN n := arr[1]; END_IF; "
                                    "CASE mode OF 5: n := arr[2]; END_CASE; END_IF;",
    "a loop and an IF in an IF": "IF mode = 1 THEN FOR k := 1 TO 1 DO n := arr[k]; END_FOR; "
                                 "IF NOT a THEN n := arr[2]; END_IF; END_IF;",
}


@pytest.mark.parametrize("optimise", [EVERY, Optimisations.only("aliases"), NONE],
                         ids=["every pass", "aliases", "no pass"])
@pytest.mark.parametrize("body", BRANCHES.values(), ids=BRANCHES.keys())
def test_an_array_named_in_branches_nested_in_one_branch(body: str, optimise: Optimisations):
    # With mode = 1 and a = TRUE each body takes the branch that stores arr[1] = 1 (by hand);
    # the aliases pass loads arr where all its uses meet, the outer branch.
    main, faults = run_with(f"""FUNCTION_BLOCK B
VAR_INPUT mode : INT; a : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR
VAR arr : ARRAY[1..3] OF INT := [1, 2, 3]; k : INT; END_VAR
{body}
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : B; END_VAR
f(mode := 1, a := TRUE);
END_PROGRAM""", optimise)
    assert (main.v_F.v_N, faults) == (1, [])


# ------------------------------------------------ a global variable stored past its range

GLOBAL_STORES = [
    # (type, initial value, expression, stored value by hand: two's complement of the width)
    ("SINT", "127", "g + 1", -128), ("INT", "32767", "g + 1", -32768),
    ("DINT", "2147483647", "g + 1", -2**31), ("LINT", "9223372036854775807", "g + 1", -2**63),
    ("USINT", "255", "g + 1", 0), ("UINT", "0", "g - 1", 65535),
    ("UDINT", "4294967295", "g + 2", 1), ("ULINT", "0", "g - 1", 2**64 - 1),
]


@pytest.mark.parametrize("where", ["PROGRAM", "FUNCTION", "FUNCTION_BLOCK"])
@pytest.mark.parametrize("t, initial, expression, stored", GLOBAL_STORES, ids=[g[0] for g in GLOBAL_STORES])
def test_a_global_integer_wraps_to_its_width_when_stored(t, initial, expression, stored, where):
    # README, "Semantics": integers wrap to their width on every store; a global is stored
    # from the PROGRAM's body, a FUNCTION's or an FB's (VAR_EXTERNAL).
    body = f"g := {expression};"
    pous = {"PROGRAM": "", "FUNCTION": f"FUNCTION Store : BOOL\nVAR_EXTERNAL g : {t}; END_VAR\n{body}\n"
                                       f"Store := TRUE;\nEND_FUNCTION\n",
            "FUNCTION_BLOCK": f"FUNCTION_BLOCK Keep\nVAR_EXTERNAL g : {t}; END_VAR\n{body}\nEND_FUNCTION_BLOCK\n"}
    call = {"PROGRAM": body, "FUNCTION": "done := Store();", "FUNCTION_BLOCK": "k();"}[where]
    main, faults = run_with(f"""VAR_GLOBAL g : {t} := {initial}; END_VAR
{pous[where]}PROGRAM Main
VAR_EXTERNAL g : {t}; END_VAR
VAR x : {t}; done : BOOL; {"k : Keep;" if where == "FUNCTION_BLOCK" else ""} END_VAR
{call}
x := g;
END_PROGRAM""", EVERY)
    assert (main.v_X, faults) == (stored, [])


def test_a_global_real_is_rounded_to_single_precision_when_stored():
    # README: REAL is float32, rounded on every store. The two REAL operands are float32(0.1)
    # and float32(0.2); their sum is exact in double and stored rounded to float32 (NumPy).
    import numpy as np

    main, faults = run_with("""VAR_GLOBAL r : REAL; END_VAR
PROGRAM Main
VAR_EXTERNAL r : REAL; END_VAR
VAR a : REAL := 0.1; b : REAL := 0.2; x : LREAL; END_VAR
r := a + b;
x := r;
END_PROGRAM""", EVERY)
    exact = np.float64(np.float32(0.1)) + np.float64(np.float32(0.2))
    assert (main.v_X, faults) == (float(np.float32(exact)), [])


# ---------------------------------------- a METHOD reaches each kind of its FB's variables

@pytest.mark.parametrize("dialect", ["iec", "codesys"])     # (nj: no METHOD, E-DIALECT-001)
def test_a_method_reads_and_writes_each_kind_of_its_fbs_variables(dialect: str):
    # A METHOD works on its instance's variables (IEC 61131-3 (2013) 6.6.5): the input a = 2,
    # the output q, the local n, the elementary in-out io (bound to Main's x = 5) and the
    # array in-out arr (bound to Main's v). Bump: io := 6 (x follows), n := 2 + 6 = 8,
    # arr[2] := 8 (v[2] follows), q := 8 * 2 = 16; it returns q + io = 22.
    main, faults = run_with("""FUNCTION_BLOCK Counter
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
VAR_IN_OUT io : INT; arr : ARRAY[1..3] OF INT; END_VAR
VAR n : INT; END_VAR
METHOD Bump : INT
io := io + 1;
n := a + io;
arr[2] := n;
q := n * 2;
Bump := q + io;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR x : INT := 5; v : ARRAY[1..3] OF INT; c : Counter; y : INT; END_VAR
c(a := 2, io := x, arr := v);
y := c.Bump();
END_PROGRAM""", EVERY, dialect=dialect)
    assert (main.v_X, main.v_V, main.v_C.v_Q, main.v_Y, faults) == (6, [0, 8, 0], 16, 22, [])


# ------------------------------------------- an FB instance's variables, as the API shows them

def test_an_fb_instance_shows_its_own_variables_not_its_externals():
    # st_runtime.api Instance.to_json: "every variable (not VAR_IN_OUT/VAR_EXTERNAL/VAR_TEMP)
    # by declared name"; a path names an instance's variables only. B reads and stores the
    # global g through VAR_EXTERNAL (g = 4, q = 8): g is the global's, not one of f's.
    main, faults = run_with("""VAR_GLOBAL g : INT := 4; END_VAR
FUNCTION_BLOCK B
VAR_EXTERNAL g : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := g * 2;
g := g + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : B; END_VAR
f();
END_PROGRAM""", EVERY)
    view = api.Instance(main)
    assert (view.to_json(), view["f.q"], faults) == ({"f": {"q": 8}}, 8, [])
    with pytest.raises(KeyError, match="no variable 'g'"):
        view["f.g"]


# ------------------------------ a FUNCTION local's known range after a store that wraps

@pytest.mark.parametrize("optimise", [EVERY, NONE], ids=["every pass", "no pass"])
@pytest.mark.parametrize("c, shift, result, faults", [
    # y is -20000 or 10000 (both branches, after y := 0); x := y - 20000 is -40000, which wraps
    # to INT's 25536 (-40000 + 65536), outside arr's -40000..0: F-INDEX on lines 8 and 9, F stays 0;
    # or -10000, inside: arr[-10000] = 0.
    (True, "y - 20000", 0, [("F-INDEX", 8), ("F-INDEX", 9)]), (False, "y - 20000", 0, []),
    # the other end: x := y + 20000 is 0 (inside) or 30000 (outside, no wrap)
    (True, "y + 20000", 0, []), (False, "y + 20000", 0, [("F-INDEX", 8), ("F-INDEX", 9)]),
])
def test_a_local_stored_with_a_sum_that_may_wrap_keeps_its_index_checked(c, shift, result, faults, optimise):
    # README: integers wrap to their width on every store; arrays are checked on every access
    # (F-INDEX). The ranges pass follows FUNCTION locals; a store that may wrap ends what it
    # knew of x, so arr[x] stays checked.
    main, found = run_with(f"""FUNCTION F : INT
VAR_INPUT c : BOOL; END_VAR
VAR y : INT; x : INT; arr : ARRAY[-40000..0] OF INT; END_VAR
y := 0;
IF c THEN y := -20000; ELSE y := 10000; END_IF;
x := 0;
x := {shift};
F := arr[x];
F := F + arr[x];
END_FUNCTION
PROGRAM Main
VAR r : INT; END_VAR
r := F({"TRUE" if c else "FALSE"});
END_PROGRAM""", optimise)
    assert (main.v_R, found) == (result, faults)


# --------------------------------------- an in-out costs one reference, whatever its size

@pytest.mark.parametrize("call", ["f{n}(io := a{n});", "f{n}(EN := go, io := a{n});",
                                  "f{n}(EN := go, io := a{n}, ENO => ok);"],
                         ids=["plain", "EN", "EN and ENO"])
def test_an_in_out_array_costs_one_reference_whatever_its_size(call: str):
    # docs/nj501.md, "What a scan costs" (cost.py, CostModel._arguments): an argument passed
    # by value costs one `argument` per element, a VAR_IN_OUT one `argument` (a reference)
    # and its location. The FBs differ only in the in-out's size (2 or 10 elements) and run
    # the same body, so the two scans cost the same, with EN / ENO or without.
    from test_compiler_mutants import _scan_ps

    def scan(n: int) -> int:
        return _scan_ps(f"""FUNCTION_BLOCK B{n}
VAR_IN_OUT io : ARRAY[1..{n}] OF INT; END_VAR
VAR k : INT; END_VAR
k := k + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR f{n} : B{n}; a{n} : ARRAY[1..{n}] OF INT; go : BOOL := TRUE; ok : BOOL; END_VAR
{call.format(n=n)}
END_PROGRAM
""")

    assert scan(10) == scan(2)

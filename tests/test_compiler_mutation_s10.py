"""Compiler behaviours that mutants left open by sessions 8 and 9, and survivors of the mutation
sample of seed 25, pinned down (issue 16, session 10; docs/mutation.md, "st_runtime/compiler/",
"Session 10").

Each test loads ST through the public entry point and takes its expected values from
IEC 61131-3, the CODESYS rules the codesys dialect follows, OMRON's manuals as docs/nj501.md
cites them, or a hand calculation stated beside it.
"""

from __future__ import annotations

import pytest

from st_runtime.api import load_text
from st_runtime.compiler import SharedPrelude
from test_compiler_mutants import run


# ------------------------------------- a METHOD whose whole body reads its FB's array

METHOD_OVER_FB_ARRAY = """
FUNCTION_BLOCK Acc
VAR a : ARRAY[1..8] OF REAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]; END_VAR
METHOD Sum : REAL
VAR s : REAL; t : REAL; END_VAR
s := a[1] + a[2] + a[3] + a[4];
t := a[5] + a[6] + a[7] + a[8];
s := s + t + a[1] * a[2];
Sum := s;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Acc; r : REAL; END_VAR
r := f.Sum();
END_PROGRAM"""


@pytest.mark.parametrize("dialect", ["iec", "codesys"])
def test_a_method_reading_its_blocks_array_at_literal_indices(dialect: str):
    # A METHOD reads its FB's variables through the instance (IEC 61131-3 6.6.5); a body of
    # eight element reads at literal indices that stores only the METHOD's own locals is
    # compiled as one region whose reads are looked up by name afterwards.
    # 1 + 2 + ... + 8 = 36, and 1 * 2 = 2: Sum = 38.
    main, plc = run(METHOD_OVER_FB_ARRAY, dialect=dialect)
    assert (main["r"], plc.faults) == (38.0, [])


# ------------------------------------------------ where an integer division by zero faults

def test_an_integer_division_by_zero_faults_at_its_operator():
    # IEC 61131-3: an integer division by zero is an error; the fault record names the
    # division itself, whose position is its operator's: line 3, column 8 of `x := a / b;`
    # (x at column 1), not the statement's start.
    main, plc = run("""PROGRAM Main
VAR a : INT := 7; b : INT; x : INT; END_VAR
x := a / b;
END_PROGRAM""")
    assert [(f.code, f.line, f.col) for f in plc.faults] == [("F-DIV-ZERO", 3, 8)]
    assert main["x"] == 0


# ------------------ a LINT stored into an LREAL: through `=>`, a read, an expression

@pytest.mark.parametrize("call", ["f(q => lr);", "n := g(q => lr);", "lr := li;", "lr := li + 0;"])
def test_a_lint_is_rounded_where_an_lreal_takes_it(call: str):
    # LINT widens implicitly to LREAL (IEC 61131-3, 6.4.2, implicit conversions), rounded
    # to the nearest double, ties to even: 2**53 + 1 lies halfway between 2**53 and
    # 2**53 + 2 and becomes 2**53 = 9007199254740992.0 (IEEE 754), as LINT_TO_LREAL gives;
    # compared in ST with that value, it is equal and not above it.
    main, plc = run("""FUNCTION_BLOCK Fb
VAR_OUTPUT q : LINT; END_VAR
q := 9007199254740993;
END_FUNCTION_BLOCK
FUNCTION g : INT
VAR_OUTPUT q : LINT; END_VAR
q := 9007199254740993;
g := 1;
END_FUNCTION
PROGRAM Main
VAR f : Fb; lr : LREAL; n : INT; same : BOOL; above : BOOL; li : LINT := 9007199254740993; END_VAR
""" + call + """
same := lr = 9007199254740992.0;
above := lr > 9007199254740992.0;
END_PROGRAM""")
    assert (main["lr"], main["same"], main["above"], plc.faults) == (9007199254740992.0, True, False, [])


# ------------------------------------------- the prelude's STRUCTs' __init__ sources

def test_the_prelude_structs_init_sources_are_their_python_sources():
    # CompiledProgram.python_sources maps each key to the Python source compiled for it;
    # a STRUCT of the shared prelude (AXIS_REF) keeps its `__init__` source there as the
    # program's own STRUCTs do: a `def` that compiles.  A SharedPrelude made here is read
    # the same way (the process-wide one was made before this test ran).
    project = load_text("""
TYPE Pt : STRUCT x : INT; END_STRUCT; END_TYPE
PROGRAM Main
VAR p : Pt; a : AXIS_REF; END_VAR
END_PROGRAM""", "m.st", "nj")
    fresh = SharedPrelude(project.program.prelude)
    sources = project.compiled.python_sources
    for key, source in [("init:PT", sources["init:PT"]), ("init:AXIS_REF", sources["init:AXIS_REF"]),
                        ("init:AXIS_REF", fresh.init_sources["init:AXIS_REF"])]:
        assert isinstance(source, str) and source.startswith("def ")
        compile(source, key, "exec")


def test_every_kept_python_source_compiles_even_of_a_type_without_variables():
    # python_sources keeps what each POU and type was compiled to, and for a PROGRAM (made
    # once per run) or a type whose `__init__` sets nothing, the `__init__` source that the
    # stores stand for: an `__init__` of nothing is still a Python function (its body
    # `pass`), as every other kept source.
    project = load_text("""
FUNCTION_BLOCK Empty
END_FUNCTION_BLOCK
PROGRAM Main
VAR e : Empty; END_VAR
e();
END_PROGRAM
PROGRAM Idle
END_PROGRAM""", "m.st", "iec")
    sources = project.compiled.python_sources
    assert {"init:EMPTY", "init:IDLE"} <= set(sources)
    for key, source in sources.items():
        compile(source, key, "exec")


# ------------------------------------ an operator in call form costs what the operator costs

@pytest.mark.parametrize("body, units", [
    # ADD(a, b) is the function form of a + b (IEC 61131-3, the standard arithmetic functions:
    # ADD is written + as an operator), compiled to the same expression: load, load, an
    # integer operation, and the store of x, as `x := a + b;` is charged.
    ("x := ADD(a, b);", lambda w: 2 * w["load"] + w["int_op"] + w["store"]),
    ("x := a + b;", lambda w: 2 * w["load"] + w["int_op"] + w["store"]),
    # GT(a, b) is a > b: two loads, a comparison, the store of g
    ("g := GT(a, b);", lambda w: 2 * w["load"] + w["compare"] + w["store"]),
])
def test_an_operator_in_call_form_is_charged_as_the_operator(body: str, units):
    from st_runtime.compiler.cost import WEIGHTS
    from test_compiler_mutants import _ps, _scan_ps

    src = f"PROGRAM Main\nVAR a : INT := 2; b : INT := 3; x : INT; g : BOOL; END_VAR\n{body}\nEND_PROGRAM\n"
    assert _scan_ps(src) == _ps(units(WEIGHTS))


# ---------------------------------------------------- a TIME sum past its 64 bits wraps

def test_a_time_sum_past_64_bits_wraps_to_a_negative_duration():
    # TIME is signed 64-bit nanoseconds and wraps to its width when stored (README,
    # "Semantics"): T#106751D is 106751 * 86400 * 10**9 = 9223286400000000000 ns, twice that
    # is 18446572800000000000, past 2**63 - 1, and wraps to 18446572800000000000 - 2**64
    # = -171273709551616 ns: a negative duration.
    main, plc = run("""PROGRAM Main
VAR t1 : TIME := T#106751D; t : TIME; neg : BOOL; END_VAR
t := t1 + t1;
neg := t < T#0S;
END_PROGRAM""")
    assert (main["neg"], plc.faults) == (True, [])

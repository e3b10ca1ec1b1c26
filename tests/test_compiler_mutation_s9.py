"""Compiler behaviours that survivors of the mutation sample of seed 24 pinned down (issue 16,
session 9; docs/mutation.md, "st_runtime/compiler/", "Session 9").

Each test loads ST through the public entry point (or calls a pass on its own lines) and
takes its expected values from IEC 61131-3, the CODESYS rules the codesys dialect follows,
the passes' own documented contracts, or a hand calculation stated beside it.
"""

from __future__ import annotations

import pytest

from st_runtime.api import LoadError, load_text
from st_runtime.compiler import CompileUnit, Optimisations, SharedPrelude, compile_program
from st_runtime.compiler.cost import WEIGHTS
from st_runtime.compiler.optimise import chains, fastpath
from st_runtime.compiler.statements import BodyCompiler
from test_compiler_mutants import run


# ------------------------------------------------------------ a CASE with an ELSE only

def test_a_case_without_labels_runs_its_else():
    # IEC 61131-3 7.3.3.3.3: the ELSE's statements run when the selector matches no label;
    # with no label at all they always run: y = 5, z = 7 (the statement after the CASE).
    main, plc = run("""
PROGRAM Main
VAR x : INT := 3; y : INT; z : INT; END_VAR
CASE x OF
ELSE
    y := 5;
END_CASE;
z := 7;
END_PROGRAM""")
    assert (main["y"], main["z"], plc.faults) == (5, 7, [])


# ------------------------------------------- a bit of a variable passed to a VAR_IN_OUT

BIT_TO_IN_OUT = """
FUNCTION_BLOCK Setter
VAR_IN_OUT b : BOOL; END_VAR
b := TRUE;
END_FUNCTION_BLOCK
PROGRAM Main
VAR w : WORD; f : Setter; END_VAR
f(b := w.3);
END_PROGRAM"""


@pytest.mark.parametrize("dialect", ["nj", "codesys"])
def test_a_bit_access_is_refused_as_an_in_out_argument(dialect: str):
    # CODESYS: "A bit access must not be assigned to a VAR_IN_OUT variable" (a VAR_IN_OUT is
    # passed by reference; a bit has no address of its own): the checker refuses it on the
    # call's line (8) as it refuses an expression there (E-CALL-007), not an internal error.
    with pytest.raises(LoadError) as raised:
        load_text(BIT_TO_IN_OUT, "m.st", dialect)
    assert [(d.code, d.pos.line) for d in raised.value.diagnostics] == [("E-CALL-007", 8)]


HOLDER = """FUNCTION_BLOCK Setter
VAR_IN_OUT b : INT; END_VAR
b := 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Holder
VAR v : INT; END_VAR
PROPERTY P : INT
GET P := v; END_GET
SET v := P; END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR h : Holder; s : Setter; w : WORD; r : REF_TO INT; q : REF_TO BOOL; p : POINTER TO BOOL; END_VAR
"""


@pytest.mark.parametrize("statement, code", [
    ("s(b := h.P);", "E-CALL-007"),             # a PROPERTY to a VAR_IN_OUT
    ("r := REF(h.P);", "E-TYPE-014"),           # REF of a PROPERTY
    ("q := REF(w.3);", "E-TYPE-014"),           # REF and ADR of a bit
    ("p := ADR(w.3);", "E-TYPE-014"),
])
def test_what_has_no_address_is_refused_where_a_reference_is_taken(statement: str, code: str):
    # A PROPERTY's accessors run code and a bit has no address of its own: neither can be
    # passed by reference (the codesys dialect, where PROPERTY, REF and ADR all exist); the
    # statement (line 14) is refused, where the load ended in an internal compiler error.
    with pytest.raises(LoadError) as raised:
        load_text(HOLDER + statement + "\nEND_PROGRAM\n", "m.st", "codesys")
    assert [(d.code, d.pos.line) for d in raised.value.diagnostics] == [(code, 14)]


# ------------------------------------------------------ the prelude's STRUCTs' __init__

def test_the_prelude_structs_init_sources_are_kept_under_their_init_keys():
    # CompiledProgram.python_sources keeps each STRUCT's __init__ source under "init:" + its
    # upper-case name, whether the STRUCT is the program's own or the shared prelude's
    # (AXIS_REF, the prelude's axis variable, is a STRUCT): the same key for both.  The
    # prelude is compiled once per process; a SharedPrelude made here gives the same keys.
    project = load_text("""
TYPE Pt : STRUCT x : INT; END_STRUCT; END_TYPE
PROGRAM Main
VAR p : Pt; a : AXIS_REF; END_VAR
END_PROGRAM""", "m.st", "nj")
    keys = [k for k in project.compiled.python_sources if k[:5].lower() == "init:"]
    assert "init:PT" in keys and "init:AXIS_REF" in keys
    assert all(k.startswith("init:") for k in keys)
    fresh = SharedPrelude(project.program.prelude)
    assert "init:AXIS_REF" in fresh.init_sources and all(k.startswith("init:") for k in fresh.init_sources)


# ------------------------------------- `chains`: a second store that does not read the element

@pytest.mark.parametrize("lines", [
    ["v_S[3] = v_R[1]", "v_S[3] = (v_YYYY + 1.0)"],     # reads another variable only
    ["v_S[3] = v_R[1]", "v_S[3] = 2.0"],                # a constant
])
def test_a_store_that_does_not_read_the_element_is_not_merged(lines):
    # chains.py: merged only when the second store reads the element as the left operand
    # of its outermost `+ - *`; these replace it, so both lines stay as they are.
    out = list(lines)
    chains.merge(out, 0)
    assert out == lines


# ---------------------------------------- fastpath: a body that calls a function block

def test_a_body_calling_a_plain_function_block_has_a_worst_case():
    # fastpath.py: a body qualifies when every FB written in ST that it calls qualifies (not
    # one that extends or is extended).  Acc's body, Total := Total + Step, charges
    # 2 loads + an integer operation + a store (the weights table); Main's call of it is
    # bounded too, and more than that (the call itself is charged).
    program = load_text("""
FUNCTION_BLOCK Acc
VAR_INPUT Step : INT; END_VAR
VAR_OUTPUT Total : INT; END_VAR
Total := Total + Step;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Base
VAR n : INT; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Derived EXTENDS Base
END_FUNCTION_BLOCK
PROGRAM Main
VAR a : Acc; d : Derived; END_VAR
a(Step := 2);
d();
END_PROGRAM""").program
    unit = CompileUnit(program)
    unit.optimise = Optimisations()
    w = WEIGHTS
    body = 2 * w["load"] + w["int_op"] + w["store"]
    acc = BodyCompiler(program, program.pous["ACC"], unit, method=True)
    assert fastpath.worst_case(acc, acc.body) == body
    main = BodyCompiler(program, program.pous["MAIN"], unit, method=True)
    assert fastpath.worst_case(main, main.body[:1]) > body
    assert fastpath.worst_case(main, main.body[1:]) is None     # Derived: another body may run


# ------------------------------------------------------------------ MOD, compiled and run

def test_mod_takes_the_sign_of_the_dividend():
    # IEC 61131-3 Table 30 (MOD): a = b * (a / b) + a MOD b, with / truncating toward zero:
    # 17 MOD 5 = 2, -17 MOD 5 = -2, 17 MOD -5 = 2.
    main, plc = run("""
PROGRAM Main
VAR a : INT := 17; n : INT := -17; b : INT := 5; m : INT := -5; x : INT; y : INT; z : INT; END_VAR
x := a MOD b;
y := n MOD b;
z := a MOD m;
END_PROGRAM""")
    assert (main["x"], main["y"], main["z"], plc.faults) == (2, -2, 2, [])


# ------------------------------------------- an array input that the FUNCTION modifies

def test_a_function_modifies_its_own_copy_of_an_array_input():
    # A VAR_INPUT is passed by value (IEC 61131-3 6.5.1); the codesys dialect lets a POU
    # write its inputs, and the FUNCTION's stores then change its own copy, not the
    # caller's array.  Sum of [1, 2, 3] after V[1] := 10: 10 + 2 + 3 = 15; a stays [1, 2, 3].
    main, plc = run("""
FUNCTION Bump : INT
VAR_INPUT V : ARRAY[1..3] OF INT; END_VAR
V[1] := 10;
Bump := V[1] + V[2] + V[3];
END_FUNCTION
PROGRAM Main
VAR a : ARRAY[1..3] OF INT := [1, 2, 3]; s : INT; END_VAR
s := Bump(V := a);
END_PROGRAM""", dialect="codesys")
    assert (main["s"], main["a"], plc.faults) == (15, [1, 2, 3], [])


# ------------------------- nj: a narrower sum inside a wider one overflows in its own type

@pytest.mark.parametrize("dialect, expected", [("nj", -32768), ("iec", 32768)])
def test_a_narrower_sum_inside_a_wider_one(dialect: str, expected: int):
    # W501 6-5-3 (docs/nj501.md; test_nj_expression_overflow): under nj an addition is
    # evaluated in the type of its highest-ranked operand and overflows there: i1 + i2 is
    # INT + INT, 32767 + 1 overflows to -32768 before the DINT addition takes it (0 + it).
    # Under iec the intermediate stays exact: 32768.
    main, plc = run("""
PROGRAM Main
VAR d0 : DINT := 0; i1 : INT := 32767; i2 : INT := 1; d : DINT; END_VAR
d := d0 + (i1 + i2);
END_PROGRAM""", dialect=dialect)
    assert (main["d"], plc.faults) == (expected, [])


# -------------------------- `ranges`: a bit store changes the variable it is a bit of

def test_a_bit_store_forgets_the_known_range_of_its_variable():
    # x := 1 puts x in 1..4, but x.0 := FALSE clears bit 0: x = 0, outside a's bounds 1..4,
    # so a[x] faults (F-INDEX, line 6) and Pick keeps its initial 0 (IEC 61131-3: an index
    # out of the bounds is an error; the runtime's fault).  The codesys dialect (bit access).
    main, plc = run("""
FUNCTION Pick : INT
VAR x : INT; a : ARRAY[1..4] OF INT := [10, 20, 30, 40]; END_VAR
x := 1;
x.0 := FALSE;
Pick := a[x];
END_FUNCTION
PROGRAM Main
VAR r : INT; END_VAR
r := Pick();
END_PROGRAM""", dialect="codesys")
    assert (main["r"], [(f.code, f.line) for f in plc.faults]) == (0, [("F-INDEX", 6)])


# ------------------------------------- a POU without statements, compiled without charges

def test_a_program_without_statements_compiles_without_charges():
    # compile_program(charge_costs=False) leaves out the time charges; a PROGRAM whose body has
    # no statement (the ST grammar allows it) still becomes a Python function (a `pass`), and
    # an instance of it keeps its initial values.
    program = load_text("PROGRAM Main\nVAR x : INT := 4; END_VAR\nEND_PROGRAM\n").program
    compiled = compile_program(program, charge_costs=False)
    assert compiled.new("Main").v_X == 4


# ------------------------------------------------- a call statement with ENO and no EN

def test_a_call_with_eno_only_runs_and_sets_eno():
    # IEC 61131-3 6.6.1.5 (EN/ENO): without EN the call runs (EN is TRUE), and ENO is TRUE
    # after a call that ran without error: Total = 0 + 2, ok = TRUE.
    main, plc = run("""
FUNCTION_BLOCK Acc
VAR_INPUT Step : INT; END_VAR
VAR_OUTPUT Total : INT; END_VAR
Total := Total + Step;
END_FUNCTION_BLOCK
PROGRAM Main
VAR a : Acc; ok : BOOL; END_VAR
a(Step := 2, ENO => ok);
END_PROGRAM""")
    assert (main["a.Total"], main["ok"], plc.faults) == (2, True, [])

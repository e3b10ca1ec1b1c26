"""A global FOR control variable altered by a POU called inside its loop (checker/loop_writes.py).

IEC 61131-3 3rd ed. 7.3.3.4.2 (FOR): the control variable "shall not be altered by any of the
repeated statements". A call in the loop of a FUNCTION or FB whose body writes the global that
controls the loop (itself, or through what it calls) alters it: W-ASSIGN-001 at the call, a
warning (the program still loads and runs: the loop goes on from the value the callee leaves,
which tests/test_compiler_tables_core.py pins; a write in the loop's own text is E-ASSIGN-003). The
near misses (a read, another global, a local of the same name, a loop over a local, a call after
the loop) stay accepted. A METHOD of any instance that writes the global (through its FB's
VAR_EXTERNAL) alters it the same way. Inside an FB, a FOR over one of its variables: a METHOD
called on this instance (`M()`, `THIS.M()`, `SUPER.M()`) that writes it, or calls one that does,
is warned of the same way; another instance's method writes that instance's variable (accepted).
A call that may run an override (`M()`, `THIS.M()`, through a VAR_IN_OUT or an INTERFACE) follows
every override in the program and names the one that writes; SUPER and an instance held by value
run the declared method. A reference whose every store is `r := REF(i)` (ADR under codesys) refers
to i: a write through it in a FOR over i, or a call in the loop handing it to an input its callee
writes through, is warned of; a reference to another variable, or with any other store, is not.
Expected places are counted by hand in each text.
"""

from __future__ import annotations

import pytest

from checker_helpers import diagnostics
from stgen.cli import main

DIALECTS = ("iec", "codesys", "nj")

GLOBALS = "VAR_GLOBAL\n  g : INT;\n  h : INT;\nEND_VAR\n"            # lines 1-4


def function(name: str, body: str, externals: str = "g : INT;", local: str = "") -> str:
    """FUNCTION `name` : INT, five lines plus the body's."""
    return (f"FUNCTION {name} : INT\nVAR_EXTERNAL {externals} END_VAR\nVAR {local} END_VAR\n"
            f"{body}\n{name} := 0;\nEND_FUNCTION\n")


def main_program(body: str, externals: str = "g : INT;") -> str:
    return (f"PROGRAM Main\nVAR_EXTERNAL {externals} END_VAR\nVAR s : INT; t : T; END_VAR\n"
            f"{body}\nEND_PROGRAM\n")


FB_T = "FUNCTION_BLOCK T\nVAR_EXTERNAL g : INT; END_VAR\ng := 0;\nEND_FUNCTION_BLOCK\n"   # 4 lines

# Bump (lines 5-10) writes g; Peek (11-16) reads it; Other (17-22) writes h; Outer (23-28) calls Bump;
# Own (29-34) writes a local g; Loop (35-40) runs its own FOR over g; T (41-44) writes g; Main from 45.
POUS = (GLOBALS
        + function("Bump", "g := g + 1;")
        + function("Peek", "h := g;", externals="g : INT; h : INT;")
        + function("Other", "h := 1;", externals="h : INT;")
        + function("Outer", "Outer := Bump();", externals="")
        + function("Own", "g := 5;", externals="h : INT;", local="g : INT;")
        + function("Loop", "FOR g := 1 TO 2 DO END_FOR;")
        + FB_T)
MAIN_LINE = 45
LOOP = "FOR g := 1 TO 3 DO\n  {}\nEND_FOR;"       # the call on Main's line 4, column 3


GOES_ON = "IEC 61131-3 forbids it; the loop goes on from the value left"


def alters(callee: str, chain: str) -> str:
    return (f"call of {callee} alters global 'g', the control variable of an enclosing FOR loop "
            f"({chain}): {GOES_ON}")


WARNED = [
    pytest.param("Bump();", 3, alters("Bump", "Bump writes it"), id="function_writes_it"),
    pytest.param("s := Bump();", 8, alters("Bump", "Bump writes it"), id="function_in_an_expression"),
    pytest.param("Outer();", 3, alters("Outer", "Outer calls Bump, which writes it"), id="through_a_call"),
    pytest.param("Loop();", 3, alters("Loop", "Loop writes it"), id="callee_runs_its_own_for_over_it"),
    pytest.param("t();", 3, alters("T", "T writes it"), id="fb_instance_writes_it"),
]


@pytest.mark.parametrize("dialect", DIALECTS)
@pytest.mark.parametrize("call, column, message", WARNED)
def test_a_call_that_writes_the_loops_global_is_warned_of_at_the_call(call, column, message, dialect):
    text = POUS + main_program(LOOP.format(call))
    assert diagnostics(text, dialect) == [("W-ASSIGN-001", MAIN_LINE + 4, column, message)]


ACCEPTED = [
    pytest.param(LOOP.format("s := Peek();"), id="callee_only_reads_it"),
    pytest.param(LOOP.format("Other();"), id="callee_writes_another_global"),
    pytest.param(LOOP.format("Own();"), id="callee_writes_its_own_local_of_that_name"),
    pytest.param("FOR s := 1 TO 3 DO\n  Bump();\nEND_FOR;", id="loop_over_a_local"),
    pytest.param("FOR g := 1 TO 3 DO\n  s := g;\nEND_FOR;\nBump();", id="call_after_the_loop"),
]


@pytest.mark.parametrize("dialect", DIALECTS)
@pytest.mark.parametrize("body", ACCEPTED)
def test_near_misses_stay_accepted(body, dialect):
    assert diagnostics(POUS + main_program(body), dialect) == []


def test_the_nj_dialect_warns_with_the_global_named_directly():
    """Under nj a global is seen without VAR_EXTERNAL (Sysmac Studio's global variable table)."""
    text = (GLOBALS + "FUNCTION Bump : INT\ng := g + 1;\nBump := 0;\nEND_FUNCTION\n"
            "PROGRAM Main\nVAR s : INT; END_VAR\nFOR g := 1 TO 3 DO\n  Bump();\nEND_FOR;\nEND_PROGRAM\n")
    assert diagnostics(text, "nj") == [("W-ASSIGN-001", 12, 3, alters("Bump", "Bump writes it"))]


def test_stgen_check_names_file_line_and_column(tmp_path, capsys):
    path = tmp_path / "loop.st"
    path.write_text(POUS + main_program(LOOP.format("Outer();")), encoding="utf-8")
    assert main(["check", str(path)]) == 0          # a warning: the file still checks
    out = capsys.readouterr().err
    assert f"{path}:{MAIN_LINE + 4}:3: warning[W-ASSIGN-001]: " + alters("Outer", "Outer calls Bump, which writes it") in out


# ====================================================================== METHODs on this instance
# Inside an FB, a FOR over one of its variables: a METHOD called on this instance that writes it
# alters it too. Counter's methods on lines 3-15, its FOR from line 16 (the call on line 17).

COUNTER = ("FUNCTION_BLOCK Base\nVAR i : INT; s : INT; END_VAR\n"            # 1-2
           "METHOD Reset\ni := 0;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"          # 3-6
           "FUNCTION_BLOCK Counter EXTENDS Base\n"                           # 7
           "METHOD Bump\ni := i + 1;\nEND_METHOD\n"                          # 8-10
           "METHOD Outer\nBump();\nEND_METHOD\n"                             # 11-13
           "METHOD Peek : INT\nVAR i : INT; END_VAR\ni := 7;\nPeek := s;\nEND_METHOD\n"   # 14-18
           "FOR {var} := 1 TO 3 DO\n  {call}\nEND_FOR;\n"                    # 19-21
           "END_FUNCTION_BLOCK\n")
CALL_LINE = 20


def method_alters(callee: str, chain: str) -> str:
    return (f"call of method {callee} alters 'i', the control variable of an enclosing FOR loop "
            f"({chain}): {GOES_ON}")


METHOD_WARNED = [
    pytest.param("Bump();", 3, method_alters("Bump", "Bump writes it"), id="unqualified"),
    pytest.param("THIS.Bump();", 3, method_alters("Bump", "Bump writes it"), id="through_this"),
    pytest.param("THIS.Outer();", 3, method_alters("Outer", "Outer calls Bump, which writes it"),
                 id="through_another_method"),
    pytest.param("SUPER.Reset();", 3, method_alters("Reset", "Reset writes it"), id="the_base_fbs_method"),
]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("call, column, message", METHOD_WARNED)
def test_a_method_that_writes_the_fbs_loop_variable_is_warned_of_at_the_call(call, column, message, dialect):
    text = COUNTER.format(var="i", call=call)
    assert diagnostics(text, dialect) == [("W-ASSIGN-001", CALL_LINE, column, message)]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("var, call", [
    pytest.param("i", "s := Peek();", id="method_writes_its_own_local_of_that_name"),
    pytest.param("s", "Bump();", id="loop_over_another_variable"),
    pytest.param("i", "s := s + 1;", id="no_call"),
])
def test_method_near_misses_stay_accepted(var, call, dialect):
    assert diagnostics(COUNTER.format(var=var, call=call), dialect) == []


def test_a_method_called_on_another_instance_is_not_followed():
    """Another instance's variable of the same name is not this loop's: accepted (and the
    documented limit: what `other` refers to is not analysed)."""
    text = COUNTER.format(var="i", call="other.Bump();").replace(
        "FUNCTION_BLOCK Counter EXTENDS Base\n", "FUNCTION_BLOCK Counter EXTENDS Base\nVAR other : Counter2; END_VAR\n")
    text += "FUNCTION_BLOCK Counter2\nVAR i : INT; END_VAR\nMETHOD Bump\ni := i + 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
    assert diagnostics(text, "iec") == []


def test_a_method_called_through_an_in_out_of_this_fbs_type_is_not_followed():
    """`peer.Bump()` with `peer` a VAR_IN_OUT of this FB's own type writes peer's `i`, not the
    loop's (unless peer is bound to this instance, which the checker does not analyse)."""
    text = COUNTER.format(var="i", call="peer.Bump();").replace(
        "FUNCTION_BLOCK Counter EXTENDS Base\n", "FUNCTION_BLOCK Counter EXTENDS Base\nVAR_IN_OUT peer : Counter; END_VAR\n")
    assert diagnostics(text, "iec") == []


def test_a_method_of_this_instance_calling_another_instances_method_is_not_followed():
    """Outer calls `peer.Bump()`, which writes peer's `i`: the chain leaves this instance."""
    text = COUNTER.format(var="i", call="Outer();").replace(
        "FUNCTION_BLOCK Counter EXTENDS Base\n", "FUNCTION_BLOCK Counter EXTENDS Base\nVAR_IN_OUT peer : Counter; END_VAR\n"
    ).replace("METHOD Outer\nBump();", "METHOD Outer\npeer.Bump();")
    assert diagnostics(text, "iec") == []


def test_a_method_called_on_an_array_element_is_not_followed():
    text = COUNTER.format(var="i", call="others[1].Bump();").replace(
        "FUNCTION_BLOCK Counter EXTENDS Base\n",
        "FUNCTION_BLOCK Counter EXTENDS Base\nVAR others : ARRAY[1..2] OF Counter2; END_VAR\n")
    text += "FUNCTION_BLOCK Counter2\nVAR i : INT; END_VAR\nMETHOD Bump\ni := i + 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
    assert diagnostics(text, "codesys") == []


def test_a_chain_of_three_calls_is_named_in_order():
    # Bump (lines 5-10), Outer (11-16), Outer2 (17-22), T (23-26), Main from 27: the call on 31.
    text = (GLOBALS + function("Bump", "g := g + 1;") + function("Outer", "Outer := Bump();", externals="")
            + function("Outer2", "Outer2 := Outer();", externals="") + FB_T
            + main_program(LOOP.format("Outer2();")))
    chain = "Outer2 calls Outer, which calls Bump, which writes it"
    assert diagnostics(text, "iec") == [("W-ASSIGN-001", 31, 3, alters("Outer2", chain))]


def test_each_call_in_the_loop_is_warned_of():
    """Two calls that write the loop's global: a warning at each, in order."""
    text = POUS + main_program(LOOP.format("Bump();\n  Outer();"))
    assert diagnostics(text, "iec") == [
        ("W-ASSIGN-001", MAIN_LINE + 4, 3, alters("Bump", "Bump writes it")),
        ("W-ASSIGN-001", MAIN_LINE + 5, 3, alters("Outer", "Outer calls Bump, which writes it"))]


def test_nested_loops_over_two_globals_one_warning_per_call():
    """FOR g, FOR h inside it (Main from line 21, the calls on 26 and 27): Other writes h, the inner loop's
    global (a warning though g, the first looked at, is not written); Both writes both (one
    warning, for g)."""
    text = (GLOBALS + function("Other", "h := 1;", externals="h : INT;")
            + function("Both", "g := 1; h := 1;", externals="g : INT; h : INT;") + FB_T    # 5-20
            + main_program("FOR g := 1 TO 3 DO\n  FOR h := 1 TO 2 DO\n    Other();\n    Both();\n"
                           "  END_FOR;\nEND_FOR;", externals="g : INT; h : INT;"))
    other = ("call of Other alters global 'h', the control variable of an enclosing FOR loop "
             f"(Other writes it): {GOES_ON}")
    assert diagnostics(text, "iec") == [("W-ASSIGN-001", 26, 5, other),
                                        ("W-ASSIGN-001", 27, 5, alters("Both", "Both writes it"))]


def test_each_method_call_in_the_loop_is_warned_of():
    text = COUNTER.format(var="i", call="Bump();\n  SUPER.Reset();")
    assert diagnostics(text, "iec") == [
        ("W-ASSIGN-001", CALL_LINE, 3, method_alters("Bump", "Bump writes it")),
        ("W-ASSIGN-001", CALL_LINE + 1, 3, method_alters("Reset", "Reset writes it"))]


# ====================================================================== METHODs of other instances
# A global names one storage from every POU: a METHOD of any instance that writes it (through its
# FB's VAR_EXTERNAL), itself or through what it calls, alters a FOR over it. X's methods on lines
# 8-25 (Inc writes g, Via calls Bump, Own writes X's i, Other writes h, Loop runs a FOR over g
# calling {inner} on line 23); Main from line 27, its FOR calling {call} on line 31.

INSTANCES = (GLOBALS                                                            # 1-4
             + "FUNCTION_BLOCK X\nVAR_EXTERNAL g : INT; h : INT; END_VAR\nVAR i : INT; END_VAR\n"  # 5-7
             "METHOD Inc\ng := g + 1;\nEND_METHOD\n"                            # 8-10
             "METHOD Via\nBump();\nEND_METHOD\n"                                # 11-13
             "METHOD Own\ni := i + 1;\nEND_METHOD\n"                            # 14-16
             "METHOD Other\nh := 1;\nEND_METHOD\n"                              # 17-19
             "METHOD Loop\nVAR s : INT; END_VAR\nFOR g := 1 TO 2 DO\n  {inner}\nEND_FOR;\nEND_METHOD\n"   # 20-25
             "END_FUNCTION_BLOCK\n"                                             # 26
             "PROGRAM Main\nVAR_EXTERNAL g : INT; END_VAR\n"                    # 27-28
             "VAR x : X; xs : ARRAY[1..2] OF X; s : INT; END_VAR\n"             # 29
             "FOR g := 1 TO 3 DO\n  {call}\nEND_FOR;\nEND_PROGRAM\n"            # 30-33
             + function("Bump", "g := g + 1;"))
INNER_LINE, OUTER_LINE = 23, 31


def method_alters_global(callee: str, chain: str) -> str:
    return alters(f"method {callee}", chain)


INSTANCE_WARNED = [
    pytest.param("x.Inc();", "s := 0;", OUTER_LINE, method_alters_global("Inc", "Inc writes it"),
                 id="a_method_of_an_instance_writes_it"),
    pytest.param("xs[2].Via();", "s := 0;", OUTER_LINE,
                 method_alters_global("Via", "Via calls Bump, which writes it"),
                 id="an_array_elements_method_calls_a_function_that_writes_it"),
    pytest.param("x.Own();", "Inc();", INNER_LINE, method_alters_global("Inc", "Inc writes it"),
                 id="a_method_of_this_instance_writes_the_global"),
    pytest.param("x.Own();", "THIS.Via();", INNER_LINE,
                 method_alters_global("Via", "Via calls Bump, which writes it"),
                 id="this_instance_through_a_function"),
]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("call, inner, line, message", INSTANCE_WARNED)
def test_a_method_of_any_instance_that_writes_the_loops_global_is_warned_of(call, inner, line, message, dialect):
    text = INSTANCES.format(call=call, inner=inner)
    assert diagnostics(text, dialect) == [("W-ASSIGN-001", line, 3, message)]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("call", [
    pytest.param("x.Own();", id="the_method_writes_its_instances_own_variable"),
    pytest.param("xs[1].Other();", id="the_method_writes_another_global"),
    pytest.param("s := 1;", id="no_call"),
])
def test_instance_near_misses_stay_accepted(call, dialect):
    assert diagnostics(INSTANCES.format(call=call, inner="s := 0;"), dialect) == []


# Z's body calls y.Chain (lines 11-14), Chain calls Inc on its instance (8-10), Inc writes g:
# the chain goes through the calls made in METHODs' bodies.
THROUGH_METHODS = (GLOBALS                                                      # 1-4
                   + "FUNCTION_BLOCK Y\nVAR_EXTERNAL g : INT; END_VAR\n"        # 5-6
                   "METHOD Inc\ng := g + 1;\nEND_METHOD\nMETHOD Chain\nInc();\nEND_METHOD\n"   # 7-12
                   "END_FUNCTION_BLOCK\n"                                     # 13
                   "FUNCTION_BLOCK Z\nVAR y : Y; END_VAR\ny.Chain();\nEND_FUNCTION_BLOCK\n"   # 14-17
                   "PROGRAM Main\nVAR_EXTERNAL g : INT; END_VAR\nVAR z : Z; END_VAR\n"  # 18-20
                   "FOR g := 1 TO 3 DO\n  z();\nEND_FOR;\nEND_PROGRAM\n")         # 21-24


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
def test_a_chain_through_the_calls_of_methods_is_followed(dialect):
    assert diagnostics(THROUGH_METHODS, dialect) == [
        ("W-ASSIGN-001", 22, 3, alters("Z", "Z calls Chain, which calls Inc, which writes it"))]


def test_stgen_check_names_another_instances_method_and_its_chain(tmp_path, capsys):
    path = tmp_path / "instances.st"
    path.write_text(INSTANCES.format(call="xs[2].Via();", inner="s := 0;"), encoding="utf-8")
    assert main(["check", "--dialect", "codesys", str(path)]) == 0
    out = capsys.readouterr().err
    assert f"{path}:{OUTER_LINE}:3: warning[W-ASSIGN-001]: " + method_alters_global(
        "Via", "Via calls Bump, which writes it") in out


# ====================================================================== overrides
# `M()`, `THIS.M()`, a call through a VAR_IN_OUT and one through an INTERFACE run the method of
# the instance's dynamic type, which may be an FB extending the declared one: every override in
# the program counts, and the warning names it. A SUPER call and an instance held by value run
# the declared method. Base.Run's FOR over i calls {call} on line 9; D (13-26) overrides Step
# with {override} on line 16 and runs a FOR over i calling {again} on line 23; Impl.Go (34-36) is
# {go} on line 35; User's FOR over g (line 42) calls {use} on line 43.

OVERRIDES = (
    "VAR_GLOBAL g : INT; END_VAR\n"                                                 # 1
    "FUNCTION_BLOCK Base\nVAR i : INT; s : INT; END_VAR\n"                          # 2-3
    "METHOD Step\ns := s + 1;\nEND_METHOD\n"                                        # 4-6
    "METHOD Run\nFOR i := 1 TO 3 DO\n  {call}\nEND_FOR;\nEND_METHOD\n"              # 7-11
    "END_FUNCTION_BLOCK\n"                                                          # 12
    "FUNCTION_BLOCK D EXTENDS Base\nVAR_EXTERNAL g : INT; END_VAR\n"                # 13-14
    "METHOD Step\n{override}\nEND_METHOD\n"                                         # 15-17
    "METHOD Helper\ni := 0;\nEND_METHOD\n"                                          # 18-20
    "METHOD Again\nFOR i := 1 TO 3 DO\n  {again}\nEND_FOR;\nEND_METHOD\n"           # 21-25
    "END_FUNCTION_BLOCK\n"                                                          # 26
    "INTERFACE I\nMETHOD Go\nEND_METHOD\nEND_INTERFACE\n"                           # 27-30
    "FUNCTION_BLOCK Impl IMPLEMENTS I\nVAR_EXTERNAL g : INT; END_VAR\nVAR t : INT; END_VAR\n"  # 31-33
    "METHOD Go\n{go}\nEND_METHOD\n"                                                 # 34-36
    "END_FUNCTION_BLOCK\n"                                                          # 37
    "FUNCTION_BLOCK User\nVAR_EXTERNAL g : INT; END_VAR\nVAR_IN_OUT io : Base; END_VAR\n"  # 38-40
    "VAR b : Base; it : I; rb : REF_TO Base; END_VAR\n"                             # 41
    "FOR g := 1 TO 3 DO\n  {use}\nEND_FOR;\nEND_FUNCTION_BLOCK\n"                   # 42-45
    # an FB with methods of those names that neither extends Base nor implements I, and an
    # ABSTRACT FB implementing I without a Go of its own
    "FUNCTION_BLOCK Stranger\nVAR_EXTERNAL g : INT; END_VAR\n"
    "METHOD Step\ng := 3;\nEND_METHOD\nMETHOD Go\ng := 4;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
    "FUNCTION_BLOCK ABSTRACT Half IMPLEMENTS I\nEND_FUNCTION_BLOCK\n")
RUN_LINE, USE_LINE = 9, 43
QUIET = {"call": "s := 0;", "override": "s := 2;", "again": "s := 0;", "go": "t := 1;", "use": "b.Step();"}


def overrides(**parts: str) -> str:
    return OVERRIDES.format(**{**QUIET, **parts})


def override_alters(method: str, what: str, fb: str, chain: str) -> str:
    return (f"call of method {method} alters {what}, the control variable of an enclosing FOR loop "
            f"(for an instance of {fb}, {fb}.{chain}): {GOES_ON}")


OVERRIDE_WARNED = [
    pytest.param({"call": "Step();", "override": "i := 0;"}, RUN_LINE,
                 override_alters("Step", "'i'", "D", "Step writes it"), id="unqualified_call_its_override_writes"),
    pytest.param({"call": "THIS.Step();", "override": "Helper();"}, RUN_LINE,
                 override_alters("Step", "'i'", "D", "Step calls Helper, which writes it"),
                 id="through_this_the_override_calls_a_writer"),
    pytest.param({"use": "io.Step();", "override": "g := 1;"}, USE_LINE,
                 override_alters("Step", "global 'g'", "D", "Step writes it"), id="through_a_var_in_out"),
    pytest.param({"use": "rb^.Step();", "override": "g := 1;"}, USE_LINE,
                 override_alters("Step", "global 'g'", "D", "Step writes it"), id="through_a_reference"),
    pytest.param({"use": "it.Go();", "go": "g := 2;"}, USE_LINE,
                 override_alters("Go", "global 'g'", "Impl", "Go writes it"), id="through_an_interface"),
]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("parts, line, message", OVERRIDE_WARNED)
def test_an_override_that_may_run_and_writes_is_warned_of(parts, line, message, dialect):
    assert diagnostics(overrides(**parts), dialect) == [("W-ASSIGN-001", line, 3, message)]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("parts", [
    pytest.param({"call": "Step();"}, id="the_override_does_not_write"),
    pytest.param({"use": "b.Step();", "override": "g := 1;"}, id="an_instance_held_by_value_runs_the_declared_method"),
    pytest.param({"again": "SUPER.Step();", "override": "i := 0;"}, id="super_runs_the_base_method"),
    pytest.param({"use": "it.Go();"}, id="the_implementation_does_not_write"),
    pytest.param({"use": "io.Step();"}, id="an_unrelated_fbs_method_of_that_name_writes"),
])
def test_override_near_misses_stay_accepted(parts, dialect):
    assert diagnostics(overrides(**parts), dialect) == []


def test_each_declared_fb_has_its_own_overrides():
    # st.Step() may run Stranger's Step only, io.Step() Base's or D's: each call's candidates
    # come from its own declared FB, whichever was asked first.
    text = overrides(use="st.Step();\n  io.Step();", override="g := 1;").replace(
        "VAR_IN_OUT io : Base;", "VAR_IN_OUT io : Base; st : Stranger;")
    assert diagnostics(text, "codesys") == [
        ("W-ASSIGN-001", USE_LINE, 3, alters("method Step", "Step writes it")),
        ("W-ASSIGN-001", USE_LINE + 1, 3, override_alters("Step", "global 'g'", "D", "Step writes it"))]


def test_stgen_check_names_the_override(tmp_path, capsys):
    path = tmp_path / "overrides.st"
    path.write_text(overrides(call="THIS.Step();", override="Helper();"), encoding="utf-8")
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().err
    assert f"{path}:{RUN_LINE}:3: warning[W-ASSIGN-001]: " + override_alters(
        "Step", "'i'", "D", "Step calls Helper, which writes it") in out


# ====================================================================== references
# A reference every store of which is `r := REF(i)` (ADR under codesys) refers to i: a write
# through it in a FOR over i, or a call handing it to an input its callee writes through, alters
# i. Poke (1-5) writes through its input, Peek (6-9) reads through it; Main's r refers to i (line
# 12), q to {q} (line 13), line 14 is {before}, and the FOR over i (15-17) runs {body} on line 16.

REFERENCES = (
    "FUNCTION Poke : INT\nVAR_INPUT p : REF_TO INT; END_VAR\np^ := 0;\nPoke := 0;\nEND_FUNCTION\n"   # 1-5
    "FUNCTION Peek : INT\nVAR_INPUT p : REF_TO INT; END_VAR\nPeek := p^;\nEND_FUNCTION\n"          # 6-9
    "PROGRAM Main\nVAR i : INT; j : INT; r : REF_TO INT; q : REF_TO INT; s : INT; END_VAR "         # 10-11
    "VAR_TEMP t : REF_TO INT; END_VAR VAR_INPUT ri : REF_TO INT; END_VAR\n"
    "r := REF(i);\nq := REF({q});\n{before}\n"                                                      # 12-14
    "FOR i := 1 TO 3 DO\n  {body}\nEND_FOR;\nEND_PROGRAM\n"                                          # 15-18
    "FUNCTION Rebind : INT\nVAR_IN_OUT io : REF_TO INT; END_VAR\nRebind := 0;\nEND_FUNCTION\n")         # 19-22
BODY_LINE = 16


def references(dialect: str, body: str, q: str = "j", before: str = "s := 0;") -> str:
    text = REFERENCES.format(body=body, q=q, before=before)
    return text.replace("REF_TO", "POINTER TO").replace("REF(", "ADR(") if dialect == "codesys" else text


def through(dialect: str, what: str, ref: str, why: str = "") -> str:
    how = "ADR" if dialect == "codesys" else "REF"
    line = {"r": 12, "q": 13, "t": 14}[ref]
    return (f"{what} alters 'i', the control variable of an enclosing FOR loop ({why}'{ref}' refers "
            f"to it: {ref} := {how}(i) on line {line}): {GOES_ON}")


REFERENCE_WARNED = [
    pytest.param({"body": "r^ := 5;"}, 3, "write through 'r'", "r", "", id="written_through_in_the_loop"),
    pytest.param({"body": "s := Poke(r);"}, 8, "call of Poke", "r",
                 "Poke writes through its input 'p', given 'r'; ", id="handed_to_a_callee_that_writes_through_it"),
    pytest.param({"body": "Poke(p := q);", "q": "i"}, 3, "call of Poke", "q",
                 "Poke writes through its input 'p', given 'q'; ", id="handed_as_a_formal_argument"),
    pytest.param({"body": "t^ := 5;", "before": "t := REF(i);"}, 3, "write through 't'", "t", "",
                 id="a_var_temp_reference"),
]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("parts, column, what, ref, why", REFERENCE_WARNED)
def test_a_reference_to_the_control_variable_written_through_is_warned_of(parts, column, what, ref, why, dialect):
    assert diagnostics(references(dialect, **parts), dialect) == [
        ("W-ASSIGN-001", BODY_LINE, column, through(dialect, what, ref, why))]


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
@pytest.mark.parametrize("parts", [
    pytest.param({"body": "q^ := 5;"}, id="a_reference_to_another_variable"),
    pytest.param({"body": "s := Peek(r);"}, id="the_callee_only_reads_through_it"),
    pytest.param({"body": "s := Poke(q);"}, id="a_callee_given_a_reference_to_another_variable"),
    pytest.param({"body": "r^ := 5;", "before": "r := REF(j);"}, id="a_reference_made_to_two_variables"),
    pytest.param({"body": "r^ := 5;", "before": "r := q;"}, id="a_reference_stored_from_another"),
    pytest.param({"body": "r^ := 5;", "before": "r := NULL;"}, id="a_reference_also_set_to_null"),
    pytest.param({"body": "s := r^;"}, id="read_through"),
])
def test_reference_near_misses_stay_accepted(parts, dialect):
    assert diagnostics(references(dialect, **parts), dialect) == []


def test_stgen_check_names_the_reference_and_where_it_was_taken(tmp_path, capsys):
    path = tmp_path / "references.st"
    path.write_text(references("codesys", "s := Poke(r);"), encoding="utf-8")
    assert main(["check", "--dialect", "codesys", str(path)]) == 0
    out = capsys.readouterr().err
    assert f"{path}:{BODY_LINE}:8: warning[W-ASSIGN-001]: " + through(
        "codesys", "call of Poke", "r", "Poke writes through its input 'p', given 'r'; ") in out


def test_an_input_reference_has_no_known_target():
    """A caller may store into an input (codesys lets the POU write its inputs too)."""
    assert diagnostics(references("codesys", "ri^ := 5;", before="ri := ADR(i);"), "codesys") == []


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
def test_a_reference_bound_to_a_var_in_out_has_no_known_target(dialect):
    """The callee may store another reference into it. (Binding it is refused today, E-CALL-011:
    typesys.same_type knows no reference types; the bound reference still counts as stored.)"""
    found = diagnostics(references(dialect, "r^ := 5;", before="s := Rebind(r);"), dialect)
    assert [d for d in found if d[0] in ("W-ASSIGN-001", "E-CHECK-999")] == []


@pytest.mark.parametrize("dialect", ("iec", "codesys"))
def test_each_write_through_and_hand_off_in_the_loop_is_warned_of(dialect):
    """After a near miss (q refers to j), the two uses of r: a warning at each, in order."""
    text = references(dialect, "q^ := 5;\n  r^ := 5;\n  s := Poke(r);")
    assert diagnostics(text, dialect) == [
        ("W-ASSIGN-001", BODY_LINE + 1, 3, through(dialect, "write through 'r'", "r")),
        ("W-ASSIGN-001", BODY_LINE + 2, 8, through(dialect, "call of Poke", "r",
                                                   "Poke writes through its input 'p', given 'r'; "))]

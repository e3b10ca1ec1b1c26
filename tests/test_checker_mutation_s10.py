"""Checker rules that mutation testing found unchecked: seed 24's last survivors
and the survivors of the fresh seed-25 sample (issue 16, docs/mutation.md,
checker, session 10).

Each test states a rule of IEC 61131-3 (3rd ed. 2013) or of the checker's own
contract (one root cause, one diagnostic), with line and column counted by hand
in the snippet and values worked out by hand.
"""

from __future__ import annotations

from checker_helpers import diagnostics, program
from test_checker_mutants_third import after_one_scan


# ------------------------------------------------------------ seed 24's last survivors

def test_the_bounds_of_a_refused_for_variable_add_no_diagnostic():
    """A REAL control variable is the one error (E-TYPE-010); `SQRT(4)` as the end
    value is a REAL function of an untyped literal (4 is then LREAL) and must not
    be reported as well: typed against the refused variable's ERROR, the literal
    would become SINT and SQRT would be refused for it."""
    assert diagnostics(program("    r : REAL;", "FOR r := 1 TO SQRT(4) DO\nEND_FOR;")) == \
        [("E-TYPE-010", 5, 1, "FOR control variable 'r': expected an integer variable, found REAL")]


def test_not_of_a_typed_bit_string_constant_is_a_constant():
    """3rd ed. 6.5.1.5: an initial value is a constant expression, and so is a CASE
    label.  NOT WORD#16#00FF = 16#FF00 = 65280; NOT BYTE#16#FE = 1."""
    main = after_one_scan(program("    w : WORD := NOT WORD#16#00FF; b : BYTE := 1; hit : BOOL;",
                                  "CASE b OF\n  NOT BYTE#16#FE: hit := TRUE;\nEND_CASE;"))
    assert (main["w"], main["hit"]) == (65280, True)


def test_a_method_that_never_assigns_its_result_returns_the_default_value():
    """A METHOD's result is a variable like a FUNCTION's: not assigned, it keeps its
    type's default initial value (0 for INT, 3rd ed. table 10); `Next` assigns
    n * 10 after the two increments: 20."""
    text = ("FUNCTION_BLOCK Counter\nVAR n : INT; END_VAR\n"
            "METHOD Untouched : INT\nn := n + 1;\nEND_METHOD\n"
            "METHOD Next : INT\nn := n + 1;\nNext := n * 10;\nEND_METHOD\n"
            "END_FUNCTION_BLOCK\n" + program("    c : Counter; a, b : INT := -1;", "a := c.Untouched();\nb := c.Next();"))
    main = after_one_scan(text)
    assert (main["a"], main["b"]) == (0, 20)


def test_a_real_constant_beyond_real_is_refused_only_where_it_is_stored():
    """The literal typing rule (checker/expressions.py): a constant that does not fit is
    an error in an assignment, initial value or input argument (E-TYPE-005), not as an
    operand.  `r < 1.0E40` compares, stores nothing: accepted, and TRUE for r = 3.0E38."""
    text = program("    r : REAL := 3.0E38; b : BOOL;", "b := r < 1.0E40;")
    assert diagnostics(text) == []
    assert after_one_scan(text)["b"] is True


def test_a_global_of_a_prelude_structure_orders_the_types_as_a_full_check():
    """checker/prelude_base.py: a load that shares the checked prelude gives exactly the
    program of a full check, its tables in the same order.  A global AXIS_REF resolves
    that prelude TYPE before the others; its member types enter first, as resolving it
    does in the full check."""
    from test_prelude_sharing import _both_ways, _layout

    texts = {"g.st": "VAR_GLOBAL gax : AXIS_REF; END_VAR\n"
                     + program("    p : LREAL;", "p := gax.Cmd.Pos;")}
    (shared, program_shared), (full, program_full) = _both_ways(texts, "iec")
    assert shared == full == []
    assert _layout(program_shared) == _layout(program_full)

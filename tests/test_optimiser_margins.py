"""Each line's leading spaces (st_runtime/compiler/optimise/margins.py), by hand: the plain
`lstrip()` where only spaces lead, and only the spaces counted where another white space does."""

from __future__ import annotations

from st_runtime.compiler.optimise.margins import stripped, widths


def test_the_leading_spaces_of_plain_lines():
    text = ["def f():", "    x = 1", "", "        y", "   "]
    assert widths(text) == [0, 4, 0, 8, 3]
    assert stripped(text) == ["def f():", "x = 1", "", "y", ""]


def test_only_spaces_count_where_another_white_space_leads():
    """A tab, a form feed, an ideographic space: `str.lstrip()` would strip them too (wrong)."""
    assert widths(["  \tx = 1", "    y = 2"]) == [2, 4]
    assert widths(["    \x0cz", "\u3000w"]) == [4, 0]
    assert stripped(["  \tx"]) == ["\tx"]


def test_the_first_line_passing_a_test_each_way():
    """Indentations 0, then 100 lines of 8, then 4, then 0 (lines 0..102): from line 1 the first
    line not deeper than 4 is line 101 (past several windows), the first less indented than 4
    line 102; back from line 100 the first not deeper than 4 is line 0; none deeper than 8."""
    from st_runtime.compiler.optimise.margins import first_passing

    indents = [0] + [8] * 100 + [4, 0]
    assert first_passing(indents, 1, (4).__ge__) == 101
    assert first_passing(indents, 1, (4).__gt__) == 102
    assert first_passing(indents, 100, (4).__ge__, -1) == 0
    assert first_passing(indents, 0, (8).__lt__) is None
    assert first_passing(indents, 0, (8).__lt__, -1) is None
    assert first_passing(indents, 103, (8).__ge__) is None and first_passing(indents, -1, (8).__ge__, -1) is None
    assert first_passing(indents, 5, (8).__ge__) == 5 and first_passing(indents, 5, (8).__ge__, -1) == 5

"""The text passes' line patterns read a line's leading white space possessively (`*+`):
without it, a line that does not match is tried again once for each leading space (the regex
engine backtracks into the indentation), which on the generated code's deep indentation cost
several times the match itself.  What follows the white space in each pattern can never
start with white space, so each matches exactly what the same pattern without `+` matches:
asserted here on lines of each kind, matching and not, by `match`, `fullmatch` and `search`."""

from __future__ import annotations

import importlib
import re

import pytest

PATTERNS = [("charges", name) for name in ("_CHARGE", "_LOOP", "_BRANCH", "_SETS", "_COMPOUND",
                                           "LITERAL_STORE", "LOCAL_TEST", "_BINDS", "_TARGET")] + [
    ("reads", "_ASSIGNMENT"), ("aliases", "_LOAD_LINE"), ("vector", "_TOKEN"), ("pivots", "_CANDIDATE"),
    ("unguard", "_ASSIGNMENT"), ("unguard", "_STORE"), ("unguard", "_ELEMENT_STORE"), ("unguard", "_COPY"),
    ("fuse", "_PURE"), ("fuse", "_ACCUMULATE"), ("fuse", "_LOOP"), ("halves", "_SINGLE_TEST"),
    ("reuse", "_MARKER"), ("chains", "_STORE")]

LINES = ["        _spent += 12", "    _spent = 0", "  _spent -= 3", "    if v_X:", "    elif (not v_X):",
         "        if (v_NEW == 4):", "    v_S = -2", "    v_S = True", "    for i in r:", "    while x:",
         "    with a:", "    else:", "        try:", "    except E as v_E:", "    del v_X", "            x = 1",
         "            if x > 2: y = 3", "    _spentx = 1", "     ", "", "\t_spent += 1", "  \t if v_X:",
         "    v_A = self.v_A", "    v_A = _G.v_A", "    v_A = self.v_B", "        x += (a * b)",
         "    x = (x + 1.5)", "    self.v_Q[3] = v_R", "    v_Q[:] = v_R", "    v_Q[_WHOLE] = v_R", "    v_Q[2] = (a - b)",
         "      elif _t3 == 4:", "    if _t1 < 8:", "    if (abs(v_A[1]) > abs(v_M[v_K])):",
         "  \x04" + "1,2\x04", "\x04" + "7\x04", "    a\n    \x04" + "3\x04", "  ( x + 1 )", "12.5e3 * y"]


@pytest.mark.parametrize("module, name", PATTERNS)
def test_a_possessive_pattern_matches_what_the_backtracking_one_does(module, name):
    possessive = getattr(importlib.import_module(f"st_runtime.compiler.optimise.{module}"), name)
    assert "*+" in possessive.pattern
    backtracking = re.compile(possessive.pattern.replace("*+", "*"), possessive.flags)
    for line in LINES:
        for method in ("match", "fullmatch", "search"):
            found, expected = getattr(possessive, method)(line), getattr(backtracking, method)(line)
            assert (found and (found.span(), found.groups())) == (expected and (expected.span(), expected.groups())), \
                (method, line)

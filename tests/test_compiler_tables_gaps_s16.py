"""The charges pass line by line, session 16 (issue 16; docs/mutation.md, "Session 16, gaps"):
rows for the survivors of a run of every mutant of st_runtime/compiler/optimise/charges.py.

`charges.merge(lines, start)` rewrites a body's generated Python in place.  Each row gives
the lines as the compiler writes them and the lines after the pass, worked out by hand from
the pass's rules (its module docstring):

- two charges `_spent += N` of one block level join (the later amount added to the earlier
  line) when no line between can raise, check the budget or leave the level: a `try`,
  `except`, `finally`, `_ctx`, `_overrun`, `return`, `break`, `continue`, a call of ST code
  (`.execute(`, `_fn_`), a loop head, or any other line opening a block that is not a branch
  of an IF; and no line between is less indented than the two;
- then a charge that an IF chain follows (within 16 lines, none a barrier, no condition one)
  goes into each branch: added to the branch's first charge of its level (before any barrier),
  or written at the branch's start; a chain without ELSE gets one that charges it; a charge
  so moved goes on into a chain it is followed by (8 readings at most);
- with fewer than two charges in the body, nothing changes.
"""

from __future__ import annotations

import pytest

from st_runtime.compiler.optimise import charges


def _lines(text: str) -> list[str]:
    return text.strip("\n").split("\n")


# (name, the lines before, the lines after); every body inside `def`, at indentation 4 or more.
MERGES = [
    ("two charges with an assignment between join",
     """
    _spent += 3
    v_A = 1
    _spent += 4
""", """
    _spent += 7
    v_A = 1
"""),
    ("one charge alone stays",
     """
    _spent += 3
    v_A = 1
""", None),
    ("a charge of another form is not one (a name, a comment)",
     """
    _spent += 3
    _spent += n
    _spent += 4  # four
""", None),
    ("three charges join into the first",
     """
    _spent += 1
    v_A = 1
    _spent += 20
    v_B = 2
    _spent += 300
""", """
    _spent += 321
    v_A = 1
    v_B = 2
"""),
    ("a budget check between keeps them apart",
     """
    _spent += 3
    if _ctx.budget < _spent: _overrun(_ctx, _spent)
    _spent += 4
""", None),
    ("a call of ST code between keeps them apart",
     """
    _spent += 3
    self.v_F.execute(_ctx)
    _spent += 4
""", None),
    ("a FUNCTION's call between keeps them apart",
     """
    _spent += 3
    v_A = _fn_F(_ctx, 1)
    _spent += 4
""", None),
    ("a return between keeps them apart",
     """
    _spent += 3
    return v_A
    _spent += 4
""", None),
    ("a loop between keeps them apart",
     """
    _spent += 3
    for v_I in range(1, 3):
        v_A = v_I
    _spent += 4
""", None),
    ("a while loop between keeps them apart",
     """
    _spent += 3
    while v_A < 3:
        v_A = v_A + 1
    _spent += 4
""", None),
    ("a try between keeps them apart",
     """
    _spent += 3
    try:
        v_A = 1
    except _FAULTS as _e:
        pass
    _spent += 4
""", None),
    ("a with block between keeps them apart",
     """
    _spent += 3
    with x:
        v_A = 1
    _spent += 4
""", None),
    ("a break between keeps them apart (the first sinks into the IF before it)",
     """
    for v_I in range(3):
        _spent += 3
        if v_I > 1:
            break
        _spent += 4
""", """
    for v_I in range(3):
        if v_I > 1:
            _spent += 3
            break
        else:
            _spent += 3
        _spent += 4
"""),
    ("a continue between keeps them apart (the first sinks into the IF before it)",
     """
    for v_I in range(3):
        _spent += 3
        if v_I > 1:
            continue
        _spent += 4
""", """
    for v_I in range(3):
        if v_I > 1:
            _spent += 3
            continue
        else:
            _spent += 3
        _spent += 4
"""),
    ("a barrier's word inside a longer word is none",
     """
    _spent += 3
    v_A = self.returns
    v_B = _breaking + continued
    v_C = {retry: 1}
    v_D = excepted
    v_E = {notfinally: 1}
    _spent += 4
""", """
    _spent += 7
    v_A = self.returns
    v_B = _breaking + continued
    v_C = {retry: 1}
    v_D = excepted
    v_E = {notfinally: 1}
"""),
    ("an IF between, its branch with its own charge: the level's charges join, the branch's stays",
     """
    _spent += 3
    if v_A > 1:
        _spent += 10
        v_B = 1
    _spent += 4
    v_C = 2
""", """
    if v_A > 1:
        _spent += 17
        v_B = 1
    else:
        _spent += 7
    v_C = 2
"""),
    ("charges of two branches never join (the ELSE line is less indented)",
     """
    if v_A > 1:
        v_B = 1
        _spent += 3
    else:
        _spent += 4
        v_B = 2
""", None),
    ("a barrier after two joined charges keeps the third apart",
     """
    _spent += 1
    v_A = 1
    _spent += 2
    self.v_F.execute(_ctx)
    _spent += 4
    v_B = 1
    _spent += 8
""", """
    _spent += 3
    v_A = 1
    self.v_F.execute(_ctx)
    _spent += 12
    v_B = 1
"""),
    ("charges of two levels, each joined at its own",
     """
    _spent += 1
    if v_A > 1:
        _spent += 2
        v_B = 1
        _spent += 4
    _spent += 8
""", """
    if v_A > 1:
        _spent += 15
        v_B = 1
    else:
        _spent += 9
"""),
    ("a line holding every barrier word (a STRING literal's text) is still a barrier",
     """
    _spent += 3
    v_S = 'try: except finally: _ctx _overrun return break continue .execute( _fn_'
    _spent += 4
""", None),
    ("a line opening a block of another kind (a def) is a barrier",
     """
    _spent += 3
    def _f():
        v_A = 1
    _spent += 4
""", None),
    ("a loop written on one line is a barrier",
     """
    _spent += 3
    while v_A > 0: v_A = v_A - 1
    _spent += 4
""", None),
    # ---- sinking into IF chains
    ("a charge sinks into both branches of the IF after it",
     """
    _spent += 5
    if v_A > 1:
        v_B = 1
    else:
        v_B = 2
    v_C = 3
    self.v_F.execute(_ctx)
    _spent += 1
""", """
    if v_A > 1:
        _spent += 5
        v_B = 1
    else:
        _spent += 5
        v_B = 2
    v_C = 3
    self.v_F.execute(_ctx)
    _spent += 1
"""),
    ("past assignments that cannot raise, and into an ELSIF",
     """
    _spent += 5
    v_X = 0
    if v_A > 1:
        v_B = 1
    elif v_A > 0:
        v_B = 2
    else:
        v_B = 3
    _ctx.x = 1
    _spent += 1
""", """
    v_X = 0
    if v_A > 1:
        _spent += 5
        v_B = 1
    elif v_A > 0:
        _spent += 5
        v_B = 2
    else:
        _spent += 5
        v_B = 3
    _ctx.x = 1
    _spent += 1
"""),
    ("a chain without ELSE gets one that charges",
     """
    _spent += 5
    if v_A > 1:
        v_B = 1
    v_C = 2
    _ctx.x = 1
    _spent += 1
""", """
    if v_A > 1:
        _spent += 5
        v_B = 1
    else:
        _spent += 5
    v_C = 2
    _ctx.x = 1
    _spent += 1
"""),
    ("a chain without ELSE at the end of the body",
     """
    _ctx.x = 1
    _spent += 1
    _spent += 5
    if v_A > 1:
        v_B = 1
""", """
    _ctx.x = 1
    if v_A > 1:
        _spent += 6
        v_B = 1
    else:
        _spent += 6
"""),
    ("a branch's own first charge takes the sunk one",
     """
    _spent += 5
    if v_A > 1:
        v_B = 1
        _spent += 7
        v_C = 1
    else:
        _spent += 9
""", """
    if v_A > 1:
        v_B = 1
        _spent += 12
        v_C = 1
    else:
        _spent += 14
"""),
    ("a branch charge after a barrier is not taken: one is written at the branch's start",
     """
    _spent += 5
    if v_A > 1:
        self.v_F.execute(_ctx)
        _spent += 7
    else:
        v_B = 2
""", """
    if v_A > 1:
        _spent += 5
        self.v_F.execute(_ctx)
        _spent += 7
    else:
        _spent += 5
        v_B = 2
"""),
    ("a barrier between the charge and the IF keeps it",
     """
    _spent += 5
    self.v_F.execute(_ctx)
    if v_A > 1:
        _spent += 1
        v_B = 1
""", None),
    ("an IF whose condition is a barrier keeps it",
     """
    _spent += 5
    if _fn_F(_ctx, v_A) > 1:
        _spent += 1
        v_B = 1
""", None),
    ("an ELSIF whose condition is a barrier keeps it",
     """
    _spent += 5
    if v_A > 1:
        _spent += 1
    elif _fn_F(_ctx, v_A) > 1:
        v_B = 1
""", None),
    ("a line of a deeper level before the IF keeps it",
     """
    _spent += 5
    v_A = 1
        v_B = 2
    if v_A > 1:
        _spent += 1
""", None),
    ("a chain without ELSE whose branch has a charge",
     """
    _spent += 5
    if v_A > 1:
        _spent += 1
    v_B = 1
""", """
    if v_A > 1:
        _spent += 6
    else:
        _spent += 5
    v_B = 1
"""),
    # the four paths pay 5+1+3, 5+1+4, 5+2+3, 5+2+4 before and 10-1, 10, 11-1, 11 after
    ("two chains in a row: the charge sinks into the first, the second's ELSE charge is lifted into it",
     """
    _spent += 5
    if v_A > 1:
        _spent += 1
    else:
        _spent += 2
    if v_B > 1:
        _spent += 3
    else:
        _spent += 4
""", """
    if v_A > 1:
        _spent += 10
    else:
        _spent += 11
    if v_B > 1:
        _spent -= 1
"""),
    ("a charge with no chain after it, or of another form, leaves the later ones to sink",
     """
    _spent += 1
    _spent += 3 * 40
    self.v_F.execute(_ctx)
    _spent += 5
    if v_A > 1:
        v_B = 1
""", """
    _spent += 1
    _spent += 3 * 40
    self.v_F.execute(_ctx)
    if v_A > 1:
        _spent += 5
        v_B = 1
    else:
        _spent += 5
"""),
    ("a branch's charge that took a sunk one sinks with it into the chain after it, in one reading",
     """
    _spent += 5
    if v_A > 1:
        _spent += 2
        if v_B > 1:
            _spent += 1
        else:
            _spent += 3
    else:
        _spent += 4
""", """
    if v_A > 1:
        if v_B > 1:
            _spent += 8
        else:
            _spent += 10
    else:
        _spent += 9
"""),
    ("two chains without ELSE ending at one line: the inner ELSE is written first",
     """
    _spent += 5
    if v_A > 1:
        v_B = 1
        _spent += 2
        if v_C > 1:
            v_D = 1
    v_E = 1
""", """
    if v_A > 1:
        v_B = 1
        if v_C > 1:
            _spent += 7
            v_D = 1
        else:
            _spent += 7
    else:
        _spent += 5
    v_E = 1
"""),
    ("a sunk charge goes on into the chain its branch opens with",
     """
    _spent += 5
    if v_A > 1:
        if v_B > 1:
            _spent += 1
        else:
            _spent += 2
    else:
        _spent += 3
""", """
    if v_A > 1:
        if v_B > 1:
            _spent += 6
        else:
            _spent += 7
    else:
        _spent += 8
"""),
]


def _chain_text(depth: int) -> str:
    """A charge, then IFs nested `depth` deep, each with an ELSE that charges 1."""
    lines = ["    _spent += 5"]
    for level in range(depth):
        pad = "    " * (level + 1)
        lines += [f"{pad}if v_A > {level}:"]
    lines.append("    " * (depth + 1) + "v_B = 1")
    for level in reversed(range(depth)):
        pad = "    " * (level + 1)
        lines += [f"{pad}else:", f"{pad}    _spent += 1"]
    return "\n".join(lines)


def _after_ahead(plain: int) -> str:
    return "\n".join(["    _spent += 5", *[f"    v_X{k} = {k}" for k in range(plain)],
                      "    if v_A > 1:", "        _spent += 1", "    else:", "        _spent += 2"])


@pytest.mark.parametrize("name, before, after", MERGES, ids=[m[0] for m in MERGES])
def test_merge(name, before, after):
    lines = _lines(before)
    charges.merge(lines, 0)
    assert lines == _lines(after if after is not None else before)


def test_merge_reads_only_from_its_start():
    head = ["    _spent += 1", "    v_B = 1"]
    text = head + ["    _spent += 3", "    v_A = 1", "    _spent += 4"]
    charges.merge(text, len(head))
    assert text == head + ["    _spent += 7", "    v_A = 1"]


@pytest.mark.parametrize("plain, sinks", [(0, True), (14, True), (15, True), (16, False)])
def test_a_charge_sinks_past_at_most_15_plain_lines(plain, sinks):
    """`_LOOK_AHEAD` 16: the IF must be among the 16 lines after the charge."""
    lines = _lines(_after_ahead(plain))
    charges.merge(lines, 0)
    assert (lines[0] != "    _spent += 5") == sinks
    if sinks:
        assert lines[plain:] == ["    if v_A > 1:", "        _spent += 6", "    else:", "        _spent += 7"]


@pytest.mark.parametrize("depth", [1, 2, 8, 9, 10])
def test_a_sunk_charge_goes_eight_chains_deep(depth):
    """`_ROUNDS` 8: each reading moves a charge written at a branch's start one chain deeper;
    the innermost THEN gets the 5 when it is at most 8 chains deep (each ELSE's 1 becomes 6)."""
    lines = _lines(_chain_text(depth))
    charges.merge(lines, 0)
    reached = min(depth, 8)        # the chains the 5 went into: their ELSEs charge 6
    assert [line.strip() for line in lines].count("_spent += 6") == reached
    assert [line.strip() for line in lines].count("_spent += 1") == depth - reached
    # the 5 at the start of the THEN of the last chain reached (the innermost one's body when
    # all were), written before that chain's next IF or its v_B
    fives = [line for line in lines if line.strip() == "_spent += 5"]
    assert fives == ["    " * (reached + 1) + "_spent += 5"]

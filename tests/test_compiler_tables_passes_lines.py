"""The line passes' table (issue 16, session 13; docs/mutation.md, compiler, "Session 13,
optimise"): seal.py, charges.py and gather.py rewrite the generated Python's lines; each row
is a body's lines and the lines the pass's contract gives, written out by hand, and for
charges and seal the rewritten body run beside the original (the same `_spent` at every
read, the same seal object at every test).
"""

from __future__ import annotations

import operator

import pytest

from st_runtime.compiler.optimise import charges, gather, seal

# ------------------------------------------------------------------------------------ seal
# A body that reads `_ctx.seal` twice or more (as code, not inside a string) reads it once,
# `_seal = _ctx.seal` first; one read or none: unchanged.

SEAL = [
    ("no read", ["    x = 1", "    y = 2"], None),
    ("one read", ["    if f._at_rest is not _ctx.seal: f.go()"], None),
    ("two reads on two lines",
     ["    if f._at_rest is not _ctx.seal: f.go()", "    f._at_rest = _ctx.seal"],
     ["    _seal = _ctx.seal", "    if f._at_rest is not _seal: f.go()", "    f._at_rest = _seal"]),
    ("two reads on one line",
     ["    if a is not _ctx.seal or b is not _ctx.seal: go()"],
     ["    _seal = _ctx.seal", "    if a is not _seal or b is not _seal: go()"]),
    ("three reads, indented blocks",
     ["    try:", "        if a is not _ctx.seal:", "            a = _ctx.seal", "        b = (_ctx.seal, 1)"],
     ["    _seal = _ctx.seal", "    try:", "        if a is not _seal:", "            a = _seal", "        b = (_seal, 1)"]),
    ("a read inside a string is a value",
     ["    x = '_ctx.seal'", "    y = \"_ctx.seal and _ctx.seal\"", "    z = _ctx.seal"], None),
    ("a string and a read on one line",
     ["    f(\"_ctx.seal\", _ctx.seal)", "    g(_ctx.seal)"],
     ["    _seal = _ctx.seal", "    f(\"_ctx.seal\", _seal)", "    g(_seal)"]),
    ("a longer name is not the read",
     ["    a = x_ctx.seal", "    b = _ctx.sealed", "    c = _ctx.seal"], None),
    ("spaces around the dot are no read of ours",
     ["    a = _ctx . seal", "    b = _ctx.seal"], None),
    ("a line that is no whole statement",
     ["    x = (_ctx.seal,", "         _ctx.seal)", "    y = _ctx.seal"], None),
]


@pytest.mark.parametrize("name, lines, want", SEAL, ids=[r[0] for r in SEAL])
def test_seal(name, lines, want):
    body = ["def _body_X(self, _ctx):", *lines]
    out = list(body)
    seal.hoist(out, 1)
    assert out == (body if want is None else ["def _body_X(self, _ctx):", *want])


def test_seal_starts_where_it_is_told():
    lines = ["    y = _ctx.seal", "def _body_X(self, _ctx):", "    a = _ctx.seal", "    b = _ctx.seal"]
    seal.hoist(lines, 2)
    assert lines == ["    y = _ctx.seal", "def _body_X(self, _ctx):", "    _seal = _ctx.seal",
                     "    a = _seal", "    b = _seal"]
    lines = ["def f():", "    a = _ctx.seal", "    b = 1"]
    seal.hoist(lines, 2)                   # one read from line 2 on: left
    assert lines == ["def f():", "    a = _ctx.seal", "    b = 1"]


# --------------------------------------------------------------------------------- charges
# A charge of a block level is added to the one before it in that level when nothing
# between them can raise, check the budget or leave the level.

BARRIERS = ["try:", "except _FAULTS:", "finally:", "_ctx.fault(e)", "_overrun(x)", "return v_X",
            "break", "continue", "f.execute(_ctx)", "v_Y = _fn_F(_ctx)", "for v_K in _k1:",
            "while True:", "with x:", "def g():"]


def _run_charges(lines: list[str]) -> list[str]:
    out = list(lines)
    charges.merge(out, 0)
    return out


def test_two_charges_with_assignments_between_are_one():
    assert _run_charges(["        _spent += 5", "        v_X = 1", "        v_Y = (v_X + 2)", "        _spent += 7"]) \
        == ["        _spent += 12", "        v_X = 1", "        v_Y = (v_X + 2)"]


def test_a_run_of_charges_and_an_if_with_its_own_charges():
    lines = ["    _spent += 1", "    if v_A:", "        _spent += 10", "        v_X = 2", "    else:",
             "        _spent += 20", "    _spent += 3", "    v_Y = 1", "    _spent += 4"]
    # the run's 1 + 3 + 4 joined, then sunk into both branches of the IF after it
    assert _run_charges(lines) == ["    if v_A:", "        _spent += 18", "        v_X = 2",
                                   "    else:", "        _spent += 28", "    v_Y = 1"]


@pytest.mark.parametrize("barrier", BARRIERS)
def test_a_barrier_between_keeps_both(barrier: str):
    lines = ["        _spent += 5", f"        {barrier}", "        _spent += 7"]
    assert _run_charges(lines) == lines


def test_a_barrier_before_the_first_or_after_the_last_does_not_count():
    assert _run_charges(["        try:", "        _spent += 5", "        v_X = 1", "        _spent += 7", "        return v_X"]) \
        == ["        try:", "        _spent += 12", "        v_X = 1", "        return v_X"]


def test_a_charge_after_a_less_indented_line_starts_a_new_run():
    lines = ["        _spent += 5", "    v_X = 1", "        _spent += 7"]
    assert _run_charges(lines) == lines
    lines = ["    if v_A:", "        _spent += 5", "    if v_B:", "        _spent += 7"]
    assert _run_charges(lines) == lines


def test_a_charge_joins_across_a_deeper_block_and_the_barrier_restarts_the_run():
    lines = ["    _spent += 1", "    if v_A:", "        _spent += 2", "        v_X = 1", "        _spent += 3",
             "    _spent += 4", "    _overrun(x)", "    _spent += 5", "    v_Y = 0", "    _spent += 6"]
    # 1 + 4 joined and sunk into the IF, which gets an ELSE to charge it on the other path
    assert _run_charges(lines) == ["    if v_A:", "        _spent += 10", "        v_X = 1", "    else:",
                                   "        _spent += 5", "    _overrun(x)", "    _spent += 11", "    v_Y = 0"]


def test_a_charge_sinks_through_nested_chains_and_stops_at_a_barrier():
    lines = ["    _spent += 1", "    v_Z = 0", "    if v_A:", "        _spent += 2", "        if v_B:",
             "            v_X = 1", "    elif v_C:", "        v_X = 2", "    v_Y = 0"]
    # 1 into each branch (the ELIF's has none: written at its start; an ELSE added), the
    # IF's 3 into its inner IF (an ELSE added there too, before the outer one's)
    assert _run_charges(lines) == ["    v_Z = 0", "    if v_A:", "        if v_B:", "            _spent += 3",
                                   "            v_X = 1", "        else:", "            _spent += 3",
                                   "    elif v_C:", "        _spent += 1", "        v_X = 2", "    else:",
                                   "        _spent += 1", "    v_Y = 0"]
    for barrier in ("    if _ctx.budget < _spent:", "    try:"):
        lines = ["    _spent += 1", barrier, "        v_X = 1", "    _spent += 2"]
        assert _run_charges(lines)[:2] == lines[:2]


def test_one_charge_or_none_is_left_as_it_is():
    for lines in (["    v_X = 1"], ["    _spent += 1", "    v_X = 1"]):
        assert _run_charges(lines) == lines


def test_merge_starts_where_it_is_told():
    lines = ["    _spent += 1", "    _spent += 2", "    v_X = 1", "    _spent += 3"]
    charges.merge(lines, 1)
    assert lines == ["    _spent += 1", "    _spent += 5", "    v_X = 1"]


# ---------------------------------------------------------------------------------- gather

def _registry():
    bound = {}

    def register(value):
        bound[f"_k{len(bound)}"] = value
        return f"_k{len(bound) - 1}"
    return bound, register


def test_gather_a_run_of_four_loads_from_one_owner():
    bound, register = _registry()
    lines = ["v_A = self.v_A", "v_B = self.v_B", "v_C = self.v_C", "v_D = self.v_D", "_spent = 0"]
    assert gather.prologue(lines, register) == ["v_A, v_B, v_C, v_D = _k0(self)", "_spent = 0"]
    getter = bound["_k0"]
    assert isinstance(getter, operator.attrgetter)

    class Owner:
        v_A, v_B, v_C, v_D = 1, 2, 3, 4
    assert getter(Owner) == (1, 2, 3, 4)


def test_gather_leaves_short_runs_and_splits_at_another_owner_or_line():
    bound, register = _registry()
    lines = ["v_A = self.v_A", "v_B = self.v_B", "v_C = self.v_C", "v_G = _G.v_G", "v_H = _G.v_H",
             "v_I = _G.v_I", "v_J = _G.v_J", "x = 1", "v_E = self.v_E", "v_F = self.v_F"]
    assert gather.prologue(lines, register) == ["v_A = self.v_A", "v_B = self.v_B", "v_C = self.v_C",
                                                "v_G, v_H, v_I, v_J = _k0(_G)", "x = 1",
                                                "v_E = self.v_E", "v_F = self.v_F"]
    assert len(bound) == 1
    lines = ["v_A = self.v_A", "v_B = self.v_B", "v_C = self.v_C", ["a list"], "v_D = self.v_D"]
    assert gather.prologue(lines, register) == lines
    renamed = ["x = self.v_A", "y = self.v_B", "z = self.q", "w = self.v_D"]
    assert gather.prologue(renamed, register) == ["x, y, z, w = _k1(self)"]
    assert bound["_k1"].__reduce__()[1] == ("v_A", "v_B", "q", "v_D")


# --------------------------------------------------------------- branches: code that cannot fault
# branches.code_cannot_fault: names, literals, attributes, subscripts, comparisons,
# `& | ^ ~ not and or`, `+ - *` (at most 14), calls of abs/min/max only; no `/ // % ** << >>`,
# no `:=`, no `=` store, no other call, no keyword but not/and/or/if/else/in/is.

from st_runtime.compiler.optimise import branches  # noqa: E402

SUM = " + ".join(f"v_{chr(65 + i)}" for i in range(15))          # 14 `+`
CODES = [
    ("v_X", True), ("self.v_X", True), ("_G.v_X", True), ("v_A[3]", True), ("v_A[v_I - 1]", True),
    ("(v_X + 1)", True), ("(v_X - 1)", True), ("(v_X * 2)", True), ("(v_X - -1)", True),
    ("(v_X / 2)", False), ("(v_X // 2)", False), ("(v_X % 2)", False), ("(v_X ** 2)", False),
    ("(v_X << 1)", False), ("(v_X >> 1)", False), ("(v_X == 1)", True), ("(v_X != 1)", True),
    ("(v_X <= 1)", True), ("(v_X >= 1)", True), ("(v_X < 1)", True), ("(v_X > 1)", True),
    ("(_t1 := v_X)", True), ("(v_X := 1)", False), ("v_X = 1", False), ("abs(v_X)", True), ("abs (v_X)", True),
    ("min(v_X, 2)", True), ("max(v_A, v_B, 3)", True), ("_f32(v_X)", False), ("len(v_X)", False),
    ("v_X.append(1)", False), ("not v_A", True), ("(v_A and v_B)", True), ("(v_A or v_B)", True),
    ("(v_A if v_B else v_C)", True), ("(v_X in (1, 2))", True), ("(v_X in {1, 2})", True), ("{v_X: 1}", False), ("(v_X is None)", True),
    ("True", True), ("False", True), ("(v_A & v_B)", True), ("(v_A | v_B)", True), ("(v_A ^ v_B)", True),
    ("~v_A", True), ("'a'", False), ('"a"', False), ("(v_X @ v_Y)", False), ("lambda: 1", False),
    ("(v_A for v_A in v_B)", False), ("await v_X", False), ("", False), ("   ", False),
    (SUM, True), (SUM + " + v_Z", False), ("(1e+308 + 2.5e-300) - 1E+5", True),
    ("(" + " * ".join(["2.0e+10"] * 15) + ")", True), ("(" + " * ".join(["v_X"] * 15) + ")", True),
    ("(" + " * ".join(["v_X"] * 16) + ")", False),
    (" + ".join(f"v_{chr(65 + i)}" for i in range(14)) + " + \x00_t3\x00", False),   # i * 1: one more
    (" + ".join(f"v_{chr(65 + i)}" for i in range(14)) + " + \x031\x03", True),      # a reuse value: _c1
    ("(v_X + \x00_t3\x00)", True),
]


@pytest.mark.parametrize("code, ok", CODES, ids=[repr(c)[:40] for c, _ in CODES])
def test_code_that_cannot_fault(code: str, ok: bool):
    assert branches.code_cannot_fault(code) is ok


def test_per_iteration_values_and_reuse_tokens():
    assert branches.per_iteration_values("v_A[\x00_t2\x00]") == "v_A[(_t2 * 1)]"
    assert branches.per_iteration_values("(\x037\x03 + \x00_t1\x00)") == "(_c7 + (_t1 * 1))"
    assert branches.per_iteration_values("(v_X + 1)") == "(v_X + 1)"

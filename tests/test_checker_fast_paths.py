"""The checker's short ways give what its general ways give (docs/load.md, tenth round).

`ExprChecker.settle` types a lone integer literal that fits the integer type it is expected
as at once; the general way (`_settle_folded`) folds the expression and types each node.
Both are compared by every `record` the checker makes (node, position, type, value, in
order) and by the diagnostics, on literals at the edges of each integer type and on the
accept corpus."""

from __future__ import annotations

from pathlib import Path

import pytest

from st_runtime import ast
from st_runtime import types as T
from st_runtime.checker import typesys as ts
from st_runtime.checker.constfold import NOT_CONSTANT
from st_runtime.checker.context import Scope
from st_runtime.checker.declarations import Declarations
from st_runtime.checker.expressions import ExprChecker
from st_runtime.loader import load_texts

ROOT = Path(__file__).resolve().parent.parent
ACCEPT = sorted((ROOT / "tests" / "corpus" / "accept").glob("*.st"))

#: Literals at and beyond the edges of the integer types, in every context that expects a type.
EDGES = """
TYPE Small : INT (0..10); END_TYPE
PROGRAM Main
VAR
    s : SINT := 127; us : USINT := 255; i : INT := -32768; ui : UINT := 65535;
    b : BYTE := 16#FF; w : WORD := 65535; d : DINT := 2147483647; ud : UDINT := 4294967295;
    l : LINT := 9223372036854775807; ul : ULINT := 18446744073709551615;
    r : REAL := 3; lr : LREAL := 1; x : BOOL := 1; sm : Small := 10; t : TIME;
    a : ARRAY[0..3] OF INT := [1, 2, 32767, 0];
END_VAR
s := 0; s := 127; us := 0; us := 255; i := 32767; ui := 0; b := 0; w := 1;
d := 2147483647; ud := 4294967295; l := 1; ul := 18446744073709551615;
sm := 0; sm := 10; r := 7; lr := 100000; x := 0;
s := s + 1; s := 1 + s; i := s + 200; us := us - 255; d := d * 65536;
x := s > 100; x := s > 200; x := i = 32768; x := 5 < i;
ul := ul + 18446744073709551615; l := l - 9223372036854775807;
w := w AND 16#FF00; b := b OR 1;
i := a[3] + 1; i := s MOD 7; i := i / 2;
t := T#1s * 3;
CASE i OF 0: s := 1; 1, 2: s := 2; 3..127: s := 3; END_CASE;
FOR i := 0 TO 3 BY 1 DO a[i] := i + 1; END_FOR;
END_PROGRAM
"""

#: Literals that do not fit what they are stored into: E-TYPE-005 from the general way.
TOO_LARGE = """
PROGRAM Main
VAR s : SINT; us : USINT; i : INT; b : BYTE; sm : INT (0..10); x : BOOL; END_VAR
s := 128; us := 256; i := 32768; b := 256; sm := 11;
s := 127; us := 255; i := 32767; b := 255; sm := 10; s := -128; i := -32768;
s := s + 128; i := i + 32768; x := s < 1000; sm := sm + 11; b := b + 256;
END_PROGRAM
"""


def _general_settle(self, e, expected, strict: bool):
    """`settle` without its short way: the BOOL literal, then the general way."""
    if ts.is_bool(expected) and isinstance(e, ast.IntLiteral) and e.value in (0, 1):
        return self.record(e, T.BOOL, bool(e.value))
    return self._settle_folded(e, expected, strict)


def _checked(monkeypatch, texts: dict, dialect: str, general: bool) -> tuple[list, list, int]:
    """(every record the checker made, the diagnostics, how many settles did not fold)."""
    load_texts({"warm.st": "PROGRAM W END_PROGRAM"}, dialect)     # (the prelude checked before)
    records, folded = [], []
    record, settle_folded = ExprChecker.record, ExprChecker._settle_folded
    settles = []

    def logged(self, e, t, value=NOT_CONSTANT):
        records.append((str(getattr(e, "pos", None)), type(e).__name__, str(t), repr(value)))
        return record(self, e, t, value)

    def counted_settle(self, e, expected, strict):
        settles.append(e)
        return settle(self, e, expected, strict)

    def counted_folded(self, e, expected, strict):
        folded.append(e)
        return settle_folded(self, e, expected, strict)

    settle = _general_settle if general else ExprChecker.settle
    with monkeypatch.context() as patch:
        patch.setattr(ExprChecker, "record", logged)
        patch.setattr(ExprChecker, "settle", counted_settle)
        patch.setattr(ExprChecker, "_settle_folded", counted_folded)
        result = load_texts(dict(texts), dialect)
    diagnostics = [(d.code, d.message, str(d.pos), d.severity) for d in result.diagnostics]
    return records, diagnostics, len(settles) - len(folded)


@pytest.mark.parametrize("dialect", ["iec", "nj", "codesys"])
@pytest.mark.parametrize("text", [EDGES, TOO_LARGE], ids=["edges", "too-large"])
def test_a_lone_literal_is_typed_as_the_general_way_types_it(monkeypatch, text, dialect):
    short = _checked(monkeypatch, {"t.st": text}, dialect, general=False)
    general = _checked(monkeypatch, {"t.st": text}, dialect, general=True)
    assert short[:2] == general[:2]
    assert short[2] - general[2] > 5      # (the short way was taken: the comparison says something)


def test_the_corpus_is_typed_as_the_general_way_types_it(monkeypatch):
    taken = 0
    for path in ACCEPT:
        texts = {str(path.relative_to(ROOT)): path.read_text(encoding="utf-8")}
        short = _checked(monkeypatch, texts, "iec", general=False)
        general = _checked(monkeypatch, texts, "iec", general=True)
        assert short[:2] == general[:2], path.name
        taken += short[2] - general[2]
    assert taken > 300


#: (type, constant recorded for a name of it, what the table of constants must hold): an
#: integer wraps to its type's width (two's complement), a REAL rounds to float32, the rest
#: stays as it is (hand values; session 23's `record` keeps in-range integers and the
#: unchanged kinds by a look-up).
STORED = [
    ("SINT", 127, 127), ("SINT", -128, -128), ("SINT", 128, -128), ("SINT", -129, 127),
    ("INT", 32767, 32767), ("INT", 32768, -32768), ("USINT", 255, 255), ("USINT", 256, 0),
    ("UINT", -1, 65535), ("BYTE", 256, 0), ("WORD", 65535, 65535), ("WORD", 65536, 0),
    ("DINT", 2147483648, -2147483648), ("UDINT", 4294967295, 4294967295),
    ("LINT", 2**63, -2**63), ("ULINT", -1, 2**64 - 1), ("DINT", True, True),
    ("REAL", 0.1, 0.10000000149011612), ("REAL", 3, 3.0), ("LREAL", 0.1, 0.1),
    ("BOOL", True, True), ("BOOL", 0, 0), ("TIME", 10**12, 10**12), ("DATE", -5, -5),
]


@pytest.mark.parametrize("name, value, stored", STORED)
def test_a_recorded_constant_is_stored_as_its_type_holds_it(name, value, stored):
    from st_runtime.checker.context import Context, FastSink, Scope
    from st_runtime.symbols import CheckedProgram

    ctx = Context(CheckedProgram(files=[]), FastSink(), "iec", False)
    ex = ExprChecker(ctx, Scope(ctx, None))
    node = ast.Name("x")
    assert ex.record(node, T.ELEMENTARY[name], value) is T.ELEMENTARY[name]
    held = ctx.program.constants[id(node)]
    assert held == stored and type(held) is type(stored)


#: Names met again in one body: variables, a CONSTANT (its value is recorded each time), a
#: subrange (its limits are kept apart each time), a global, an input, THIS, an enumeration value.
NAMES_AGAIN = """
TYPE Small : INT (0..10); Color : (Red, Green); END_TYPE
VAR_GLOBAL gl : DINT; END_VAR
FUNCTION_BLOCK F
VAR_INPUT inp : INT; END_VAR
VAR n : INT; c : Color; END_VAR
n := n + inp; n := THIS.n + inp; c := Green; c := Green;
END_FUNCTION_BLOCK
PROGRAM Main
VAR CONSTANT K : INT := 7; Z : INT := 0; END_VAR
VAR s : Small; i : INT; d : DINT; f : F; END_VAR
i := K; i := K + K; i := i / Z; i := i / Z; s := s + 1; s := s; i := s * s;
d := gl; gl := d + gl; f(inp := i); f(inp := K);
CASE i OF K: i := 1; END_CASE;
END_PROGRAM
"""


def _names_typed(monkeypatch, texts: dict, dialect: str, kept: bool) -> tuple[list, list]:
    """(position, name, type, symbol, constant, subrange) of every name the checker typed,
    in order, and the diagnostics; `kept=False`: every name looked up (no `_variables`)."""
    from st_runtime.checker import expressions

    load_texts({"warm.st": "PROGRAM W END_PROGRAM"}, dialect)     # (the prelude checked before)
    typed, (maybe, name), init = [], expressions._TYPERS[ast.Name], ExprChecker.__init__

    def logged(self, e, expected):
        t = name(self, e, expected)
        program, k = self.program, id(e)
        sym = program.name_refs.get(k)
        typed.append((str(e.pos), e.name, str(t), getattr(sym, "name", None), getattr(sym, "kind", None),
                      repr(program.constants.get(k, "-")), str(program.subranges.get(k))))
        return t

    def looking_up(self, ctx, scope, declared=False):
        init(self, ctx, scope, False)

    def body_checker(self, info):     # (the declarations' checker would be declared)
        return ExprChecker(self.ctx, Scope(self.ctx, info))

    with monkeypatch.context() as patch:
        patch.setitem(expressions._TYPERS, ast.Name, (maybe, logged))
        if not kept:
            patch.setattr(ExprChecker, "__init__", looking_up)
            patch.setattr(Declarations, "body_checker", body_checker)
        result = load_texts(dict(texts), dialect)
    return typed, [(d.code, d.message, str(d.pos), d.severity) for d in result.diagnostics]


def test_a_name_met_again_in_a_body_is_typed_as_its_look_up_types_it(monkeypatch):
    """A body's checker keeps the variables it found (`ExprChecker._variables`), not
    the constants or subranges, whose `record` does more than store a type."""
    texts = [{"t.st": NAMES_AGAIN}] + [{str(p.relative_to(ROOT)): p.read_text(encoding="utf-8")} for p in ACCEPT]
    names = 0
    for dialect in ("iec", "nj"):
        for text in texts:
            kept = _names_typed(monkeypatch, text, dialect, kept=True)
            assert kept == _names_typed(monkeypatch, text, dialect, kept=False), list(text)
            names += len(kept[0])
    assert names > 2000


def test_a_name_in_a_declaration_is_looked_up_where_it_is():
    """While a POU's declarations are checked a name may refer to a global, then to a local
    declared after it (`Scope.lookup`: a POU's own variables before the globals):
    `b`'s initial value reads the local BOOL `g`, not the global INT `g` that `a`'s read."""
    text = ("VAR_GLOBAL g : INT; END_VAR\nPROGRAM P\nVAR\n  a : INT := g;\n  g : BOOL;\n  b : INT := g;\n"
            "END_VAR\nEND_PROGRAM\n")
    found = [(d.code, d.pos.line, d.pos.col) for d in load_texts({"t.st": text}, "iec").diagnostics
             if "expected INT, found BOOL" in d.message]
    assert found == [("E-TYPE-004", 6, 14)]


def test_a_plain_variable_as_a_target_is_refused_for_each_reason():
    """`check_store` types a plain variable target at once (no path walked, no property
    looked up) and still refuses it for each reason a path is refused: a CONSTANT
    (E-ASSIGN-001), the POU's own input (E-ASSIGN-002), an enclosing FOR's control variable
    (E-ASSIGN-003), an enumeration value (E-TYPE-014), each at the target's name; a plain
    local (`n`) is written.  A fast path that returned the type at once fails every row."""
    text = ("TYPE Color : (Red, Green); END_TYPE\nPROGRAM P\nVAR_INPUT i : INT; END_VAR\n"
            "VAR CONSTANT c : INT := 1; END_VAR\nVAR k : INT; n : INT; END_VAR\n"
            "c := 2;\ni := 2;\nFOR k := 1 TO 2 DO\n  k := 3;\nEND_FOR;\nRed := 1;\nn := 4;\nEND_PROGRAM\n")
    found = [(d.code, d.pos.line, d.pos.col) for d in load_texts({"t.st": text}, "iec").diagnostics]
    assert found == [("E-ASSIGN-001", 6, 1), ("E-ASSIGN-002", 7, 1), ("E-ASSIGN-003", 9, 3),
                     ("E-TYPE-014", 11, 1)]

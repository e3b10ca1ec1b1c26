"""The parser's fast LALR loop (st_runtime/lalr_fast.py) builds exactly the AST, and
leads to exactly the diagnostics, of Lark's own parser loop, on every ST file of the
repository (corpus, rejected syntax, dialect files, generated code, examples)."""

from __future__ import annotations

from pathlib import Path

import pytest

from st_runtime import parser as st_parser
from st_runtime.lalr_fast import FAILED

ROOT = Path(__file__).resolve().parent.parent
FILES = sorted({p for folder in ("tests", "generated", "examples", "stgen", "st_runtime")
                for p in (ROOT / folder).rglob("*.st")})


def _both(text: str, path: str, parse=st_parser.parse):
    grammar = st_parser.grammar()
    usable = grammar.fast.usable
    fast = parse(text, path)
    grammar.fast.usable = False           # Lark's own loop, as before the fast path
    try:
        plain = parse(text, path)
    finally:
        grammar.fast.usable = usable
    return fast, plain


def _positions(node) -> list:
    """Every position in an AST (or parse result), in order: == does not compare them."""
    import dataclasses

    if isinstance(node, (list, tuple)):
        return [p for item in node for p in _positions(item)]
    if dataclasses.is_dataclass(node) and not isinstance(node, type):
        return [getattr(node, "pos", None)] + [
            p for f in dataclasses.fields(node) if f.name != "pos" for p in _positions(getattr(node, f.name))]
    return []


def test_there_are_files_of_every_kind():
    assert st_parser.grammar().fast.usable      # (the installed Lark has what the loop reads)
    assert len(FILES) > 400
    assert any("reject_syntax" in str(p) for p in FILES) and any("generated" in str(p) for p in FILES)


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_fast_loop_builds_the_same_ast(path: Path):
    text = path.read_text(encoding="utf-8", errors="replace")
    fast, plain = _both(text, path.name)
    assert fast == plain
    assert _positions(fast) == _positions(plain)


@pytest.mark.parametrize("text", [
    "", "PROGRAM", "PROGRAM P x := ; END_PROGRAM", "PROGRAM P VAR x : INT END_VAR END_PROGRAM",
    "PROGRAM P VAR x : INT; END_VAR x := 16#FFFFFFFFFFFFFFFFFF; END_PROGRAM",     # a literal error
    "PROGRAM P VAR x : TIME := T#1x; END_VAR END_PROGRAM", "FUNCTION_BLOCK F (* open",
    "x := 1; y := x * (2 + 3);",
])
def test_fast_loop_gives_the_same_diagnostics(text: str):
    fast, plain = _both(text, "t.st")
    assert fast == plain
    fast, plain = _both(text, "t.st", st_parser.parse_body)
    assert fast == plain


TEST_FILES = [p for p in FILES if "END_TEST" in p.read_text(encoding="utf-8", errors="replace")]


@pytest.mark.parametrize("path", TEST_FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_fast_loop_reads_test_files_alike(path: Path):
    """TEST, SETUP, ... are keywords there only (the postlexer's work, inline)."""
    text = path.read_text(encoding="utf-8")
    fast, plain = _both(text, path.name, st_parser.parse_tests)
    assert fast[0] is not None and fast == plain
    fast, plain = _both(text, path.name)          # elsewhere they are identifiers
    assert fast == plain


def test_every_rule_has_a_plan_of_its_own():
    """Each reduction does inline what Lark's wrapper objects do; a rule whose wrappers
    the loop does not know would keep Lark's callback (LARK): none does today, and
    every `?rule` of one symbol only changes the state (UNIT), every `_rule` is a list."""
    from st_runtime import lalr_fast

    fast = st_parser.grammar().fast
    plans = {rule: fast._plan(rule) for rule in fast.callbacks}
    kinds = {plan[2] for plan in plans.values()}
    assert lalr_fast.LARK not in kinds
    assert {lalr_fast.UNIT, lalr_fast.INLINE, lalr_fast.SPLICE} <= kinds
    for rule, plan in plans.items():
        if rule.origin.name.startswith("_"):
            assert plan[2] == lalr_fast.SPLICE, rule
        if rule.options.expand1 and not rule.alias and len(rule.expansion) == 1 \
                and not rule.expansion[0].name.startswith("_"):
            assert plan[2] == lalr_fast.UNIT, rule


def test_a_written_plan_gives_the_children_larks_filter_gives():
    """A reduction to a builder method with a child filter of Nones or spliced lists
    (CALL_PLAN) calls the method with one expression written for its rule
    (lalr_fast._call_of_plan): on the same popped values it passes, in order, the
    children Lark's own child filter of the rule gives (the filter object of the rule,
    with a list as its node builder), for every such rule of the grammar."""
    import copy

    from lark import Tree

    from st_runtime import lalr_fast

    fast = st_parser.grammar().fast
    written = 0
    for rule in fast.callbacks:
        size, _, _, _, keep, nones, _ = fast._plan(rule)
        if fast._step(rule)[1] != lalr_fast.CALL_PLAN:
            continue
        written += 1
        spliced = {i for i, splice, _ in keep if splice}

        def values(spliced_as=list):     # (fresh each time: a filter may extend a first spliced list)
            return [spliced_as([f"{i}a", f"{i}b"]) if i in spliced else f"{i}" for i in range(size)]
        lark_filter = copy.copy(fast.callbacks[rule])
        lark_filter.node_builder = list
        call = lalr_fast._call_of_plan(lambda *children: list(children), keep, nones)
        # (Lark's loop gives an inlined rule's children as a Tree, this loop as a list)
        assert call(values()) == lark_filter(values(lambda items: Tree("_inlined", items))), rule
    assert written >= 100       # (rules with an [optional] or an inlined list: 151 today)


@pytest.mark.parametrize("text", [
    # placeholders of absent [optionals], `?rule`s of several children, left-recursive
    # lists, operators at every precedence level, nested parentheses, unary chains
    "FUNCTION F : INT VAR_INPUT a, b : INT; END_VAR F := -a ** -b * (a + b) MOD 3 - NOT a; END_FUNCTION",
    "PROGRAM P VAR x : ARRAY[1..3] OF INT := [1, 2(3)]; s : STRING[10]; t : TON; END_VAR "
    "t(IN := x[1] > 2 AND x[2] <= 3 OR x[3] <> 1 XOR TRUE, PT := T#1s); "
    "IF x[1] = 1 THEN ; ELSIF x[2] >= 2 THEN x[1] := 2; ELSE x[3] := ((((1)))); END_IF; "
    "CASE x[1] OF 1, 2..3: x[2] := 0; ELSE x[3] := 1; END_CASE "
    "FOR x[1] := 1 TO 10 BY 2 DO EXIT; END_FOR; END_PROGRAM",
    "TYPE E : (A, B := 3) INT; S : STRUCT a : INT := 1; END_STRUCT END_TYPE",
    "x := a & b; y := - - - 1; z := f(a, b,); w := g(); v := h(q := 1, r => s);",
])
def test_fast_loop_builds_the_same_ast_for_every_shape(text: str):
    for parse in (st_parser.parse, st_parser.parse_body):
        fast, plain = _both(text, "t.st", parse)
        assert fast == plain
        assert _positions(fast) == _positions(plain)     # (== leaves positions out)


@pytest.mark.parametrize("text", [
    "   ", "\n\n", "\ufeffPROGRAM P END_PROGRAM", "PROGRAM P\r\n\tVAR x : INT; END_VAR\r\n\f x := 1;\n\n  \nEND_PROGRAM \t\n",
    "PROGRAM P VAR x : INT; END_VAR\n  (* a *)  \n  x := 1; // c\n\t{attribute}\n END_PROGRAM\n\n\n   ",
])
def test_fast_loop_skips_blanks_where_lark_does(text: str):
    """The loop skips an ignored WS token without the scanner (lalr_fast._lexing):
    the same AST and every position, line ends and tabs included."""
    fast, plain = _both(text, "b.st")
    assert fast == plain
    assert _positions(fast) == _positions(plain)


def test_no_terminal_but_ws_starts_with_a_blank():
    """What the blank skip relies on: where WS matches, no other terminal of the
    grammar can (each is tried on every blank followed by text of every kind)."""
    import re

    lark = st_parser.grammar().lark
    blanks = " \t\f\r\n\ufeff"
    after = ["x", "1", "%IX0.1", ":=", "(*c*)", "'s'", "OF", "AT %Q", " ", "\n", "#", "..", ";", ""]
    others = [t for t in lark.terminals if t.name != "WS"]
    assert len(others) > 100
    for terminal in others:
        pattern = re.compile(terminal.pattern.to_regexp(), re.IGNORECASE if "i" in terminal.pattern.flags else 0)
        for blank in blanks:
            for rest in after:
                assert pattern.match(blank + rest) is None, (terminal.name, blank + rest)


def _fields(token) -> tuple:
    return (token.type, str(token), token.start_pos, token.line, token.column,
            token.end_line, token.end_column, token.end_pos)


@pytest.mark.parametrize("path", FILES[::7], ids=lambda p: str(p.relative_to(ROOT)))
def test_fast_loop_makes_the_tokens_of_larks_lexer(path: Path):
    """Every token of the fast loop (its line, column and end worked out when read,
    lalr_fast._Token) has the fields of the token Lark's own lexer makes in its loop."""
    text = path.read_text(encoding="utf-8", errors="replace")
    grammar = st_parser.grammar()
    fast = grammar.fast
    made = []

    def record(token):
        made.append(_fields(grammar.retype(token)))
        return token

    retype, retyped = fast.retype, fast.retyped
    fast.retype, fast.retyped = record, {t for row in fast.states.values() for t in row}
    try:
        grammar.reset_builder(path.name)
        tree = fast.parse(text, "start")
    finally:
        fast.retype, fast.retyped = retype, retyped
    if tree is FAILED:
        pytest.skip("a syntax error: Lark's loop parses it")
    grammar.reset_builder(path.name)
    lark_tokens = [_fields(t) for t in grammar.lark.parse_interactive(text, start="start").iter_parse()]
    assert made and made == lark_tokens


def test_a_token_is_pickled_as_larks_own():
    import pickle

    from lark import Token

    from st_runtime.lalr_fast import _Lines, _Token

    text = "x\n  ab := 1;"
    token = str.__new__(_Token, "ab")
    token.type, token.start_pos, token.value, token.lines = "IDENT", 4, "ab", _Lines(text)
    assert (token.line, token.column, token.end_line, token.end_column, token.end_pos) == (2, 3, 2, 5, 6)
    copy = pickle.loads(pickle.dumps(token))
    assert type(copy) is Token and _fields(copy) == _fields(token)


def test_every_lexer_state_has_the_fast_scanner():
    """Each state's lexer is one the loop scans with its blanks (lalr_fast._blanks_and_scanner),
    and the pattern it builds is the one Lark's own Scanner builds for that lexer."""
    from lark.lexer import _create_unless

    from st_runtime.lalr_fast import scanner_pattern

    fast = st_parser.grammar().fast
    for state in fast.states:
        fast._scanner(state)
    for lexer in {id(fast.lexers[s]): fast.lexers[s] for s in fast.states}.values():
        terminals, _ = _create_unless(lexer.terminals, lexer.g_regex_flags, lexer.re, lexer.use_bytes)
        assert [p.pattern for p in lexer.scanner._mres] == [scanner_pattern(terminals)]


def _may_match_a_line_end(items) -> bool:
    """Whether a parsed pattern (re._parser) has a character that may match '\n'
    (conservative: `.` and every class of categories but digits and words count)."""
    from re import _constants as c

    never = {c.CATEGORY_DIGIT, c.CATEGORY_WORD, c.CATEGORY_NOT_SPACE, c.CATEGORY_NOT_LINEBREAK,
             c.CATEGORY_UNI_DIGIT, c.CATEGORY_UNI_WORD, c.CATEGORY_UNI_NOT_SPACE, c.CATEGORY_UNI_NOT_LINEBREAK}

    def in_class(members) -> bool:
        negate = bool(members) and members[0][0] is c.NEGATE
        hit = any(op is c.LITERAL and arg == 10 or op is c.RANGE and arg[0] <= 10 <= arg[1]
                  or op is c.CATEGORY and arg not in never for op, arg in members)
        return hit != negate

    for op, arg in items:
        if (op is c.LITERAL and arg == 10 or op is c.NOT_LITERAL and arg != 10 or op is c.ANY
                or op is c.IN and in_class(arg) or op is c.CATEGORY and arg not in never
                or op is c.SUBPATTERN and _may_match_a_line_end(arg[3])
                or op in (c.MAX_REPEAT, c.MIN_REPEAT, c.POSSESSIVE_REPEAT) and _may_match_a_line_end(arg[2])
                or op is c.BRANCH and any(_may_match_a_line_end(b) for b in arg[1])
                or op is c.ATOMIC_GROUP and _may_match_a_line_end(arg)):
            return True
    return False


def test_only_larks_newline_terminals_can_hold_a_line_end():
    """Lark counts lines only in the tokens of terminals whose pattern looks as if it
    may hold a '\n' (`newline_types`); the fast loop counts every '\n' of the text
    (lalr_fast._Lines).  The same lines, since no other terminal can match one."""
    import re
    from re import _parser

    from lark.lexer import _regexp_has_newline      # Lark's look at a pattern (BasicLexer)

    grammar = st_parser.grammar()
    newline_types = {t.name for t in grammar.lark.terminals if _regexp_has_newline(t.pattern.to_regexp())}
    assert {"WS", "COMMENT", "SSTRING"} <= newline_types
    assert _may_match_a_line_end(_parser.parse("a|[^x]")) and not _may_match_a_line_end(_parser.parse(r"[A-Z_]\w*"))
    others = [t for t in grammar.lark.terminals if t.name not in newline_types]
    assert len(others) > 100
    for terminal in others:
        regexp = terminal.pattern.to_regexp()
        assert not _may_match_a_line_end(_parser.parse(regexp)), terminal.name
        assert not re.search("\n", terminal.pattern.value), terminal.name


def test_a_token_no_rule_keeps_is_never_read():
    """The loop makes no Token of a terminal that every rule's child filter leaves out
    (lalr_fast.FastLalr._unkept: `:=`, `:`, `END_VAR`, ...): with a Token made for
    every terminal, as Lark's lexer does, the ASTs and their positions are the same."""
    fast = st_parser.grammar().fast
    assert {"_ASSIGN", "_COLON", "_END_VAR", "_END_PROGRAM", "_LPAR"} <= fast.unkept
    assert not {"IDENT", "PROGRAM", "INT"} & fast.unkept    # (kept: names, positions, values)
    for path in FILES[::5]:
        text = path.read_text(encoding="utf-8", errors="replace")
        lean = st_parser.parse(text, path.name)
        unkept = fast.unkept
        fast.unkept = frozenset()
        fast.unread_beside = None        # (worked out again from `unkept` on the next parse)
        try:
            full = st_parser.parse(text, path.name)
        finally:
            fast.unkept, fast.unread_beside = unkept, None
        assert lean == full and _positions(lean) == _positions(full), path


@pytest.mark.parametrize("text", ["0", "7", "007", "42", "1234567890123456789", "9" * 19, "9" * 20,
                                  "18446744073709551616", "1_000", "0_7", "9" * 40, "1" + "0" * 39])
def test_plain_digits_are_the_integer_decode_int_gives(text):
    """`AstBuilder.int_literal` reads plain digits itself: the value (or the diagnostic, for a
    literal too long) is decode_int's, as the general way gives it."""
    from st_runtime.literals import LiteralError, decode_int

    source = f"PROGRAM P\nVAR x : LREAL; END_VAR\nx := {text};\nEND_PROGRAM\n"
    parsed, diagnostics = st_parser.parse(source, "t.st")
    try:
        expected, refused = decode_int(text), False
    except LiteralError:
        expected, refused = 0, True
    assert [(d.pos.line, d.pos.col) for d in diagnostics] == ([(3, 6)] if refused else [])
    if not refused:
        literal = parsed.items[0].body[0].value
        assert type(literal.value) is int and literal.value == expected


def test_a_table_that_shifts_at_the_end_is_refused():
    """The loop shifts without asking whether the token is the end of the input
    (Lark's loop asserts it is not): the action table of a state that would shift
    $END is refused when it is made, so such a parse falls back to Lark's loop."""
    from types import SimpleNamespace

    from lark.parsers.lalr_analysis import Shift

    from st_runtime.lalr_fast import _Actions

    fake = SimpleNamespace(states={0: {"IDENT": (Shift, 1)}, 1: {"$END": (Shift, 0)}},
                           _step=lambda rule: rule)
    actions = _Actions(fake)
    assert actions[0] == {"IDENT": (Shift, 1)}     # (a shift of a token: kept as it is)
    with pytest.raises(ValueError):
        actions[1]
    assert 1 not in actions                         # (not kept: asked again, refused again)
    # The grammar's own tables never shift the end; its accepting states have no action.
    fast = st_parser.grammar().fast
    assert all(fast.states[state] == {} for state in fast.end_states.values())
    assert not any(row.get("$END", (None,))[0] is Shift for row in fast.states.values())


@pytest.mark.parametrize("text", [
    "PROGRAM P END_PROGRAM PROGRAM",          # a complete file, then a token: not accepted
    "PROGRAM P END_PROGRAM END_PROGRAM",
    "PROGRAM P",                              # the end before the file is complete
    "x := 1; y",
])
def test_the_end_is_accepted_only_in_the_accepting_state(text: str):
    """The loop accepts where its state's table has no action for the end (a KeyError,
    lalr_fast.FastLalr._parse): only in the accepting state with the end as the token;
    any other missing action, or the end elsewhere, is a syntax error (FAILED)."""
    fast = st_parser.grammar().fast
    for start in ("start", "stmt_list"):
        st_parser.grammar().reset_builder("e.st")
        assert fast.parse(text, start) is FAILED
    st_parser.grammar().reset_builder("e.st")
    assert fast.parse("PROGRAM P END_PROGRAM", "start") is not FAILED
    st_parser.grammar().reset_builder("e.st")
    assert fast.parse("x := 1;", "stmt_list") is not FAILED

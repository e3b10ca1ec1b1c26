"""Parse Structured Text into the AST, or into diagnostics worth reading.

    file, diagnostics = parse(text, "motion.st")
    statements, diagnostics = parse_body(text, "Main.body.st")   # a POU body alone

`parse` never raises.  The fast path is Lark's LALR parser with the contextual
lexer and the AST builder as its in-parser transformer (no parse tree).  Only
when that fails does `recovery.py` re-read the text token by token to report
each fault once, with what was expected and what was found.

Keywords are reserved everywhere: the lexer turns an identifier that spells a
keyword (in any case) into the keyword, so `VAR if : INT;` is a syntax error
rather than a variable named `if`.  The lexer also offers an identifier in
every parser state, so that `IFX` is one identifier, never `IF` + `X`.
"""

from __future__ import annotations

import os
import threading

from lark.lark import PostLex

from . import ast
from .ast_builder import AstBuilder
from .diagnostics import Diagnostic, register
from .grammar_cache import cached_lark
from .lalr_fast import FAILED, FastLalr

GRAMMAR_PATH = os.path.join(os.path.dirname(__file__), "grammar.lark")

CODES = register({
    "E-PARSE-001": "syntax error: the token found cannot continue the program here",
    "E-PARSE-002": "missing ';' at the end of a statement or declaration",
    "E-PARSE-003": "a block (IF, CASE, FOR, WHILE, REPEAT, VAR, POU, ...) is not closed",
    "E-PARSE-004": "an expression was expected",
    "E-PARSE-005": "unterminated comment or pragma",
    "E-PARSE-006": "unterminated string literal",
    "E-PARSE-007": "a character that cannot appear in Structured Text",
    "E-PARSE-008": "the file ends in the middle of a declaration or statement",
    "E-PARSE-009": "a literal with no valid value (digits, units or escapes)",
    "E-PARSE-010": "a statement in a CASE before its first label",
    "E-PARSE-011": "a VAR block other than VAR_GLOBAL outside a POU",
    "E-PARSE-012": "an unknown TASK parameter",
    "E-PARSE-013": "too many syntax errors: the rest of the file was not read",
    "E-PARSE-014": "an SFC action association with an unknown qualifier, a missing duration (L, D, SD, DS, SL) or extra arguments",
    "E-PARSE-099": "internal parser error (a bug: please report it)",
})


class _Postlex(PostLex):
    """Lets the contextual lexer see identifiers in every state (see module doc).

    Lark retypes an identifier that spells a keyword terminal before any
    callback runs, so the test-file keywords become identifiers again here
    unless a test file is being parsed.
    """

    always_accept = ("IDENT",)

    def __init__(self, grammar: "_Grammar"):
        self.grammar = grammar

    def process(self, stream):
        for token in stream:
            yield self.grammar.retype(token)


class _Grammar:
    """The Lark parser and its builder, built once per process."""

    def __init__(self) -> None:
        with open(GRAMMAR_PATH, encoding="utf-8") as handle:
            grammar = handle.read()
        self.builder = AstBuilder()
        # (Lark's v_args wraps each public method: fetched once, not on every parse)
        self.reset_builder = self.builder.reset
        every_keyword = _keyword_terminals(grammar)
        self.keywords = {w: k for w, k in every_keyword.items() if w not in TEST_KEYWORDS}
        self.test_keywords = every_keyword
        self.contextual = _contextual_terminals(grammar)
        self.active = self.keywords          # parse_tests swaps in test_keywords
        self._fast: FastLalr | None = None

        def reserve_keywords(token):     # (lalr_fast does the same inline: keep them alike)
            kind = self.active.get(token.value.upper())
            if kind is not None:
                token.type = kind
            return token

        self.reserve_keywords = reserve_keywords

        self.lark = cached_lark(         # tables kept in the user cache (grammar_cache.py)
            grammar,
            dict(parser="lalr", lexer="contextual", maybe_placeholders=True,
                 start=["start", "stmt_list", "test_file"]),
            dict(transformer=self.builder, postlex=_Postlex(self),
                 lexer_callbacks={"IDENT": reserve_keywords}),
        )

    @property
    def fast(self) -> FastLalr:
        if self._fast is None:
            self._fast = FastLalr(self.lark, self.retype, TEST_TERMINALS,   # (retype changes no other)
                                  keywords=(self.reserve_keywords, lambda: self.active))
        return self._fast

    def retype(self, token):
        """The token, an identifier again if it spells a test keyword outside a test file."""
        if token.type in TEST_TERMINALS and self.active is not self.test_keywords:
            token.type = "IDENT"
        return token


# Reserved only in test files (grammar.lark, block "test files").
TEST_KEYWORDS = frozenset({"TEST", "END_TEST", "SETUP", "END_SETUP", "TEARDOWN", "END_TEARDOWN"})
TEST_TERMINALS = frozenset({"TEST", "_END_TEST", "SETUP", "_END_SETUP", "TEARDOWN", "_END_TEARDOWN"})


def reserved_words() -> frozenset[str]:
    """The keywords of the grammar, upper case: a name spelled like one (any case) is never an identifier."""
    global _reserved
    if _reserved is None:
        with open(GRAMMAR_PATH, encoding="utf-8") as handle:
            _reserved = frozenset(_keyword_terminals(handle.read()))
    return _reserved


_reserved: frozenset[str] | None = None


def _contextual_terminals(grammar: str) -> frozenset[str]:
    """Terminals written `NAME.2: /WORD\\b/i`: keywords only where the parser takes them
    (`STEP` in a chart, `GET` in a PROPERTY); elsewhere the word is an identifier."""
    found = set()
    for line in grammar.splitlines():
        name, sep, rest = line.partition(":")
        rest = rest.strip()
        if sep and "." in name and rest.startswith("/") and rest.endswith("\\b/i"):
            found.add(name.split(".")[0].strip())
    return frozenset(found)


def _keyword_terminals(grammar: str) -> dict[str, str]:
    """Upper-case keyword -> terminal name, from lines `NAME: "WORD"i`."""
    result = {}
    for line in grammar.splitlines():
        name, sep, rest = line.partition(":")
        rest = rest.strip()
        if sep and rest.endswith('"i') and rest.startswith('"'):
            word = rest[1:-2]
            if word.replace("_", "").isalpha():
                result[word.upper()] = name.strip()
    return result


_grammar: _Grammar | None = None
_lock = threading.RLock()


def grammar() -> _Grammar:
    global _grammar
    if _grammar is None:
        with _lock:
            if _grammar is None:
                _grammar = _Grammar()
    return _grammar


def parse(text: str, path: str) -> tuple[ast.SourceFile | None, list[Diagnostic]]:
    """Parse one file.  Returns (AST, []) or (None, diagnostics); never raises."""
    return _guarded(text, path, "start", "parse")


def parse_body(text: str, path: str) -> tuple[tuple[ast.Stmt, ...] | None, list[Diagnostic]]:
    """Parse a POU body alone (statements only, as Sysmac Studio stores it).

    Returns (statements, []) or (None, diagnostics); never raises.
    """
    return _guarded(text, path, "stmt_list", "parse_body")


def parse_tests(text: str, path: str) -> tuple[ast.SourceFile | None, list[Diagnostic]]:
    """Parse a test file (POUs plus SETUP, TEARDOWN and TEST blocks); never raises.

    TEST, SETUP, TEARDOWN and their END_ keywords are reserved only here.
    """
    return _guarded(text, path, "test_file", "parse_tests")


def _guarded(text: str, path: str, start: str, caller: str):
    try:
        if not isinstance(text, str):
            raise TypeError(f"{caller}() needs str, not {type(text).__name__}")
        with _lock:
            return _parse(text, path) if start == "start" else _parse(text, path, start)
    except Exception as exc:  # the promise: no traceback for any input
        return None, [Diagnostic("E-PARSE-099", f"internal parser error: "
                                 f"{type(exc).__name__}: {exc}", ast.Pos(path, 1, 1))]


def _parse(text: str, path: str, start: str = "start"):
    g = grammar()
    g.reset_builder(path)
    g.active = g.test_keywords if start == "test_file" else g.keywords
    try:
        return _parse_with(g, text, path, start)
    finally:
        g.active = g.keywords


def _parse_with(g: _Grammar, text: str, path: str, start: str):
    tree = g.fast.parse(text, start)      # Lark's tables and callbacks, a tighter loop
    if tree is FAILED:                   # a syntax error (or anything): Lark's own parser again
        g.reset_builder(path)
        try:
            tree = g.lark.parse(text, start=start)
        except RecursionError:
            raise
        except Exception:
            return _diagnosed(g, text, path, start)
    if g.builder.errors:
        return None, list(g.builder.errors)
    return tree, []


def _diagnosed(g: _Grammar, text: str, path: str, start: str):
    from .recovery import diagnose

    diagnostics = diagnose(g, text, path, start)
    if not diagnostics:  # should not happen: keep the promise of a diagnostic
        diagnostics = [Diagnostic("E-PARSE-001", "syntax error", ast.Pos(path, 1, 1))]
    return None, diagnostics

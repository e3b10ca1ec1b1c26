"""Syntax-error reporting with recovery: one fault, one diagnostic.

Runs only after the fast parse failed.  The text is lexed once with a basic
lexer (lexical faults: unterminated comments and strings, stray characters),
then the tokens are fed to the LALR parser one by one, without building an
AST.  At each fault the first repair that lets the parser read the next few
tokens is applied, in this order:

1. insert the missing `;`;
2. insert a missing closing keyword or bracket (END_IF, END_VAR, `)`, ...);
3. delete the stray token;
4. replace the token by one the parser expects (`=` -> `:=`);
5. insert a placeholder identifier (a missing expression or name) or another
   expected keyword (THEN, DO, OF, ...);
6. panic mode: drop the open statement (pop the parser stack back to a state
   that starts statements) and skip to the next `;` or block keyword.

The report names what was expected and what was found; a fault's repair is
quiet, and faults within a few tokens of the previous one are not reported,
so one typo gives one error rather than a cascade.
"""

from __future__ import annotations

from copy import copy

from lark import Token
from lark.exceptions import UnexpectedCharacters, UnexpectedToken
from lark.lexer import LexerState

from . import ast
from .ast_builder import AstBuilder
from .diagnostics import Diagnostic

try:  # Lark >= 1.2 wraps the text in a TextSlice
    from lark.utils import TextSlice
except ImportError:  # pragma: no cover
    TextSlice = None

LOOKAHEAD = 4          # tokens a resynchronisation must let the parser read
SCORE_LOOKAHEAD = 10    # tokens over which candidate repairs are compared
QUIET = 3              # tokens after a repair during which faults are not reported
MAX_ERRORS = 25
PANIC_REACH = 400      # tokens panic mode may skip before it gives up on a fault

_CLOSERS = (
    "_END_IF", "_END_CASE", "_END_FOR", "_END_WHILE", "_END_REPEAT", "_END_VAR",
    "_END_STRUCT", "_END_TYPE", "_END_PROGRAM", "_END_FUNCTION", "_END_FUNCTION_BLOCK",
    "_END_CONFIGURATION", "_END_RESOURCE", "_RPAR", "_RSQB",
)
_OPENERS = {
    "_END_IF": ("IF",), "_END_CASE": ("CASE",), "_END_FOR": ("FOR",),
    "_END_WHILE": ("WHILE",), "_END_REPEAT": ("REPEAT",), "_END_STRUCT": ("STRUCT",),
    "_END_PROGRAM": ("PROGRAM",), "_END_FUNCTION": ("FUNCTION",),
    "_END_FUNCTION_BLOCK": ("FUNCTION_BLOCK",), "_END_CONFIGURATION": ("CONFIGURATION",),
    "_END_RESOURCE": ("RESOURCE",),
    "_END_VAR": ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_TEMP", "VAR_GLOBAL",
                 "VAR_EXTERNAL"),
}
_REPLACEMENTS = ("_ASSIGN", "_THEN", "_DO", "_OF", "_COLON", "_TO", "_SEMI", "_RPAR",
                 "_RSQB", "_COMMA", "IDENT")
_POU_OPENERS = {"_END_PROGRAM": "PROGRAM", "_END_FUNCTION_BLOCK": "FUNCTION_BLOCK",
                "_END_FUNCTION": "FUNCTION"}
_RETREAT_INSERTIONS = ("_END_VAR", "VAR")
_INSERTIONS = ("IDENT", "_THEN", "_DO", "_OF", "_TO", "_ASSIGN", "_COLON", "_LPAR")
_SYNC_KEYWORDS = frozenset(_CLOSERS[:-2]) | {"_ELSE", "ELSIF", "_UNTIL"}
_STATEMENT_STARTS = frozenset({"IF", "CASE", "FOR", "WHILE", "REPEAT", "EXIT", "CONTINUE",
                               "RETURN", "IDENT"})
_BINARY_OPERATORS = frozenset({"AMP", "AND", "OR", "XOR", "EQ", "NE", "LT", "GT", "LE", "GE",
                               "PLUS", "MINUS", "STAR", "SLASH", "MOD", "POW"})
_AFTER_STATEMENT_NAME = {"_ASSIGN", "_LPAR", "_DOT", "_LSQB"}
_EXPRESSION_STARTS = frozenset({
    "IDENT", "INT", "BASED_INT", "REAL_NUMBER", "TIME_LIT", "DATE_LIT", "TOD_LIT",
    "DT_LIT", "TYPED_LIT", "SSTRING", "DSTRING", "TRUE", "FALSE", "MINUS", "PLUS", "NOT",
})
_NAMES = {
    "IDENT": "identifier", "INT": "integer", "BASED_INT": "based integer",
    "REAL_NUMBER": "real number", "TIME_LIT": "TIME literal", "DATE_LIT": "DATE literal",
    "TOD_LIT": "TIME_OF_DAY literal", "DT_LIT": "DATE_AND_TIME literal",
    "TYPED_LIT": "typed literal", "SSTRING": "string", "DSTRING": "wide string",
    "$END": "end of file",
}


class _Lexed:
    def __init__(self) -> None:
        self.tokens: list[Token] = []
        self.diagnostics: list[Diagnostic] = []
        self.truncated = False   # an unterminated comment/string swallowed the rest
        self.after_bad: set[int] = set()  # tokens right after a stray character


def diagnose(grammar, text: str, path: str) -> list[Diagnostic]:
    """The diagnostics for a text that the fast parse rejected."""
    lexed = _lex(grammar, text, path)
    literal_errors = _literal_errors(lexed.tokens, path)
    recovery = _Recovery(grammar, lexed.tokens, text, path)
    recovery.silent = lexed.after_bad
    syntax = recovery.run(report_eof=not lexed.truncated)
    merged = sorted(lexed.diagnostics + literal_errors + syntax, key=lambda d: (d.pos.line, d.pos.col))
    if len(merged) > MAX_ERRORS + 1:
        merged = merged[:MAX_ERRORS] + [Diagnostic(
            "E-PARSE-013", "too many syntax errors; the rest of the file was not checked",
            merged[MAX_ERRORS].pos)]
    return merged


_LITERAL_RULES = {
    "INT": "int_literal", "BASED_INT": "based_literal", "REAL_NUMBER": "real_literal",
    "TIME_LIT": "time_literal", "DATE_LIT": "date_literal", "TOD_LIT": "tod_literal",
    "DT_LIT": "dt_literal", "TYPED_LIT": "typed_literal", "SSTRING": "string_literal",
    "DSTRING": "wstring_literal",
}


def _literal_errors(tokens, path: str) -> list[Diagnostic]:
    """Invalid literals: the AST builder's checks, run on the tokens alone."""
    builder = AstBuilder()
    builder.reset(path)
    for token in tokens:
        rule = _LITERAL_RULES.get(token.type)
        if rule is not None:
            getattr(builder, rule)(token)
    return builder.errors


# ------------------------------------------------------------------- lexing


def _lex(grammar, text: str, path: str) -> _Lexed:
    result = _Lexed()
    lexer = grammar.lark._build_lexer()
    state = LexerState(TextSlice.cast_from(text) if TextSlice else text)
    previous = None
    bad_run_end = -1
    while True:
        try:
            token = lexer.next_token(state)
        except EOFError:
            break
        except UnexpectedCharacters as exc:
            pos = ast.Pos(path, exc.line, exc.column)
            char = text[exc.pos_in_stream]
            if char in "'\"":
                kind = "string" if char == "'" else "wide string"
                result.diagnostics.append(Diagnostic(
                    "E-PARSE-006", f"unterminated {kind}: no closing {char} before the end "
                    "of the file", pos))
                result.truncated = True
                break
            if exc.pos_in_stream != bad_run_end:
                shown = char if char.isprintable() else f"U+{ord(char):04X}"
                result.diagnostics.append(Diagnostic(
                    "E-PARSE-007", f"unexpected character '{shown}'", pos))
            state.line_ctr.feed(char)
            bad_run_end = exc.pos_in_stream + 1
            result.after_bad.add(len(result.tokens))
            if len(result.diagnostics) > MAX_ERRORS:
                break
            continue
        if (previous is not None and token.type == "STAR"
                and previous.type in ("_LPAR", "SLASH")
                and previous.end_pos == token.start_pos):
            opener = "(*" if previous.type == "_LPAR" else "/*"
            closer = "*)" if opener == "(*" else "*/"
            result.diagnostics.append(Diagnostic(
                "E-PARSE-005", f"unterminated comment: '{opener}' has no closing '{closer}'",
                ast.Pos(path, previous.line, previous.column)))
            result.tokens.pop()
            result.truncated = True
            break
        result.tokens.append(token)
        previous = token
    return result


# ----------------------------------------------------------------- parsing


class _Recovery:
    def __init__(self, grammar, tokens: list[Token], text: str, path: str) -> None:
        self.grammar = grammar
        self.tokens = tokens
        self.text = text
        self.path = path
        self.terminals = grammar.lark._terminals_dict
        self.diagnostics: list[Diagnostic] = []
        self.silent: set[int] = set()
        self.report_eof = True
        self.consumed = -1
        self.retreat_token = None
        lines = text.count("\n") + 1
        last_newline = text.rfind("\n")
        if tokens:  # point just past the last token, on a line that exists
            last = tokens[-1]
            self.eof = Token("$END", "", last.end_pos, last.end_line, last.end_column)
        else:
            self.eof = Token("$END", "", len(text), lines, len(text) - last_newline)

    def _token(self, i: int) -> Token:
        return self.tokens[i] if i < len(self.tokens) else self.eof

    def _fresh_state(self):
        interactive = self.grammar.lark.parse_interactive("")
        state = interactive.parser_state
        conf = copy(state.parse_conf)
        conf.callbacks = {}   # syntax only: no AST while recovering
        state.parse_conf = conf
        return state

    def _expected(self, state, candidates) -> set[str]:
        """The terminals the parser can really shift now.

        LALR merges states, so the failing state's table lists terminals that
        only other contexts accept; try each one on a copy.
        """
        result = set()
        for kind in candidates:
            trial = state.copy(deepcopy_values=False)
            try:
                self._feed(trial, Token(kind, ""))
            except (UnexpectedToken, IndexError, AssertionError):
                continue
            result.add(kind)
        return result or set(candidates)

    @staticmethod
    def _feed(state, token: Token):
        return state.feed_token(token, token.type == "$END")

    def _accepts_run(self, state, inserted: list[Token], start: int, limit: int = LOOKAHEAD,
                     early_stop: bool = True):
        """Feed `inserted` then up to `limit` tokens from `start` into a copy.

        Returns (new state, next index, finished), or None if the parser
        rejects; `self.consumed` tells how many tokens it read before that.
        """
        trial = state.copy(deepcopy_values=False)
        self.consumed = -1
        try:
            for token in inserted:
                self._feed(trial, token)
            self.consumed = 0
            i = start
            for _ in range(limit):
                token = self._token(i)
                if token.type == "$END" and not self.report_eof:
                    return trial, i, False   # the text was cut short by a lexical fault
                self._feed(trial, token)
                if token.type == "$END":
                    return trial, i, True
                i += 1
                self.consumed += 1
                if early_stop and token.type == "_SEMI" and self.consumed + len(inserted) >= 2:
                    break   # a whole statement fits: the next one may have its own fault
            return trial, i, False
        except UnexpectedToken:
            return None

    def _make(self, kind: str, like: Token) -> Token:
        value = {"IDENT": "_"}.get(kind)
        if value is None:
            term = self.terminals.get(kind)
            value = getattr(term.pattern, "value", kind) if term else kind
        return Token.new_borrow_pos(kind, value, like)

    def run(self, report_eof: bool = True) -> list[Diagnostic]:
        self.report_eof = report_eof
        state = self._fresh_state()
        i = 0
        quiet_until = -1
        steps = 0
        limit = 4 * (len(self.tokens) + 10)
        while steps < limit:
            steps += 1
            token = self._token(i)
            # LALR may reduce before it notices a fault; keep the state from
            # before this token so that expectations and repairs start there.
            before = state.copy(deepcopy_values=False)
            if steps == 1:
                previous = None
            try:
                self._feed(state, token)
            except UnexpectedToken:
                state = before
                table = state.parse_conf.states[state.position]
                expected = self._expected(state, [k for k in table if k.isupper()])
                if token.type == "$END" and not report_eof:
                    break
                repaired = self._repair(state, i, expected, previous)
                previous = None
                if repaired is None:
                    repaired = ("none", [], state, i, True)
                kind, inserted, repaired_state, next_i, finished = repaired
                if (i >= quiet_until or not self.diagnostics) and i not in self.silent:
                    self._report(kind, token, inserted, expected, state)
                    if len(self.diagnostics) >= MAX_ERRORS:
                        self.diagnostics.append(Diagnostic(
                            "E-PARSE-013", "too many syntax errors; the rest of the file "
                            "was not checked", ast.Pos(self.path, token.line, token.column)))
                        break
                self.retreat_token = None
                # A repair checked on the next tokens needs no quiet time; a token
                # dropped blindly does (what follows is likely debris).
                quiet_until = next_i + (QUIET if kind == "drop" else 0)
                state, i = repaired_state, next_i
                if finished:
                    break
                continue
            if token.type == "$END":
                break
            previous = (i, before)
            i += 1
        return self.diagnostics

    # --------------------------------------------------------------- repairs

    def _repair(self, state, i: int, expected: set[str], previous=None):
        """Choose the repair that lets the parser read furthest.

        Each candidate is tried on a copy over the next SCORE_LOOKAHEAD
        tokens; the one that reads most wins (earlier candidates on ties).
        A candidate stopped by a second fault is taken up to that fault, so
        that fault is reported in its turn.
        """
        token = self._token(i)
        candidates = []   # (kind, inserted tokens, base state, resume index)
        if "_SEMI" in expected:
            candidates.append(("semi", [self._make("_SEMI", token)], state, i))
        for closer in _CLOSERS:
            if closer in expected:
                candidates.append(("close", [self._make(closer, token)], state, i))
                candidates.append(("close", [self._make(closer, token),
                                             self._make("_SEMI", token)], state, i))
        if token.type != "$END":
            candidates.append(("delete", [], state, i + 1))
            for kind in _REPLACEMENTS:
                if kind in expected:
                    candidates.append(("replace", [self._make(kind, token)], state, i + 1))
        for kind in _INSERTIONS:
            if kind in expected:
                candidates.append(("insert", [self._make(kind, token)], state, i))
        if "_COLON" in expected and token.type != "_ASSIGN":  # FUNCTION F without `: type`
            candidates.append(("insert", [self._make("_COLON", token),
                                          self._make("IDENT", token)], state, i))
        if token.type == "IDENT" and "PROGRAM" in expected:
            # `Main VAR ...` with its PROGRAM keyword lost: the POU's END_xxx
            # further on says which keyword it was.
            for later in self.tokens[i + 1:]:
                opener = _POU_OPENERS.get(later.type)
                if opener is not None:
                    candidates.append(("insert", [self._make(opener, token)], state, i))
                    break
        following = self._token(i + 1)
        if token.type != "$END" and following.type != "$END":
            candidates.append(("swap", [following, token], state, i + 2))
        if previous is not None:
            # The fault may lie before the previous token: `x : INT;` with no
            # VAR before it, or a statement after a VAR block never closed.
            back, back_state = previous
            table = back_state.parse_conf.states[back_state.position]
            for kind in _RETREAT_INSERTIONS:
                if kind in table:
                    where = self._token(back)
                    closing = "close" if kind.startswith("_END") else "open"
                    candidates.append((closing, [self._make(kind, where)], back_state, back))

        best = None
        best_score = 0
        for kind, inserted, base, start in candidates:
            outcome = self._accepts_run(base, inserted, start, SCORE_LOOKAHEAD, early_stop=False)
            score = SCORE_LOOKAHEAD + 1 if outcome is not None else self.consumed
            if score > best_score:
                best, best_score = (kind, inserted, base, start, outcome), score
        if best is not None and best_score >= 2:
            return self._apply(best, best_score, i)
        panic = self._panic(state, i)
        if panic is not None and panic[0] == "drop" and best is not None:
            return self._apply(best, best_score, i)
        return panic

    def _apply(self, best, score, fault: int):
        kind, inserted, base, start, outcome = best
        if outcome is None:  # stopped by the next fault: read up to it
            outcome = self._accepts_run(base, inserted, start, score, early_stop=False)
        trial, nxt, finished = outcome
        if start < fault:   # the repair went back before the faulty token
            self.retreat_token = self._token(start)
        return kind, inserted, trial, nxt, finished

    def _panic(self, state, i: int):
        """Skip to the nearest point where the parser, with its open
        constructs closed back to some depth, can go on.

        Sync points, nearest first: the faulty token itself, a token after a
        `;`, a block keyword (END_xxx, ELSE, ...), the end of the file.  At
        each, the parser stack is popped as little as possible.
        """
        n = len(self.tokens)
        depth = len(state.state_stack)
        j = i
        while j <= min(n, i + PANIC_REACH):
            candidate = self._token(j)
            if (j == i or candidate.type in _SYNC_KEYWORDS or candidate.type == "$END"
                    or self._token(j - 1).type == "_SEMI"):
                for keep in range(depth, 0, -1):
                    if j == i and keep == depth:
                        continue  # the unchanged state already failed here
                    trial = state.copy(deepcopy_values=False)
                    del trial.state_stack[keep:]
                    del trial.value_stack[keep - 1:]
                    outcome = self._accepts_run(trial, [], j)
                    if outcome is not None and (self.consumed >= 2 or outcome[2]):
                        new_state, nxt, finished = outcome
                        return "panic", [], new_state, nxt, finished
            j += 1
        if self._token(i).type == "$END":
            return None
        # Nothing fits: drop the token and go on from the unchanged state.
        return "drop", [], state, i + 1, False

    # ------------------------------------------------------------- messages

    def _describe_token(self, token: Token) -> str:
        if token.type == "$END":
            return "end of file"
        if token.type in self.grammar.keywords.values():
            return f"keyword '{token.value}'"
        text = token.value if len(token.value) <= 30 else token.value[:27] + "..."
        return f"'{text}'"

    def _describe_kind(self, kind: str) -> str:
        if kind in _NAMES:
            return _NAMES[kind]
        term = self.terminals.get(kind)
        value = getattr(term.pattern, "value", None) if term else None
        if value is None:
            return kind.strip("_").lower()
        return f"'{value.upper() if value.isalpha() or '_' in value else value}'"

    def _expected_list(self, expected: set[str]) -> str:
        kinds = set(expected)
        first = []
        if "_SEMI" in kinds:
            kinds.discard("_SEMI")
            first.append("';'")
        if len(kinds & _STATEMENT_STARTS) > 4:
            kinds -= _STATEMENT_STARTS
            first.append("statement")
        if {"ARRAY", "STRING", "IDENT"} <= kinds:
            kinds -= {"ARRAY", "STRING", "WSTRING", "IDENT"}
            first.append("type")
        if len(kinds & _EXPRESSION_STARTS) > 3:
            kinds -= _EXPRESSION_STARTS | {"_LPAR"}
            first.append("expression")
        if len(kinds & _BINARY_OPERATORS) > 4:
            kinds -= _BINARY_OPERATORS
            first.append("operator")
        words = first + sorted(self._describe_kind(k) for k in kinds)
        if len(words) > 6:
            words = words[:6] + ["..."]
        if len(words) == 1:
            return words[0]
        return ", ".join(words[:-1]) + " or " + words[-1]

    def _opener_line(self, lark_state, closer: str) -> str:
        openers = _OPENERS.get(closer, ())
        for value in reversed(lark_state.value_stack if lark_state else []):
            if isinstance(value, list) and len(value) == 1:
                value = value[0]
            if isinstance(value, Token) and value.type in openers:
                return f" to close the {value.type} at line {value.line}"
        return ""

    def _in_declaration(self, lark_state) -> bool:
        for value in reversed(lark_state.value_stack if lark_state else []):
            if isinstance(value, list) and len(value) == 1:
                value = value[0]   # an inlined rule such as _var_kind
            if isinstance(value, Token) and value.type in _OPENERS["_END_VAR"] + ("STRUCT",):
                return True
            if isinstance(value, Token) and value.type in ("PROGRAM", "FUNCTION",
                                                          "FUNCTION_BLOCK"):
                return False
        return False

    def _report(self, kind, token, inserted, expected, lark_state) -> None:
        if self.retreat_token is not None:
            token = self.retreat_token   # the repair went back one token
        self.retreat_token = None
        found = self._describe_token(token)
        pos = ast.Pos(self.path, token.line, token.column)
        if kind == "semi":
            where = "declaration" if self._in_declaration(lark_state) else "statement"
            code, message = "E-PARSE-002", f"expected ';' after {where}, found {found}"
            previous = self._previous_token(token)
            if previous is not None:  # point just past the unfinished line
                pos = ast.Pos(self.path, previous.end_line, previous.end_column)
        elif kind == "open":
            code = "E-PARSE-001"
            message = (f"expected 'VAR' before {found}: declarations belong in a "
                       "VAR ... END_VAR block")
        elif kind == "close" and inserted[0].type.startswith("_END"):
            closer = self._describe_kind(inserted[0].type)
            code = "E-PARSE-003"
            message = (f"expected {closer}{self._opener_line(lark_state, inserted[0].type)}, "
                       f"found {found}")
        elif kind == "insert" and inserted[0].type != "IDENT":
            code = "E-PARSE-001"
            message = f"expected {self._describe_kind(inserted[0].type)}, found {found}"
            previous = self._previous_token(token)
            if previous is not None:
                pos = ast.Pos(self.path, previous.end_line, previous.end_column)
        elif (expected == _AFTER_STATEMENT_NAME and kind in ("panic", "drop", "none")
              and self._previous_token(token) is not None):
            name = self._previous_token(token)
            code = "E-PARSE-001"
            message = (f"expected ':=' or '(' after '{name.value}' (an assignment or a call), "
                       f"found {found}")
            pos = ast.Pos(self.path, name.line, name.column)
        elif kind == "close":
            code = "E-PARSE-001"
            message = f"expected {self._describe_kind(inserted[0].type)}, found {found}"
        elif token.type == "$END":
            code = "E-PARSE-008"
            message = f"unexpected end of file: expected {self._expected_list(expected)}"
        elif len(expected & _EXPRESSION_STARTS) > 3 and token.type not in _EXPRESSION_STARTS:
            code, message = "E-PARSE-004", f"expected expression, found {found}"
        else:
            code = "E-PARSE-001"
            message = f"expected {self._expected_list(expected)}, found {found}"
        self.diagnostics.append(Diagnostic(code, message, pos))

    def _previous_token(self, token: Token):
        for index, candidate in enumerate(self.tokens):
            if candidate is token:
                return self.tokens[index - 1] if index else None
        return self.tokens[-1] if token.type == "$END" and self.tokens else None

"""Syntax-error reporting with recovery: one fault, one diagnostic.

Runs only after the fast parse failed.  `token_scan` lexes the text once
(lexical faults: unterminated comments and strings, stray characters), then
the tokens are fed to the LALR parser one by one, without building an AST.
At a fault, candidate repairs are each tried on a copy of the parser over the
next SCORE_LOOKAHEAD tokens, and the one that reads furthest wins (the
earlier in this list on ties):

- insert the missing `;`; insert a missing END_xxx, `)` or `]`;
- delete the stray token; replace it by an expected one (`=` -> `:=`);
- insert an expected keyword (THEN, DO, OF, ...) or a placeholder name;
- swap the token with the next one;
- go back one token and open or close a VAR block there (`x : INT;` with no
  VAR, a statement after a VAR block that was never closed);
- restore a lost PROGRAM/FUNCTION_BLOCK keyword.

When none reads at least two tokens, panic mode skips to the nearest `;` or
block keyword and pops the parser stack as little as it must to go on there.
`syntax_messages` words the report from the repair chosen.  A repair that
stops at a second fault is taken up to it, so that fault is reported in its
turn; a token dropped blindly silences faults for a few tokens.
"""

from __future__ import annotations

from copy import copy

from lark import Token
from lark.exceptions import UnexpectedToken

from . import ast
from .diagnostics import Diagnostic
from .syntax_messages import Messages
from .token_scan import literal_errors, scan

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
_REPLACEMENTS = ("_ASSIGN", "_THEN", "_DO", "_OF", "_COLON", "_TO", "_SEMI", "_RPAR",
                 "_RSQB", "_COMMA", "IDENT")
_POU_OPENERS = {"_END_PROGRAM": "PROGRAM", "_END_FUNCTION_BLOCK": "FUNCTION_BLOCK",
                "_END_FUNCTION": "FUNCTION"}
_RETREAT_INSERTIONS = ("_END_VAR", "VAR")
_INSERTIONS = ("IDENT", "_THEN", "_DO", "_OF", "_TO", "_ASSIGN", "_COLON", "_LPAR")
_SYNC_KEYWORDS = frozenset(_CLOSERS[:-2]) | {"_ELSE", "ELSIF", "_UNTIL"}


def diagnose(grammar, text: str, path: str, start: str = "start") -> list[Diagnostic]:
    """The diagnostics for a text that the fast parse rejected."""
    lexed = scan(grammar, text, path)
    literal_faults = literal_errors(lexed.tokens, path)
    recovery = _Recovery(grammar, lexed.tokens, text, path)
    recovery.start = start
    recovery.silent = lexed.after_bad
    syntax = recovery.run(report_eof=not lexed.truncated)
    merged = sorted(lexed.diagnostics + literal_faults + syntax,
                    key=lambda d: (d.pos.line, d.pos.col))
    if len(merged) > MAX_ERRORS + 1:
        merged = merged[:MAX_ERRORS] + [Diagnostic(
            "E-PARSE-013", "too many syntax errors; the rest of the file was not checked",
            merged[MAX_ERRORS].pos)]
    return merged


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
        self.start = "start"
        self.consumed = -1
        self.retreat_token = None
        self.messages = Messages(grammar, tokens, path)
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
        interactive = self.grammar.lark.parse_interactive("", start=self.start)
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

    def _feed(self, state, token: Token):
        # The basic lexer used here makes `Step` the keyword STEP everywhere; the
        # parser's contextual lexer makes it one only where the state takes it.
        if token.type in self.grammar.contextual \
                and token.type not in state.parse_conf.states[state.position]:
            token = Token.new_borrow_pos("IDENT", token.value, token)
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
                    shown = self.retreat_token or token   # a repair may go back one token
                    self.diagnostics.append(
                        self.messages.compose(kind, shown, inserted, expected, state))
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

"""The words of a syntax error: what was expected, what was found.

`Messages.compose` turns a fault and the repair that recovery chose into a
diagnostic.  The repair tells most about the fault: an inserted `;` is a
missing `;` (E-PARSE-002), an inserted END_IF a block left open (E-PARSE-003,
naming the line that opened it), a parser state that wants an operand an
expected expression (E-PARSE-004).  Otherwise the message lists what the
parser could take (grouped: "statement", "expression", "operator", "type")
and what it found (the token, "keyword 'X'", or "end of file").
"""

from __future__ import annotations

import difflib

from lark import Token

from . import ast
from .diagnostics import Diagnostic

OPENERS = {
    "_END_IF": ("IF",), "_END_CASE": ("CASE",), "_END_FOR": ("FOR",),
    "_END_WHILE": ("WHILE",), "_END_REPEAT": ("REPEAT",), "_END_STRUCT": ("STRUCT",),
    "_END_PROGRAM": ("PROGRAM",), "_END_FUNCTION": ("FUNCTION",),
    "_END_FUNCTION_BLOCK": ("FUNCTION_BLOCK",), "_END_CONFIGURATION": ("CONFIGURATION",),
    "_END_RESOURCE": ("RESOURCE",),
    "_END_VAR": ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_TEMP", "VAR_GLOBAL",
                 "VAR_EXTERNAL"),
}
_STATEMENT_STARTS = frozenset({"IF", "CASE", "FOR", "WHILE", "REPEAT", "EXIT", "CONTINUE",
                               "RETURN", "IDENT"})
_BINARY_OPERATORS = frozenset({"AMP", "AND", "OR", "XOR", "EQ", "NE", "LT", "GT", "LE", "GE",
                               "PLUS", "MINUS", "STAR", "SLASH", "MOD", "POW"})
_AFTER_STATEMENT_NAME = {"_ASSIGN", "_LPAR", "_DOT", "_LSQB", "CARET", "SET_RESET"}   # (^ and S= / R=: issue 13)
_EXPRESSION_STARTS = frozenset({
    "IDENT", "INT", "BASED_INT", "REAL_NUMBER", "TIME_LIT", "DATE_LIT", "TOD_LIT",
    "DT_LIT", "TYPED_LIT", "SSTRING", "DSTRING", "TRUE", "FALSE", "MINUS", "PLUS", "NOT",
})
_NAMES = {
    "IDENT": "identifier", "INT": "integer", "BASED_INT": "based integer",
    "REAL_NUMBER": "real number", "TIME_LIT": "TIME literal", "DATE_LIT": "DATE literal",
    "TOD_LIT": "TIME_OF_DAY literal", "DT_LIT": "DATE_AND_TIME literal",
    "TYPED_LIT": "typed literal", "SSTRING": "string", "DSTRING": "wide string",
    "_AT": "'AT'", "_AT_ADDRESS": "'AT'", "SET_RESET": "'S=' or 'R='", "PARTIAL": "partial access (%X3, %B0)",
    "DIRECT_VAR": "direct address (%IX0.0, %QW3, %MD10, %I*)",
    "$END": "end of file",
}
GLUE = frozenset({"_THEN", "_DO", "_OF", "_TO", "_ASSIGN", "_COLON", "_LPAR"})


class Messages:
    def __init__(self, grammar, tokens: list[Token], path: str) -> None:
        self.grammar = grammar
        self.tokens = tokens
        self.path = path
        self.terminals = grammar.lark._terminals_dict
        self._index = {id(token): i for i, token in enumerate(tokens)}

    def describe_token(self, token: Token) -> str:
        if token.type == "$END":
            return "end of file"
        if token.type in self.grammar.keywords.values():
            return f"keyword '{token.value}'"
        text = token.value if len(token.value) <= 30 else token.value[:27] + "..."
        return f"'{text}'"

    def describe_kind(self, kind: str) -> str:
        if kind in _NAMES:
            return _NAMES[kind]
        term = self.terminals.get(kind)
        value = getattr(term.pattern, "value", None) if term else None
        if value is None:
            return kind.strip("_").lower()
        if kind.strip("_") in self.grammar.contextual or kind in self.grammar.contextual:
            value = value.removesuffix("\\b")         # /STEP\b/i: the word STEP
        return f"'{value.upper() if value.isalpha() or '_' in value else value}'"

    def expected_list(self, expected: set[str]) -> str:
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
        words = first + sorted({self.describe_kind(k) for k in kinds})   # _AT, _AT_ADDRESS: one 'AT'
        if len(words) > 6:
            words = words[:6] + ["..."]
        if len(words) == 1:
            return words[0]
        return ", ".join(words[:-1]) + " or " + words[-1]

    def opener_line(self, lark_state, closer: str) -> str:
        openers = OPENERS.get(closer, ())
        for value in reversed(lark_state.value_stack if lark_state else []):
            if isinstance(value, list) and len(value) == 1:
                value = value[0]
            if isinstance(value, Token) and value.type in openers:
                return f" to close the {value.type} at line {value.line}"
        return ""

    def in_declaration(self, lark_state) -> bool:
        for value in reversed(lark_state.value_stack if lark_state else []):
            if isinstance(value, list) and len(value) == 1:
                value = value[0]   # an inlined rule such as _var_kind
            if isinstance(value, Token) and value.type in OPENERS["_END_VAR"] + ("STRUCT",):
                return True
            if isinstance(value, Token) and value.type in ("PROGRAM", "FUNCTION",
                                                          "FUNCTION_BLOCK"):
                return False
        return False

    def compose(self, kind, token, inserted, expected, lark_state) -> Diagnostic:
        """The diagnostic for a fault at `token` repaired by `kind`."""
        found = self.describe_token(token)
        pos = ast.Pos(self.path, token.line, token.column)
        if kind == "semi":
            where = "declaration" if self.in_declaration(lark_state) else "statement"
            code, message = "E-PARSE-002", f"expected ';' after {where}, found {found}"
            previous = self._previous_token(token)
            if previous is not None:  # point just past the unfinished line
                pos = ast.Pos(self.path, previous.end_line, previous.end_column)
        elif kind == "open":
            code = "E-PARSE-001"
            message = (f"expected 'VAR' before {found}: declarations belong in a "
                       "VAR ... END_VAR block")
        elif kind == "close" and inserted[0].type.startswith("_END"):
            closer = self.describe_kind(inserted[0].type)
            code = "E-PARSE-003"
            message = (f"expected {closer}{self.opener_line(lark_state, inserted[0].type)}, "
                       f"found {found}")
        elif kind == "insert" and inserted[0].type != "IDENT":
            code = "E-PARSE-001"
            message = f"expected {self.describe_kind(inserted[0].type)}, found {found}"
            previous = self._previous_token(token)
            if previous is not None and inserted[0].type in GLUE:
                # THEN, DO, OF, ... belong right after what precedes them.
                pos = ast.Pos(self.path, previous.end_line, previous.end_column)
        elif (expected == _AFTER_STATEMENT_NAME and kind in ("panic", "drop", "none")
              and self._previous_token(token) is not None):
            name = self._previous_token(token)
            code = "E-PARSE-001"
            message = (f"expected ':=' or '(' after '{name.value}' (an assignment or a call), "
                       f"found {found}{self.keyword_hint(name.value)}")
            pos = ast.Pos(self.path, name.line, name.column)
        elif kind == "close":
            code = "E-PARSE-001"
            message = f"expected {self.describe_kind(inserted[0].type)}, found {found}"
        elif token.type == "$END":
            code = "E-PARSE-008"
            message = f"unexpected end of file: expected {self.expected_list(expected)}"
        elif len(expected & _EXPRESSION_STARTS) > 3 and token.type not in _EXPRESSION_STARTS:
            code, message = "E-PARSE-004", f"expected expression, found {found}"
        else:
            code = "E-PARSE-001"
            message = f"expected {self.expected_list(expected)}, found {found}"
        return Diagnostic(code, message, pos)

    def keyword_hint(self, word: str) -> str:
        """" (did you mean END_IF?)" when `word` is a misspelt keyword (ENDIF,
        END_FI, End_Fro); only keywords that end a block or start a
        statement are offered, the words a typo usually hides."""
        candidates = [k for k in self.grammar.keywords if k.startswith("END_") or k in _STATEMENT_STARTS]
        match = difflib.get_close_matches(word.upper(), candidates, n=1, cutoff=0.75)
        return f" (did you mean {match[0]}?)" if match else ""

    def _previous_token(self, token: Token):
        index = self._index.get(id(token))
        if index is None:
            return self.tokens[-1] if token.type == "$END" and self.tokens else None
        return self.tokens[index - 1] if index else None

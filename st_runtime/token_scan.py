"""Lexing a text that failed to parse, for the error report.

`scan` lexes the whole text with a basic lexer (the grammar's terminals, no
parser state) and reports lexical faults as it goes: a string with no closing
quote, a comment with no end (both at their opening), stray characters (one
diagnostic per run).  `literal_errors` runs the AST builder's literal checks
(`2#102`, `T#5x`, `'$Q'`) on the tokens, since no AST is built while
recovering.
"""

from __future__ import annotations

from lark import Token
from lark.exceptions import UnexpectedCharacters
from lark.lexer import LexerState

from . import ast
from .ast_builder import AstBuilder
from .diagnostics import Diagnostic

try:  # Lark >= 1.2 wraps the text in a TextSlice
    from lark.utils import TextSlice
except ImportError:  # pragma: no cover
    TextSlice = None

MAX_LEXICAL_ERRORS = 25


class Scan:
    def __init__(self) -> None:
        self.tokens: list[Token] = []
        self.diagnostics: list[Diagnostic] = []
        self.truncated = False   # an unterminated comment/string swallowed the rest
        self.after_bad: set[int] = set()  # tokens right after a stray character


_LITERAL_RULES = {
    "INT": "int_literal", "BASED_INT": "based_literal", "REAL_NUMBER": "real_literal",
    "TIME_LIT": "time_literal", "DATE_LIT": "date_literal", "TOD_LIT": "tod_literal",
    "DT_LIT": "dt_literal", "TYPED_LIT": "typed_literal", "SSTRING": "string_literal",
    "DSTRING": "wstring_literal",
}


def literal_errors(tokens, path: str) -> list[Diagnostic]:
    """Invalid literals: the AST builder's checks, run on the tokens alone."""
    builder = AstBuilder()
    builder.reset(path)
    for token in tokens:
        rule = _LITERAL_RULES.get(token.type)
        if rule is not None:
            getattr(builder, rule)(token)
    return builder.errors


def scan(grammar, text: str, path: str) -> Scan:
    """Tokens of `text` and its lexical faults."""
    result = Scan()
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
            if char == "{":
                result.diagnostics.append(Diagnostic(
                    "E-PARSE-005", "unterminated pragma: '{' has no closing '}' "
                    "(pragmas do not nest)", pos))
                result.truncated = True
                break
            if exc.pos_in_stream != bad_run_end:
                shown = char if char.isprintable() else f"U+{ord(char):04X}"
                result.diagnostics.append(Diagnostic(
                    "E-PARSE-007", f"unexpected character '{shown}'", pos))
            state.line_ctr.feed(char)
            bad_run_end = exc.pos_in_stream + 1
            result.after_bad.add(len(result.tokens))
            if len(result.diagnostics) > MAX_LEXICAL_ERRORS:
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
        token = grammar.retype(token)
        result.tokens.append(token)
        previous = token
    return result

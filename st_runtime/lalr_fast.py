"""A tighter driver for Lark's LALR parser: the same tables, lexers and callbacks.

Lark's own loop (`lalr_parser_state.ParserState.feed_token`) looks every
reduction's callback up by its `Rule`, whose hash and equality are Python
methods, and reads the rule's size and origin on each reduction; each token
also passes through three generators (the lexer thread, the contextual
lexer, the postlexer).  This loop does the same shifts and reductions in the
same order, calling the same callbacks (the AST builder) on the same values,
so it builds the same AST: it keeps, per rule, its size, origin and callback
(looked up once, by the rule's identity), and runs the contextual lexer's
`next_token` and the postlexer's `retype` inline, with the same per-state
lexers, token fields and line counting.

It is a fast path only: on any exception it returns `FAILED`, and the
caller parses the text again with Lark's own parser, whose errors feed the
syntax diagnostics (`recovery.py`) exactly as before.
"""

from __future__ import annotations

from lark.lexer import Token
from lark.parsers.lalr_analysis import Shift

#: What Token(type, value, pos, line, column) calls (Lark 1.2 and later); without
#: it, or with any other internal this loop reads missing, Lark's loop parses.
new_token = getattr(Token, "_future_new", None)

FAILED = object()


class _End:
    """The end of the input, as Lark's parser sees it (a token of type $END)."""

    type = "$END"


_END = _End()


class FastLalr:
    def __init__(self, lark, retype) -> None:
        self.retype = retype                              # the postlexer's work on each token
        self.rules: dict[int, tuple] = {}                 # id(Rule) -> (size, origin, callback, Rule)
        try:
            frontend = lark.parser                        # ParsingFrontend
            self.lexers = frontend.lexer.lexer.lexers     # contextual lexer: parser state -> lexer
            parser = frontend.parser.parser               # lalr_parser._Parser
            self.states = parser.parse_table.states
            self.start_states = parser.parse_table.start_states
            self.end_states = parser.parse_table.end_states
            self.callbacks = parser.callbacks
        except AttributeError:    # another Lark inside: its own loop only
            self.usable = False
            return
        # Lark's loop also calls a callback named by a terminal on each shift; the
        # AST builder has none, and this loop is not used if one appears.
        self.usable = new_token is not None and not any(isinstance(k, str) for k in self.callbacks)

    def _rule(self, rule) -> tuple:
        info = (len(rule.expansion), rule.origin.name, self.callbacks[rule], rule)   # (keeps the rule alive)
        self.rules[id(rule)] = info
        return info

    def parse(self, text: str, start: str):
        """The callbacks' result for `text`, or FAILED (then nothing is to be trusted)."""
        if not self.usable:
            return FAILED
        try:
            return self._parse(text, start)
        except Exception:    # a syntax error, or anything else: Lark's parser says what
            return FAILED

    def _parse(self, text: str, start: str):
        states, rules, retype = self.states, self.rules, self.retype
        state_stack = [self.start_states[start]]
        value_stack: list = []
        end_state = self.end_states[start]
        lexers = self.lexers
        end = len(text)
        # Lark's line counter (LineCounter.feed), inline
        pos, line, column, line_start = 0, 1, 1, 0
        while True:
            # Lark's contextual lexer: the next token the parser's state accepts
            # (BasicLexer.next_token, then the postlexer), inline
            lexer = lexers[state_stack[-1]]
            patterns = lexer.scanner._mres          # (Scanner.match, inline: the first that matches)
            ignore, callbacks, newlines = lexer.ignore_types, lexer.callback, lexer.newline_types
            token = _END
            while pos < end:
                for pattern in patterns:
                    found = pattern.match(text, pos, end)
                    if found:
                        break
                else:
                    raise ValueError("no terminal matches here")
                value, kind = found.group(0), found.lastgroup
                ignored = kind in ignore
                made = None
                if not ignored or kind in callbacks:
                    made = new_token(kind, value, pos, line, column)
                if kind in newlines:
                    count = value.count("\n")
                    if count:
                        line += count
                        line_start = pos + value.rindex("\n") + 1
                pos += len(value)
                column = pos - line_start + 1
                if made is not None:
                    made.end_line, made.end_column, made.end_pos = line, column, pos
                    if made.type in callbacks:
                        made = callbacks[made.type](made)
                    if not ignored:
                        token = retype(made)
                        break
            kind = token.type
            while True:
                action, arg = states[state_stack[-1]][kind]
                if action is Shift:
                    if token is _END:
                        raise ValueError("shift at the end of the input")
                    state_stack.append(arg)
                    value_stack.append(token)
                    break
                size, origin, callback, _ = rules.get(id(arg)) or self._rule(arg)
                if size:
                    values = value_stack[-size:]
                    del state_stack[-size:]
                    del value_stack[-size:]
                else:
                    values = []
                value_stack.append(callback(values))
                state_stack.append(states[state_stack[-1]][origin][1])
                if token is _END and state_stack[-1] == end_state:
                    return value_stack[-1]

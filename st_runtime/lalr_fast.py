"""A tighter driver for Lark's LALR parser: the same tables, lexer and callbacks.

Lark's own loop (`lalr_parser_state.ParserState.feed_token`) looks every
reduction's callback up by its `Rule`, whose hash and equality are Python
methods, and reads the rule's size and origin on each reduction; a small
file spends a third of its parse there.  This loop does the same shifts and
reductions in the same order, calling the same callbacks (the AST builder)
on the same values, so it builds the same AST; it only keeps, per rule, its
size, origin and callback (looked up once, by the rule's identity).

It is a fast path only: on any exception it returns `FAILED`, and the
caller parses the text again with Lark's own parser, whose errors feed the
syntax diagnostics (`recovery.py`) exactly as before.
"""

from __future__ import annotations

from itertools import chain

from lark.parsers.lalr_analysis import Shift

FAILED = object()


class _End:
    """The end of the input, as Lark's parser sees it (a token of type $END)."""

    type = "$END"


_END = _End()


class _Position:
    """What the contextual lexer reads of the parser: the state on top of the stack."""

    __slots__ = ("stack",)

    def __init__(self, stack: list) -> None:
        self.stack = stack

    @property
    def position(self):
        return self.stack[-1]


class FastLalr:
    def __init__(self, lark) -> None:
        self.frontend = lark.parser                       # ParsingFrontend
        parser = self.frontend.parser.parser              # lalr_parser._Parser
        self.states = parser.parse_table.states
        self.start_states = parser.parse_table.start_states
        self.end_states = parser.parse_table.end_states
        self.callbacks = parser.callbacks
        self.rules: dict[int, tuple] = {}                 # id(Rule) -> (size, origin, callback, Rule)
        # Lark's loop also calls a callback named by a terminal on each shift; the
        # AST builder has none, and this loop is not used if one appears.
        self.usable = not any(isinstance(k, str) for k in self.callbacks)

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
        states, rules = self.states, self.rules
        state_stack = [self.start_states[start]]
        value_stack: list = []
        end_state = self.end_states[start]
        tokens = self.frontend._make_lexer_thread(text).lex(_Position(state_stack))
        for token in chain(tokens, (_END,)):     # the input, then its end
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
        raise ValueError("the input ended before its start rule")    # (never: $END reduces or fails)

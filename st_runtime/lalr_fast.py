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

Each reduction also does, inline, what Lark's wrappers around the builder's
method do (`parse_tree_builder.py`): it keeps the children that are not
filtered out, inserts the `None` of an absent `[optional]`, splices in the
children of an inlined `_rule`, returns the child of a `?rule` that has one,
and calls the method with the children inline (`v_args(inline=True)`).  The
plan of each rule is read from Lark's own wrapper objects (`_plan`); a
wrapper of another kind keeps Lark's callback.  Two shortcuts, same values:

* a `?rule` of one kept symbol (`?expr: xor_expr`, nine of them between an
  operand and its expression) only changes the parser's state;
* an inlined `_rule` is a plain list of its children instead of a `Tree`
  that its parent takes apart at once (nothing else ever sees it).

It is a fast path only: on any exception it returns `FAILED`, and the
caller parses the text again with Lark's own parser, whose errors feed the
syntax diagnostics (`recovery.py`) exactly as before.
"""

from __future__ import annotations

import re
from functools import partial
from operator import itemgetter

from lark.lexer import Token
from lark.parse_tree_builder import ChildFilterLALR, ChildFilterLALR_NoPlaceholders, ExpandSingleChild
from lark.parsers.lalr_analysis import Shift
from lark.tree import Tree
from lark.visitors import Transformer, _vargs_inline

#: What Token(type, value, pos, line, column) calls (Lark 1.2 and later); without
#: it, or with any other internal this loop reads missing, Lark's loop parses.
new_token = getattr(Token, "_future_new", None)

#: Whether a Token is a str with exactly the slots `_future_new` fills (then this
#: loop fills them itself, without a call per token).
PLAIN_TOKENS = Token.__mro__[1] is str and getattr(Token, "__slots__", None) == (
    "type", "start_pos", "value", "line", "column", "end_line", "end_column", "end_pos")

FAILED = object()

# What a reduction does with its children (see _plan):
UNIT = 0        # a `?rule` of one kept symbol: the value stays, only the state changes
INLINE = 1      # the builder's method, children inline
SINGLE = 2      # a `?rule`: its one child, or else the builder's method, children inline
SPLICE = 3      # an inlined `_rule`: the list of its children
TREE = 4        # a rule with no method: Lark's Tree (the builder has one for every rule)
LARK = 5        # a wrapper this loop does not know: Lark's callback on the raw children
SINGLE_TREE = 6  # a `?rule` with no method: its one child, or else a Tree

# How the loop runs a reduction (its step, _step): the commonest plans in one
# operation each, every other plan the general way.
CALL_ALL = 10    # INLINE keeping every child in order: the method on the popped values
CALL_PICK = 11   # INLINE keeping two or more children, none spliced: the method on those
CALL_ONE = 12    # INLINE keeping one child, not spliced: the method on it
LIST_ALL = 13    # SPLICE keeping every child in order: the popped values are the list
LIST_ONE = 14    # SPLICE keeping one spliced child only: that child's list itself
CALL_SPREAD = 15  # INLINE keeping one spliced child only: the method on its items
GENERAL = 16     # anything else: the plan, read child by child


def _builds_tree(callback) -> bool:
    """Whether a callback is Lark's default for a rule without a method:
    partial(default_callback, name), which calls Transformer.__default__, a Tree."""
    if type(callback) is not partial or len(callback.args) != 1 or callback.keywords:
        return False
    function = callback.func
    if function is Tree:
        return True
    cells = dict(zip(function.__code__.co_freevars, function.__closure__ or ()))
    handler = cells.get("default_handler")
    return function.__name__ == "default_callback" and handler is not None and \
        getattr(handler.cell_contents, "__func__", None) is Transformer.__default__


class _EveryType:
    """Every token type (a postlexer that may change any token)."""

    def __contains__(self, kind) -> bool:
        return True


_EVERY_TYPE = _EveryType()


class _End:
    """The end of the input, as Lark's parser sees it (a token of type $END)."""

    type = "$END"


_END = _End()


class _Actions(dict):
    """Parser state -> {terminal or rule name: (Shift, state) or (None, step)}: Lark's
    action table with each rule replaced by its step (FastLalr._step), made per state
    on first use."""

    def __init__(self, fast: "FastLalr") -> None:
        super().__init__()
        self.fast = fast

    def __missing__(self, state: int) -> dict:
        fast = self.fast
        actions = self[state] = {kind: (action, arg) if action is Shift else (None, fast._step(arg))
                                 for kind, (action, arg) in fast.states[state].items()}
        return actions


class _Gotos(dict):
    """State -> the state after a reduction to one rule `origin` on top of it (Lark's
    goto), looked up in Lark's table on first use."""

    def __init__(self, states, origin: str) -> None:
        super().__init__()
        self.states, self.origin = states, origin

    def __missing__(self, state: int) -> int:
        target = self[state] = self.states[state][self.origin][1]
        return target


class FastLalr:
    def __init__(self, lark, retype, retyped=None, keywords=None) -> None:
        """`keywords`, if given, is (the lexer callback `reserve`, a function giving the
        current keyword table): `reserve(token)` must set the token's type to
        table.get(token.value.upper()) when that is not None and do nothing else; the
        loop then does that inline instead of calling it."""
        self.retype = retype                              # the postlexer's work on a token
        self.retyped = retyped if retyped is not None else _EVERY_TYPE   # ... of these types only
        self.reserve, self.keyword_table = keywords if keywords is not None else (None, dict)
        self.rules: dict[int, tuple] = {}                 # id(Rule) -> its plan (_plan)
        self.actions = _Actions(self)                     # state -> its actions, with steps
        self.gotos: dict[str, _Gotos] = {}                # rule name -> _Gotos
        self.units: dict[tuple, int] = {}                 # (state below, state, token) -> _unit_chain
        self.lexing: dict[int, tuple] = {}                # parser state -> _lexing
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
        # AST builder has none, and this loop is not used if one appears.  An
        # inlined `_rule` must build Lark's plain Tree, which this loop replaces
        # by a list (_plan).
        self.usable = new_token is not None and not any(isinstance(k, str) for k in self.callbacks) \
            and all(self._plan(rule)[2] == SPLICE for rule in self.callbacks
                    if rule.origin.name.startswith("_"))
        self.rules.clear()

    def _plan(self, rule) -> tuple:
        """(size, origin, kind, function, children to keep, Nones to append, rule).

        Read from the wrappers Lark put around the builder's method
        (parse_tree_builder.ParseTreeBuilder): the child filter's
        (index, splice, Nones before) triples, ExpandSingleChild, then the
        method wrapped for v_args(inline=True), or partial(Tree, name).
        """
        callback = self.callbacks[rule]
        size, origin = len(rule.expansion), rule.origin.name
        inner, keep, nones = callback, None, 0
        if type(inner) is ChildFilterLALR:
            keep, nones, inner = tuple(inner.to_include), inner.append_none, inner.node_builder
        elif type(inner) is ChildFilterLALR_NoPlaceholders:
            keep, inner = tuple((i, splice, 0) for i, splice in inner.to_include), inner.node_builder
        single = type(inner) is ExpandSingleChild
        if single:
            inner = inner.node_builder
        wrapped = getattr(inner, "__wrapped__", None)
        if getattr(wrapped, "visit_wrapper", None) is _vargs_inline:
            kind, function = (SINGLE if single else INLINE), wrapped.base_func
        elif _builds_tree(inner):
            kind, function = (SINGLE_TREE if single else SPLICE if origin.startswith("_") else TREE), inner
        else:
            kind, function, keep, nones = LARK, callback, None, 0
        if kind in (SINGLE, SINGLE_TREE) and size == 1 and nones == 0 and keep in (None, ((0, False, 0),)):
            kind = UNIT
        plan = (size, origin, kind, function, keep, nones, rule)     # (keeps the rule alive)
        self.rules[id(rule)] = plan
        return plan

    def _step(self, rule) -> tuple:
        """(size, origin, how, function, pick, gotos): the rule's plan (_plan) as the
        loop runs it; `pick` is an itemgetter (CALL_PICK), an index (CALL_ONE, LIST_ONE,
        CALL_SPREAD) or the plan (GENERAL); `gotos` the rule's _Gotos."""
        plan = self.rules.get(id(rule)) or self._plan(rule)
        origin = plan[1]
        if origin not in self.gotos:
            self.gotos[origin] = _Gotos(self.states, origin)
        return (*self._how(plan), self.gotos[origin])

    @staticmethod
    def _how(plan: tuple) -> tuple:
        """(size, origin, how, function, pick) of a plan (see `_step`)."""
        size, origin, kind, function, keep, nones, _ = plan
        if kind == UNIT:
            return size, origin, UNIT, function, plan
        simple = nones == 0 and (keep is None or not any(splice or before for _, splice, before in keep))
        picked = tuple(range(size)) if keep is None else tuple(i for i, _, _ in keep)
        if simple and kind == INLINE:
            if picked == tuple(range(size)):
                return size, origin, CALL_ALL, function, None
            if len(picked) == 1:
                return size, origin, CALL_ONE, function, picked[0]
            if picked:
                return size, origin, CALL_PICK, function, itemgetter(*picked)
        if simple and kind == SPLICE and picked == tuple(range(size)):
            return size, origin, LIST_ALL, function, None
        if nones == 0 and keep is not None and len(keep) == 1 and keep[0][1] and not keep[0][2] \
                and kind in (SPLICE, INLINE):       # (the list itself, as the general way gives)
            return size, origin, LIST_ONE if kind == SPLICE else CALL_SPREAD, function, keep[0][0]
        return size, origin, GENERAL, function, plan

    def _lexing(self, state: int) -> tuple:
        """What the loop reads of the state's lexer: (patterns, ignored types,
        callbacks, types that may hold a newline, blanks, scan); the patterns are
        the scanner's (Scanner.match, inline: the first that matches), built before
        the callbacks, and `scan` is the match of the only one, if there is one.
        `blanks` matches the ignored WS terminal alone, or is None: no other
        terminal of the grammar starts with a blank, so where WS matches it is the
        scanner's match, and the loop skips it without trying the others."""
        lexer = self.lexers[state]
        patterns = lexer.scanner._mres
        blank = next((t for t in lexer.terminals if t.name == "WS"), None)
        blanks = None
        plain = blank is not None and blank.pattern.type == "re" and not blank.pattern.flags \
            and not lexer.g_regex_flags
        if plain and "WS" in lexer.ignore_types and "WS" in lexer.newline_types and "WS" not in lexer.callback:
            blanks = re.compile(blank.pattern.value).match
        scan = patterns[0].match if len(patterns) == 1 else None
        entry = self.lexing[state] = (patterns, lexer.ignore_types, lexer.callback, lexer.newline_types,
                                      blanks, scan)
        return entry

    def _unit_chain(self, below: int, top: int, kind: str) -> int:
        """The state after the UNIT reductions that follow one from `below`
        (`?expr: xor_expr` after `?xor_expr: and_expr`, ...) before `kind`:
        each replaces the top state by a goto from `below`, whatever lies deeper,
        so the chain from (below, top, token) always ends in the same state."""
        while True:
            action, arg = self.states[top].get(kind, (None, None))
            if action is Shift or action is None:
                return top
            plan = self.rules.get(id(arg)) or self._plan(arg)
            if plan[2] != UNIT:
                return top
            top = self.states[below][plan[1]][1]

    def parse(self, text: str, start: str):
        """The callbacks' result for `text`, or FAILED (then nothing is to be trusted)."""
        if not self.usable:
            return FAILED
        try:
            return self._parse(text, start)
        except Exception:    # a syntax error, or anything else: Lark's parser says what
            return FAILED

    def _parse(self, text: str, start: str):
        table, retype, units = self.actions, self.retype, self.units
        retyped, reserve, keywords = self.retyped, self.reserve, self.keyword_table()
        plain_tokens, str_new = PLAIN_TOKENS, str.__new__
        state = self.start_states[start]        # (the top of state_stack)
        state_stack = [state]
        value_stack: list = []
        push = value_stack.append
        end_state = self.end_states[start]
        lexing = self.lexing
        end = len(text)
        # Lark's line counter (LineCounter.feed), inline
        pos, line, column, line_start = 0, 1, 1, 0
        while True:
            # Lark's contextual lexer: the next token the parser's state accepts
            # (BasicLexer.next_token, then the postlexer), inline
            patterns, ignore, callbacks, newlines, blanks, scan = lexing.get(state) or self._lexing(state)
            token = _END
            while pos < end:
                if blanks is not None:       # an ignored WS token: only the position moves
                    found = blanks(text, pos, end)
                    if found:
                        stop = found.end()
                        count = text.count("\n", pos, stop)
                        if count:
                            line += count
                            line_start = text.rindex("\n", pos, stop) + 1
                        pos = stop
                        column = pos - line_start + 1
                        if pos == end:
                            break
                if scan is not None:        # the state's scanner is one regex
                    found = scan(text, pos, end)
                    if not found:
                        raise ValueError("no terminal matches here")
                else:
                    for pattern in patterns:
                        found = pattern.match(text, pos, end)
                        if found:
                            break
                    else:
                        raise ValueError("no terminal matches here")
                value, kind = found.group(0), found.lastgroup
                start, start_line, start_column = pos, line, column
                if kind in newlines:
                    count = value.count("\n")
                    if count:
                        line += count
                        line_start = pos + value.rindex("\n") + 1
                pos += len(value)
                column = pos - line_start + 1
                ignored = kind in ignore
                if not ignored or kind in callbacks:
                    if plain_tokens:        # Token._future_new, inline
                        made = str_new(Token, value)
                        made.type, made.start_pos, made.value, made.line, made.column = \
                            kind, start, value, start_line, start_column
                        made.end_line, made.end_column, made.end_pos = line, column, pos
                    else:
                        made = new_token(kind, value, start, start_line, start_column, line, column, pos)
                    if kind in callbacks:
                        callback = callbacks[kind]
                        if callback is reserve:     # the keyword callback, inline
                            keyword = keywords.get(value.upper())
                            if keyword is not None:
                                made.type = keyword
                        else:
                            made = callback(made)
                    if not ignored:
                        token = retype(made) if made.type in retyped else made
                        break
            kind = token.type
            while True:
                action, step = table[state][kind]
                if action is Shift:
                    if token is _END:
                        raise ValueError("shift at the end of the input")
                    state = step
                    state_stack.append(state)
                    push(token)
                    break
                size, origin, how, function, pick, gotos = step
                if how == UNIT:         # the value stays; the state is the goto's
                    below = state_stack[-2]
                    chain = (below, state, kind)
                    state = units.get(chain)
                    if state is None:
                        state = units[chain] = self._unit_chain(below, gotos[below], kind)
                    state_stack[-1] = state
                    continue
                if size:
                    values = value_stack[-size:]
                    del state_stack[-size:]
                    del value_stack[-size:]
                else:
                    values = []
                if how == CALL_ALL:
                    push(function(*values))
                elif how == LIST_ALL:
                    push(values)
                elif how == CALL_PICK:
                    push(function(*pick(values)))
                elif how == CALL_ONE:
                    push(function(values[pick]))
                elif how == LIST_ONE:
                    push(values[pick])
                elif how == CALL_SPREAD:
                    push(function(*values[pick]))
                else:       # GENERAL: Lark's ChildFilterLALR and the wrapper, inline
                    _, _, how, function, keep, nones, _ = pick
                    if how == LARK:
                        push(function(values))
                    else:
                        if keep is not None:
                            children = []
                            for i, splice, before in keep:
                                if before:
                                    children += [None] * before
                                if splice:
                                    if children:
                                        children += values[i]
                                    else:       # left recursion: extend the list in place
                                        children = values[i]
                                else:
                                    children.append(values[i])
                            if nones:
                                children += [None] * nones
                        else:
                            children = values
                        if how == INLINE:
                            push(function(*children))
                        elif how == SPLICE:
                            push(children)
                        elif how != TREE and len(children) == 1:        # SINGLE, SINGLE_TREE
                            push(children[0])
                        else:
                            push(function(*children) if how == SINGLE else function(children))
                state = gotos[state_stack[-1]]
                state_stack.append(state)
                if token is _END and state == end_state:
                    return value_stack[-1]

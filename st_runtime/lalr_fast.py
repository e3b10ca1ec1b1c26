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
terminals in the same order and the same token fields.  Two differences in
how, not what: a state's scanner matches the blanks before a token and the
token in one call (`_blanks_and_scanner`), and a token's line, column and
end are worked out from its offset when read (`_Token`), not counted on
every token.

Each reduction also does, inline, what Lark's wrappers around the builder's
method do (`parse_tree_builder.py`): it keeps the children that are not
filtered out, inserts the `None` of an absent `[optional]`, splices in the
children of an inlined `_rule`, returns the child of a `?rule` that has one,
and calls the method with the children inline (`v_args(inline=True)`).  The
plan of each rule is read from Lark's own wrapper objects (`_plan`); a
wrapper of another kind keeps Lark's callback.  A method's call whose children
are not simply some of the popped values (an absent `[optional]`'s `None`, a
spliced list) is written out once per rule as one expression of the popped
values (`_call_of_plan`), so no reduction reads its plan child by child but
the few that build a list or a `?rule`'s value.  Two shortcuts, same values:

* a `?rule` of one kept symbol (`?expr: xor_expr`, nine of them between an
  operand and its expression) only changes the parser's state;
* an inlined `_rule` is a plain list of its children instead of a `Tree`
  that its parent takes apart at once (nothing else ever sees it).

The end of the input is accepted where Lark's loop accepts it (the accepting state,
the end as the token), but tested once, not after every reduction: the accepting state
has no action, so the action's look-up fails there (a KeyError), and only a failed
look-up asks.  Nor does a shift ask whether its token is the end: no table of the
grammar shifts the end (`_Actions` refuses one that would).

It is a fast path only: on any exception it returns `FAILED`, and the
caller parses the text again with Lark's own parser, whose errors feed the
syntax diagnostics (`recovery.py`) exactly as before.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from functools import partial
from operator import itemgetter

from lark.lexer import Token
from lark.parse_tree_builder import ChildFilterLALR, ChildFilterLALR_NoPlaceholders, ExpandSingleChild
from lark.parsers.lalr_analysis import Shift
from lark.tree import Tree
from lark.visitors import Transformer, _vargs_inline

try:        # how Lark's lexer folds keywords into a regular expression's callback
    from lark.lexer import _create_unless
except ImportError:         # another Lark: its own loop only
    _create_unless = None

#: What Token(type, value, pos, line, column) calls (Lark 1.2 and later); without
#: it, or with any other internal this loop reads missing, Lark's loop parses.
new_token = getattr(Token, "_future_new", None)

#: Whether a Token is a str with exactly the slots `_future_new` fills (then this
#: loop fills them itself, without a call per token).
PLAIN_TOKENS = Token.__mro__[1] is str and getattr(Token, "__slots__", None) == (
    "type", "start_pos", "value", "line", "column", "end_line", "end_column", "end_pos")

FAILED = object()


def scanner_pattern(terminals) -> str:
    """The one regular expression of Lark's Scanner for `terminals` (Scanner._build_mres)."""
    return "|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in terminals)

#: An ignored blank run as this loop skips it inside a state's regular expression
#: (`_scanner`): a WS terminal of one character class repeated.
_CHAR_RUN = re.compile(r"\[(?:[^\]\\]|\\.)*\]\+")
_NEWLINE = re.compile("\n")
_END_OF = re.Match.end      # (mapped over the matches in C: where each line starts)


class _Lines:
    """Where each line of a text starts (`starts`): the line and column of an offset as
    Lark's line counter gives them (it counts '\n', in the tokens of the terminals that may
    hold one: every '\n' of the text, `tests/test_parser_fast_path.py` checks no other
    terminal can match one).  Found for every parse: the AST builder asks a position of
    nearly every rule (`AstBuilder._pos`, which reads `starts` as `at` does)."""

    __slots__ = ("starts",)

    def __init__(self, text: str) -> None:
        self.starts = [0, *map(_END_OF, _NEWLINE.finditer(text))]

    def at(self, pos: int) -> tuple[int, int]:
        starts = self.starts
        line = bisect_right(starts, pos)
        return line, pos - starts[line - 1] + 1


class _Token(Token):
    """A Lark Token whose line, column and end are worked out when read, from its
    offset (most tokens are never asked: counting lines per token was a sixth of the loop)."""

    __slots__ = ("lines",)

    line = property(lambda self: self.lines.at(self.start_pos)[0])
    column = property(lambda self: self.lines.at(self.start_pos)[1])
    end_pos = property(lambda self: self.start_pos + len(self.value))
    end_line = property(lambda self: self.lines.at(self.start_pos + len(self.value))[0])
    end_column = property(lambda self: self.lines.at(self.start_pos + len(self.value))[1])

    def __reduce__(self):       # a plain Token, every field filled
        return (Token, (self.type, self.value, self.start_pos, self.line, self.column,
                        self.end_line, self.end_column, self.end_pos))

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
CALL_PLAN = 9    # any other INLINE: one expression of the popped values written for its plan
# The steps done in place on the stacks, numbered last (the loop tests `how >= CALL_TOP`):
CALL_TOP = 17    # CALL_ALL of one child: the method on the top value, in place
LIST_TOP = 18    # LIST_ALL of one child: the list of the top value, in place
LIST_GROW = 19   # SPLICE of a list and one more child (a left-recursive list): the list, grown
LIST_JOIN = 20   # SPLICE of two lists: the first, extended by the second


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


def _call_of_plan(function, keep: tuple, nones: int):
    """`values -> function(*children)`, the children the general way builds from the popped
    `values` for an INLINE plan (`keep`'s (index, splice, Nones before) triples, then
    `nones` Nones), written out as one call: `f(values[0], None, *values[2], None)`.  The
    text is made of indices and counts of the grammar's rules only, never of a parsed
    text."""
    arguments = []
    for i, splice, before in keep:
        arguments += ["None"] * before
        arguments.append(f"{'*' if splice else ''}values[{int(i)}]")
    arguments += ["None"] * nones
    return eval(f"lambda values: function({', '.join(arguments)})", {"function": function})


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
        actions = {kind: (action, arg) if action is Shift else (None, fast._step(arg))
                   for kind, (action, arg) in fast.states[state].items()}
        if actions.get("$END", (None,))[0] is Shift:     # (the loop shifts without looking)
            raise ValueError("a shift at the end of the input")
        self[state] = actions
        return actions


class _Scanners(dict):
    """Parser state -> the `match` of its lexer's one-call scanner (FastLalr._scanner),
    made on first use."""

    def __init__(self, fast: "FastLalr") -> None:
        super().__init__()
        self.fast = fast

    def __missing__(self, state: int):
        return self.fast._scanner(state)


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
        self.scanners = _Scanners(self)                   # parser state -> _scanner
        self.scanners_by_lexer: dict = {}                 # lexer -> _scanner (states share lexers)
        self.blanks = None                                # WS's fullmatch
        try:
            frontend = lark.parser                        # ParsingFrontend
            self.lexers = frontend.lexer.lexer.lexers     # contextual lexer: parser state -> lexer
            parser = frontend.parser.parser               # lalr_parser._Parser
            self.states = parser.parse_table.states
            self.start_states = parser.parse_table.start_states
            self.end_states = parser.parse_table.end_states
            self.callbacks = parser.callbacks
            conf = frontend.lexer_conf
            self.ignored = frozenset(conf.ignore)
            self.reserving = frozenset(kind for kind, f in conf.callbacks.items() if f is self.reserve)
        except AttributeError:    # another Lark inside: its own loop only
            self.usable = False
            return
        # Lark's loop also calls a callback named by a terminal on each shift; the
        # AST builder has none, and this loop is not used if one appears.  An
        # inlined `_rule` must build Lark's plain Tree, which this loop replaces
        # by a list (_plan).
        self.usable = new_token is not None and PLAIN_TOKENS and _create_unless is not None and not any(isinstance(k, str) for k in self.callbacks) \
            and all(self._plan(rule)[2] == SPLICE for rule in self.callbacks
                    if rule.origin.name.startswith("_"))
        self.unkept = self._unkept()
        self.rules.clear()
        self.unread, self.unread_beside = self.unkept - self.retyped, self.retyped

    def _unkept(self) -> frozenset:
        """The terminals no rule keeps as a child (punctuation, `END_IF`, ...: Lark's child
        filters leave them out of every callback), so no token of them is ever read."""
        seen, kept = set(), set()
        for rule in self.callbacks:
            _, _, kind, _, keep, _, _ = self._plan(rule)
            every = keep is None or kind == LARK
            kept_at = {i for i, _, _ in keep} if not every else ()
            for i, symbol in enumerate(rule.expansion):
                if symbol.is_term:
                    seen.add(symbol.name)
                    if every or i in kept_at:
                        kept.add(symbol.name)
        return frozenset(seen - kept)

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
        """(size, how, function, pick, gotos): the rule's plan (_plan) as the
        loop runs it; `pick` is an itemgetter (CALL_PICK), an index (CALL_ONE, LIST_ONE,
        CALL_SPREAD) or the plan (GENERAL); `function` is the written call for CALL_PLAN
        (`_call_of_plan`); `gotos` the rule's _Gotos."""
        plan = self.rules.get(id(rule)) or self._plan(rule)
        origin = plan[1]
        if origin not in self.gotos:
            self.gotos[origin] = _Gotos(self.states, origin)
        size, _, how, function, pick = self._how(plan)     # (the loop reads no origin: gotos knows it)
        return size, how, function, pick, self.gotos[origin]

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
                return size, origin, CALL_TOP if size == 1 else CALL_ALL, function, None
            if len(picked) == 1:
                return size, origin, CALL_ONE, function, picked[0]
            if picked:
                return size, origin, CALL_PICK, function, itemgetter(*picked)
        if simple and kind == SPLICE and picked == tuple(range(size)):
            return size, origin, LIST_TOP if size == 1 else LIST_ALL, function, None
        if kind == SPLICE and nones == 0 and keep in (((0, True, 0), (1, False, 0)), ((0, True, 0), (1, True, 0))) \
                and size == 2:          # (as the general way does: the first list itself, extended)
            return size, origin, LIST_JOIN if keep[1][1] else LIST_GROW, function, None
        if nones == 0 and keep is not None and len(keep) == 1 and keep[0][1] and not keep[0][2] \
                and kind in (SPLICE, INLINE):       # (the list itself, as the general way gives)
            return size, origin, LIST_ONE if kind == SPLICE else CALL_SPREAD, function, keep[0][0]
        if kind == INLINE and keep is not None:
            return size, origin, CALL_PLAN, _call_of_plan(function, keep, nones), None
        return size, origin, GENERAL, function, plan

    def _scanner(self, state: int):
        """The `match` of the state's lexer with the blanks before a token inside it
        (`_blanks_and_scanner`), made once per lexer (states share them)."""
        lexer = self.lexers[state]
        scan = self.scanners_by_lexer.get(lexer)
        if scan is None:
            scan = self.scanners_by_lexer[lexer] = self._blanks_and_scanner(lexer)
        self.scanners[state] = scan
        return scan

    def _blanks_and_scanner(self, lexer):
        """`(?>(?:WS)*)(?:scanner)`.match, where `scanner` is the pattern Lark's lexer
        scans with (`Scanner._build_mres`, its terminals after `_create_unless`; compiled
        here instead, Lark compiles its own only when its loop runs, on an error).

        The scanner's first terminal that matches at the first character after the
        blanks is the token, as Lark's lexer finds it after skipping them one WS token
        at a time: WS is one character class repeated and no other terminal of the
        grammar starts with a blank, so the blanks are WS's and the scanner's
        alternatives are tried at the same place (its groups keep their numbers, so
        `lastgroup` is the same).  A lexer of another kind (a keyword folded into a
        callback, another callback than the keywords', another regex module) raises:
        Lark's loop parses."""
        terminals, unless = _create_unless(lexer.terminals, lexer.g_regex_flags, lexer.re, lexer.use_bytes)
        blank = next((t for t in terminals if t.name == "WS"), None)
        callbacks = lexer.user_callbacks
        if unless or lexer.re is not re or lexer.use_bytes or lexer.g_regex_flags or blank is None \
                or blank.pattern.type != "re" or blank.pattern.flags or not _CHAR_RUN.fullmatch(blank.pattern.value) \
                or lexer.ignore_types != self.ignored or "WS" not in self.ignored \
                or callbacks.keys() != self.reserving or self.reserving & self.ignored:
            raise ValueError("a lexer this loop does not know")
        self.blanks = re.compile(blank.pattern.value).fullmatch
        return re.compile(f"(?>(?:{blank.pattern.value})*)(?:{scanner_pattern(terminals)})").match

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
        retyped, reserving, keywords = self.retyped, self.reserving, self.keyword_table()
        str_new, lazy = str.__new__, _Token
        state = self.start_states[start]        # (the top of state_stack)
        state_stack = [state]
        value_stack: list = []
        push = value_stack.append
        end_state = self.end_states[start]
        scanners, ignored = self.scanners, self.ignored
        lines = _Lines(text)                    # (a token's line and column, when asked)
        if retyped is not self.unread_beside:   # (a test retypes every token: then it reads each)
            self.unread, self.unread_beside = self.unkept - retyped, retyped
        unread = self.unread
        pos, token = 0, None
        try:        # (the end: the state of an accepted input has no action, a KeyError)
            while True:
                # Lark's contextual lexer: the next token the parser's state accepts
                # (BasicLexer.next_token, then the postlexer), inline
                scan = scanners[state]
                while True:
                    found = scan(text, pos)
                    if found is None:
                        break
                    kind = found.lastgroup
                    start, pos = found.span(kind)
                    if kind not in ignored:
                        break
                if found is None:                   # blanks to the end, or no terminal here
                    if pos < len(text) and not self.blanks(text, pos):
                        raise ValueError("no terminal matches here")
                    token, kind = _END, "$END"
                else:
                    value = text[start:pos]
                    if kind in reserving:           # the keyword callback (parser.reserve_keywords), inline
                        kind = keywords.get(value.upper(), kind)
                    if kind in unread:              # a token no callback is given: its place only
                        token = kind
                    else:
                        token = str_new(lazy, value)    # Token._future_new, inline, the positions when asked
                        token.type, token.start_pos, token.value, token.lines = kind, start, value, lines
                        if kind in retyped:
                            token = retype(token)
                            kind = token.type
                while True:
                    action, step = table[state][kind]
                    if action is Shift:     # (never at the end: _Actions refuses a table that would)
                        state = step
                        state_stack.append(state)
                        push(token)
                        break
                    size, how, function, pick, gotos = step
                    if how >= CALL_TOP:     # in place: the top value replaced, or the list below grown
                        if how == CALL_TOP:
                            value_stack[-1] = function(value_stack[-1])
                        elif how == LIST_TOP:
                            value_stack[-1] = [value_stack[-1]]
                        else:               # LIST_GROW, LIST_JOIN: two children, the first a list
                            last = value_stack.pop()
                            del state_stack[-1]
                            if how == LIST_GROW:
                                value_stack[-1].append(last)
                            else:
                                value_stack[-1] += last
                        state = state_stack[-1] = gotos[state_stack[-2]]
                    elif how == UNIT:       # the value stays; the state is the goto's
                        below = state_stack[-2]
                        chain = (below, state, kind)
                        state = units.get(chain)
                        if state is None:
                            state = units[chain] = self._unit_chain(below, gotos[below], kind)
                        state_stack[-1] = state
                        continue
                    else:
                        if size:
                            values = value_stack[-size:]
                            del state_stack[-size:]
                            del value_stack[-size:]
                        else:
                            values = []
                        if how == CALL_PLAN:
                            push(function(values))
                        elif how == GENERAL:    # Lark's ChildFilterLALR and the wrapper, inline
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
                        elif how == CALL_PICK:
                            push(function(*pick(values)))
                        elif how == LIST_ONE:
                            push(values[pick])
                        elif how == CALL_SPREAD:
                            push(function(*values[pick]))
                        elif how == CALL_ALL:
                            push(function(*values))
                        elif how == LIST_ALL:
                            push(values)
                        else:                   # CALL_ONE
                            push(function(values[pick]))
                        state = gotos[state_stack[-1]]
                        state_stack.append(state)
        except KeyError:
            if token is _END and state == end_state:    # (Lark's loop tests this after each reduction)
                return value_stack[-1]
            raise

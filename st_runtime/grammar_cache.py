"""The Lark LALR parser, its tables kept across processes in the user cache.

Building the tables from `grammar.lark` takes about a second; loading them
takes a few milliseconds.  The entry's name is a hash of the grammar text,
the options that shape the tables, Lark's version and Python's, so an entry
built from anything else is never read.  Lark's tables serialize to plain
lists, dicts and strings, so the entry is read by `user_cache.loads` with no
global allowed at all (see `user_cache` for why this is safe); a damaged or
refused entry is rebuilt.

The contextual lexer (one small lexer per parser state) is built per state
when the parser first reaches that state: a short file needs a few dozen of
the 200-odd, and building them all was a fifth of `stgen check`'s start-up.
The parse table (13,000 actions) is read back without a call per action
(`_parse_table`): Lark's own reading was half of loading the grammar.
"""

from __future__ import annotations

import hashlib
import io
import re
import sys
from copy import copy

import lark
from lark import Lark
from lark.grammar import Rule
from lark.lexer import ContextualLexer
from lark.parsers.lalr_analysis import IntParseTable, Reduce, Shift
from lark.parsers.lalr_parser import LALR_Parser, _Parser

from . import user_cache


def cached_lark(grammar: str, options: dict, runtime: dict) -> Lark:
    """`Lark(grammar, **options, **runtime)`, its tables from the cache when there.

    `options` shape the tables (part of the key); `runtime` holds the objects
    given again on every load (transformer, postlex, callbacks), never stored.
    """
    runtime = {**runtime, "_plugins": {"ContextualLexer": LazyContextualLexer, "LALR_Parser": CachedLalrParser}}
    name = f"lark-{_key(grammar, options)}.pickle"
    data = user_cache.read(name)
    if data is not None:
        try:
            stored = user_cache.loads(data)
            return Lark._load_from_dict(stored["data"], stored["memo"], **runtime)
        except Exception:  # damaged, refused or from another layout: rebuild it
            pass
    parser = Lark(grammar, **options, **runtime)
    buffer = io.BytesIO()
    parser.save(buffer, exclude_options=tuple(runtime))
    user_cache.write(name, buffer.getvalue())
    return parser


def _key(grammar: str, options: dict) -> str:
    text = "\0".join([user_cache.FORMAT, grammar, repr(sorted(options.items())), lark.__version__,
                      sys.version.split()[0]])
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:40]


class CachedLalrParser(LALR_Parser):
    """Lark's LALR parser; read from the cache, its table is made by `_parse_table`."""

    @classmethod
    def deserialize(cls, data, memo, callbacks, debug=False):   # LALR_Parser.deserialize's steps
        inst = cls.__new__(cls)
        inst._parse_table = _parse_table(data, memo)
        inst.parser = _Parser(inst._parse_table, callbacks, debug)
        return inst


def _parse_table(data: dict, memo: dict) -> IntParseTable:
    """`IntParseTable.deserialize(data, memo)`: the same states, actions and order.

    A reduction's rule is stored as a reference into `memo` ({'@': n}), which
    `Rule.deserialize` looks up with some ten Python operations; here each
    action's pair is made once, for its first state, and shared by the others
    (a pair is only ever unpacked).
    """
    tokens = data["tokens"]
    pairs: dict = {}          # (1, n) -> (Reduce, memo[n]); (0, state) -> (Shift, state)
    states = {}
    for state, row in data["states"].items():
        table = states[state] = {}
        for token, (kind, arg) in row.items():
            key = (kind, arg["@"] if kind == 1 else arg)
            pair = pairs.get(key)
            if pair is None:
                pair = pairs[key] = (Reduce, Rule.deserialize(arg, memo)) if kind == 1 else (Shift, arg)
            table[tokens[token]] = pair
    return IntParseTable(states, data["start_states"], data["end_states"])


class LazyContextualLexer(ContextualLexer):
    """Lark's contextual lexer, each state's lexer made on first use.

    Same lexers as Lark's own (one per distinct set of accepted terminals,
    shared between states): only when they are made differs.
    """

    def __init__(self, conf, states, always_accept=()):  # no super(): it would build them all
        self._conf = conf
        self._states = states
        self._always_accept = frozenset(always_accept)
        self._by_accepts: dict = {}
        self.lexers = _LexersOnDemand(self)
        self._root = None
        if not conf.skip_validation:  # a fresh build: Lark's check of every terminal, once
            self._root = self.BasicLexer(self._copy_conf(list(conf.terminals), validate=True))

    @property
    def root_lexer(self):
        if self._root is None:
            self._root = self.BasicLexer(self._copy_conf(list(self._conf.terminals)))
        return self._root

    def _lexer_for(self, state):
        accepts = frozenset(self._states[state])
        lexer = self._by_accepts.get(accepts)
        if lexer is None:
            wanted = accepts | set(self._conf.ignore) | self._always_accept
            by_name = self._conf.terminals_by_name
            terminals = _live([by_name[n] for n in wanted if n in by_name])
            lexer = self.BasicLexer(self._copy_conf(terminals))
            self._by_accepts[accepts] = lexer
        return lexer

    def _copy_conf(self, terminals, validate=False):
        conf = copy(self._conf)
        conf.terminals = terminals
        conf.skip_validation = not validate   # per-state lexers: checked once already
        return conf


#: A regular expression of this form (IDENT's) matches at every place where a
#: word of letters, digits and '_' starting with a letter or '_' begins.
_WORD = re.compile(r"\[A-Za-z_\](?:\[[^\]\\]*\]\*)?")


def _order(terminal):
    """Lark's order of a lexer's alternatives (BasicLexer.__init__): the first that matches wins."""
    return (-terminal.priority, -terminal.pattern.max_width, -len(terminal.pattern.value), terminal.name)


def _live(terminals: list) -> list:
    """`terminals` without the keyword alternatives that can never match first.

    A case-insensitive keyword ("IF"i) placed after a regular expression that
    matches wherever a word begins (IDENT, which the postlexer adds to every
    state) never wins: where the keyword matches, that expression matches
    too, and Python's alternation takes the first alternative that matches.
    The keyword then comes from IDENT and the keyword callback, as it always
    did; dropping its dead alternative only makes the state's regular
    expression shorter to compile (two thirds of the terminals are keywords).
    Lark folds a keyword into the expression instead (`_create_unless`) when
    its flags are a subset of the expression's: such keywords are kept.
    """
    words = [t for t in terminals if t.pattern.type == "re" and _WORD.fullmatch(t.pattern.value)]

    def dead(t) -> bool:
        value = t.pattern.value
        return (t.pattern.type == "str" and value[:1].isalpha() and value.replace("_", "").isalnum()
                and any(_order(w) < _order(t) and not set(t.pattern.flags) <= set(w.pattern.flags)
                        for w in words))

    return [t for t in terminals if not dead(t)]


class _LexersOnDemand(dict):
    """state -> lexer, filled as states are reached."""

    def __init__(self, owner: LazyContextualLexer):
        super().__init__()
        self.owner = owner

    def __missing__(self, state):
        lexer = self[state] = self.owner._lexer_for(state)
        return lexer

"""IF conditions and CASE selectors that cannot fault are tested in place.

Without this pass an IF/ELSIF chain evaluates its conditions under one
`try` into the index of the branch taken, then compares that index with
each branch's number (a fault in a condition abandons the whole IF); a
single IF keeps its condition in a temporary, and a CASE its selector.
When no condition can raise what the handler catches (`_FAULTS`: STFault,
ArithmeticError, ValueError), the handler never runs, so `if c0: ...
elif c1: ... else: ...` evaluates the same conditions in the same order
and runs the same branch, with each branch's charge where it was (the
charges are the branches' own lines, cost.py).

What cannot fault, judged on the ST expression and on its Python code both:

* ST: no dereference, every variable read owned storage (not a VAR_IN_OUT,
  which may be unconnected: NullRef raises F-NULL-REF on any read, unless
  the fast path being compiled runs only when it is a Python list; nor a
  REF_TO or interface), no member that is an FB's VAR_IN_OUT;
* Python: names, literals, attribute reads and subscripts (of owned lists
  and objects: an IndexError or AttributeError is not caught by the
  handler either, so it propagates the same with or without it),
  comparisons, `& | ^ ~ not and or`, and `+ - *`; set displays (`x in {1, 2}`:
  hashing raises no `_FAULTS` error); calls only of `abs`,
  `min`, `max`; no `/ // % ** << >>` (ZeroDivisionError, ValueError of a
  negative shift), no `:=` but into a temporary (`_tN`), no other call (index checks call `_index_fault`,
  conversions and functions may raise).  `+ - *` of ints and floats raise
  only when an int beyond 2**1024 meets a float (OverflowError): with at
  most 14 such operators on ST integers (at most 64 bits, literals at most
  65) no intermediate gets there.
"""

from __future__ import annotations

import functools
import keyword
import re

from ... import ast
from ...types import FBType, InterfaceType, RefType, StructType, resolve_alias
from ..scope import _LEAVES, listed as nodes_under, of_classes, once
from . import reuse

# Characters an expression that cannot fault is made of: no quote, `/`, `%`, `:`, `@`.
_ALLOWED = re.compile(r"[\w\s.()\[\]{},+\-*<>=!&|^~]*")
_TEMP_SET = re.compile(r"\b_t\d+ := ")                  # a temporary set inside (`(_t1 := x) > B or ...`)
_ASSIGNMENT = re.compile(r"(?<![=<>!])=(?!=)")          # `=` outside `== <= >= !=`
_WORD = re.compile(r"\b([A-Za-z_]\w*)(\s*\()?")
_NAME = re.compile(r"[A-Za-z_]\w*")
_CALLED = re.compile(r"\w\s*\(")
_CALLABLE = {"abs", "min", "max"}
_WORDS = {"not", "and", "or", "if", "else", "in", "is", "True", "False", "None"}
_KEYWORDS = frozenset(keyword.kwlist) - _WORDS     # Python keywords code that cannot fault has not
_CALLS = _CALLABLE | _WORDS                          # words it may have before a `(`
_EXPONENT = re.compile(r"\b\d+(?:\.\d*)?[eE][+-]\d+")
MAX_ARITHMETIC = 14
_PLACEHOLDER = re.compile("\x00(_t\\d+)\x00")


def per_iteration_values(code: str) -> str:
    """`code` with each placeholder of a FOR variable's per-iteration value (`i - 1`, `i * k`:
    exprs.py `_per_iteration`) as the one operation it may be put back as."""
    if "\x03" in code:
        code = reuse.as_names(code)         # a value of the reuse pass: a name or what cannot raise
    return _PLACEHOLDER.sub(r"(\1 * 1)", code) if "\x00" in code else code


def code_cannot_fault(code: str) -> bool:
    """The Python expression `code` raises nothing `_FAULTS` catches (module docstring)."""
    code = per_iteration_values(code)
    if ":=" in code:
        code = _TEMP_SET.sub("", code)      # (setting a local cannot raise; any other `:` stays)
    if not code.strip() or not _ALLOWED.fullmatch(code) or "**" in code or "<<" in code \
            or ">>" in code or "=" in code and _ASSIGNMENT.search(code):
        return False
    # (each word `_WORD` finds is a name `_NAME` finds, and a called one ends a `_CALLED`)
    if not _KEYWORDS.isdisjoint(_NAME.findall(code)) or "(" in code and _CALLED.search(code):
        for word, called in set(_WORD.findall(code)):
            if word in _KEYWORDS or called and word not in _CALLS:
                return False
    if "e+" in code or "e-" in code or "E+" in code or "E-" in code:
        code = _EXPONENT.sub("0", code)        # the sign of 1e+308 is no operator
    return code.count("+") + code.count("-") + code.count("*") <= MAX_ARITHMETIC


# `code_cannot_fault` kept by the code's text for the process (a pure function of it: every
# body and every load asks the same expressions again).
cannot_fault_judged = functools.lru_cache(maxsize=8192)(code_cannot_fault)


def _owned(t) -> bool:
    return not isinstance(resolve_alias(t), (RefType, InterfaceType))


def expr_cannot_fault(compiler, node, code: str) -> bool:
    """`node` (compiled to `code`) reads only owned storage and its code cannot raise."""
    if not cannot_fault_judged(code):
        return False
    for n in _read_nodes(compiler, node):
        if isinstance(n, ast.Deref):
            return False
        if isinstance(n, ast.Name):
            symbol = _symbol(compiler, n)
            if symbol is not None and ((symbol.kind == "VAR_IN_OUT" and not listed(compiler, n))
                                       or not _owned(symbol.type)):
                return False
        elif isinstance(n, ast.Member):
            base = resolve_alias(compiler.ty(n.base))
            key = n.name.upper()
            if isinstance(base, StructType) and key in base.fields and not base.union:
                member_type = base.fields[key][1]
            elif isinstance(base, FBType) and key in base.variables and base.variables[key].kind != "VAR_IN_OUT":
                member_type = base.variables[key].type
            else:
                return False
            if not _owned(member_type):
                return False
    return True


def _read_nodes(compiler, node) -> tuple:
    """The Deref, Name and Member nodes under `node` in walk order, found once a node (an
    unrolled loop's copies compile the same expressions again); a leaf (a name, a literal)
    at once."""
    if type(node) in _LEAVES:
        return (node,) if type(node) is ast.Name else ()
    return once(compiler.__dict__.setdefault("_read_nodes", {}), node,
                lambda: tuple(of_classes(nodes_under(node), _READ_NODES)))


_READ_NODES = frozenset({ast.Deref, ast.Name, ast.Member})


def listed(compiler, name) -> bool:
    """`name` is a VAR_IN_OUT the fast path being compiled runs with only when it holds a
    Python list (fastpath.listed_in_outs): owned storage there."""
    return name.name.upper() in getattr(compiler, "listed_in_outs", ())


def _symbol(compiler, name):
    """The variable `name` stands for, or None (an enumerated value, a constant)."""
    key = name.name.upper()
    place = compiler.scope.places.get(key)
    if place is not None:
        return place.symbol
    if key in compiler.pou.variables:
        return compiler.pou.variables[key]
    return compiler.program.globals.get(key)

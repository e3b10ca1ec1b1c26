"""No `try` around an assignment that cannot raise.

Two rules, either one suffices:

* local arithmetic: `local = expression` where the expression uses only
  Python locals, numeric literals, parentheses and `+ - *`: every local of
  an elementary variable holds an int or a float (set in the prologue, so
  always bound), and + - * of ints and floats raise in Python only when
  an int beyond 2**1024 meets a float (OverflowError; a float overflow
  gives inf): at most 14 of them, as in the branches pass, keep every
  intermediate of 64-bit ST integers below that.
* owned store: `X := expression` compiled to the one line `target = code`,
  where X is a variable the POU owns as plain storage (a local or a
  `self.` slot: not a VAR_IN_OUT or REF_TO, whose store goes through a
  reference; not located AT %..., whose attribute is a property writing the
  process image; not a global or VAR_EXTERNAL; of an elementary type, so no
  copy), and the expression cannot fault by the rule of the branches pass
  (optimise/branches.py `expr_cannot_fault`: owned reads, literals,
  comparisons, `not and or & | ^ ~`, unary minus, at most 14 `+ - *`; no
  division, power, shift or call but `abs min max`).  Storing into a slot
  or a local raises nothing; the conversion to the target's type, where one
  is needed, is a call and keeps the handler.
* owned copy: `A := B` of arrays of one elementary element type and the same
  bounds compiled to `v_A[_WHOLE] = v_B`, A the POU's own (as above) and B its own
  or a global's (not located, not a reference), or an array variable of the POU's
  own FB instance (`A := Ik.CylinderPos`, `v_A[_WHOLE] = v_IK.v_CYLINDERPOS`: the
  instance a slot or local, not an in-out or a reference, which an unconnected
  NullRef or a NULL reference would make raise; the member not an in-out of the
  FB, not located): a slice store of a list.
* owned element store: `A[i, j] := expression` compiled to `v_A[k] = code`
  with a literal index (the compiler writes one only where the index is
  in range), where A is an array the POU owns as plain storage (as above;
  or a FUNCTION's VAR_IN_OUT inside a fast path that runs only when it
  is a Python list: fastpath.listed_in_outs) of an elementary element
  type, and the expression cannot fault by the same rule.  A store into
  a list at an index in range raises nothing.

The handler catches `_FAULTS` only: when the code cannot raise one, the
handler never runs and results, faults and the charged cost are the same.
Division, power, calls (conversions, index checks), and stores to located,
referenced or global variables keep their handler.
"""

from __future__ import annotations

import functools
import re

from ... import ast
from ...types import ArrayType, ElementaryType, FBType, resolve_alias
from . import branches

_ASSIGNMENT = re.compile(r"\s*+[A-Za-z_]\w* = ([\w\s()+\-*.]+)")
_ATTRIBUTE_OR_CALL = re.compile(r"[A-Za-z_]\w*\s*[.(]")
_STORE = re.compile(r"\s*+(?:self\.)?[A-Za-z_]\w* = (.+)")
_ELEMENT_STORE = re.compile(r"\s*+(?:self\.)?[A-Za-z_]\w*\[\d+\] = (.+)")
_PLAIN_KINDS = {"VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_TEMP", "RETURN"}
_INSTANCE_KINDS = {"VAR", "VAR_INPUT", "VAR_OUTPUT"}
_COPY = re.compile(r"\s*+v_\w+\[_WHOLE\] = v_\w+(?:\.v_\w+)?")


def cannot_fault(lines: list[str], compiler=None, node=None) -> bool:
    """The assignment's code `lines` raises nothing `_FAULTS` catches (module docstring).
    Either rule suffices and neither changes anything. A slot's store `self.v_X = ...` is
    never local arithmetic (`_ASSIGNMENT` takes no dotted target): only the owned store is
    asked; any other line asks the arithmetic first, whose answer is kept by its text."""
    if compiler is None:
        return bool(lines) and all(map(_local_arithmetic, lines))
    if lines and lines[0].lstrip().startswith("self."):
        return _owned_store(compiler, node, lines)
    return bool(lines) and all(map(_arithmetic_judged, lines)) or _owned_store(compiler, node, lines)


def _local_arithmetic(line: str) -> bool:
    match = _ASSIGNMENT.fullmatch(branches.per_iteration_values(line))
    return match is not None and not _ATTRIBUTE_OR_CALL.search(match.group(1)) \
        and branches.code_cannot_fault(match.group(1))   # no `**`, at most 14 `+ - *`


# `_local_arithmetic` of a line, kept by its text (a pure function of it): an unrolled loop
# writes its copies' lines again, the fast path the exact one's, every load the same lines.
_arithmetic_judged = functools.lru_cache(maxsize=8192)(_local_arithmetic)


def _owned_store(compiler, node, lines: list[str]) -> bool:
    """One `:=` into the POU's own storage (module docstring): an elementary variable
    (`v = code`) or, at a literal index, an element of an array of elementary elements
    (`v[k] = code`), whose expression cannot fault."""
    if len(lines) != 1 or not isinstance(node, ast.Assign) or node.mode != ":=":
        return False
    target = node.target
    if _COPY.fullmatch(lines[0]):
        return _owned_copy(compiler, node)
    if isinstance(target, ast.Name):
        match = _STORE.fullmatch(lines[0])
        owned = match is not None and _plain_variable(compiler, target)
    elif isinstance(target, ast.Index) and isinstance(target.base, ast.Name):
        match = _ELEMENT_STORE.fullmatch(lines[0])
        owned = match is not None and _plain_array(compiler, target.base)
    else:
        return False
    return owned and branches.expr_cannot_fault(compiler, node.value, match.group(1))


def _owned_copy(compiler, node) -> bool:
    """`A := B` of two arrays of the same elementary type, compiled to `v_A[_WHOLE] = v_B`: A the
    POU's own array, B its own or a global's (not located, not reached through a reference) or
    an array of its own FB instance (`_instance_array`): both Python lists of the same length, and a slice store of a list raises nothing."""
    if not (isinstance(node.target, ast.Name) and _plain_array(compiler, node.target)):
        return False
    if isinstance(node.value, ast.Member):
        return _same_array(compiler, node.target, _instance_array(compiler, node.value))
    if not isinstance(node.value, ast.Name):
        return False
    source = branches._symbol(compiler, node.value)
    if source is None or source.kind not in _PLAIN_KINDS | {"VAR_GLOBAL", "VAR_EXTERNAL"} \
            or source.decl is not None and getattr(source.decl, "location", None) is not None:
        return False
    place = compiler.scope.places.get(node.value.name.upper())
    if place is not None and place.how not in ("alias", "global"):
        return False
    return _same_array(compiler, node.target, source.type)


def _instance_array(compiler, member):
    """The type of `member`, `I.V` of the POU's own FB instance I (a slot or local: not an
    in-out, not through a reference) and its variable V (an instance slot: VAR, VAR_INPUT or
    VAR_OUTPUT, not located); None otherwise."""
    if not isinstance(member.base, ast.Name) or _own_symbol(compiler, member.base) is None:
        return None
    fb = resolve_alias(compiler.ty(member.base))
    variable = fb.variables.get(member.name.upper()) if isinstance(fb, FBType) else None
    if variable is None or variable.kind not in _INSTANCE_KINDS \
            or variable.decl is not None and getattr(variable.decl, "location", None) is not None:
        return None
    return variable.type


def _same_array(compiler, target, source_type) -> bool:
    """The source's type `source_type` is an array of the target's bounds and element type."""
    a, b = resolve_alias(branches._symbol(compiler, target).type), resolve_alias(source_type)
    return isinstance(b, ArrayType) and a.dims == b.dims and resolve_alias(a.element) == resolve_alias(b.element)


def _own_symbol(compiler, name, listed_in_outs: bool = False):
    """The symbol of `name` when the POU holds it as plain storage: its own variable (a
    global has kind VAR_GLOBAL) or, with `listed_in_outs`, an in-out the fast path has seen
    to be a Python list; not located (AT %...).  Else None."""
    symbol = branches._symbol(compiler, name)
    if symbol is None or not (symbol.kind in _PLAIN_KINDS or listed_in_outs and branches.listed(compiler, name)):
        return None
    if symbol.decl is not None and getattr(symbol.decl, "location", None) is not None:
        return None
    return symbol


def _plain_array(compiler, name) -> bool:
    """`name` is an array of elementary elements the POU owns as a Python list (or an
    in-out the fast path has seen to be one)."""
    symbol = _own_symbol(compiler, name, listed_in_outs=True)
    if symbol is None:
        return False
    t = resolve_alias(symbol.type)
    return isinstance(t, ArrayType) and not t.is_open and isinstance(resolve_alias(t.element), ElementaryType)


def _plain_variable(compiler, name) -> bool:
    """`name` is the POU's own elementary variable held as a local or a slot."""
    symbol = _own_symbol(compiler, name)
    return symbol is not None and isinstance(resolve_alias(symbol.type), ElementaryType)

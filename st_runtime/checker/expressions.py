"""Typing of expressions.

Every expression node gets a type in `CheckedProgram.expr_types`; constant
subexpressions also get their value in `CheckedProgram.constants`.

Literal typing rule (the compiler relies on it):

* A typed literal (`INT#5`, `LREAL#1`) has its prefix type; its value must fit.
* An *untyped constant expression* is an untyped integer or real literal, or
  `+ - * / MOD` and unary `+ -` applied only to such literals.  It is folded
  exactly (integer `/` truncates toward zero) and then typed:
  - if it contains a real literal: the context's type when that is REAL or
    LREAL, else LREAL;
  - integer-valued: the context's integer or bit-string type when the value
    fits (in an assignment, initial value or input argument a value that does
    not fit is an error, E-TYPE-005); a lone integer literal in a REAL/LREAL
    context takes that real type (`r * 2`: 2 is LREAL); otherwise the smallest
    of SINT, INT, DINT, LINT (then ULINT) holding every intermediate value.
  Inside, every node carries its folded value in `constants`: the compiler
  should emit that constant rather than recompute the subexpression.
* In a binary operation the context of an untyped operand is the other
  operand's type (`i + 1`: 1 takes i's type if it fits).
* The result of a typed binary operation is the narrowest type both operands
  implicitly convert to (INT + DINT -> DINT, DINT + REAL -> LREAL).
"""

from __future__ import annotations

import difflib
import math

from .oo import assignable_reference, find_property, may_call
from ..per_class import PerClass
from ..process_image import PLAIN_TYPES, parse_address
from .. import ast
from .. import types as T
from ..ast import key
from . import typesys as ts
from ..values import to_real32
from .constfold import NOT_CONSTANT, DivisionByZero, apply_binary, apply_unary
from .context import Context, Scope

ARITHMETIC = ("+", "-", "*", "/", "MOD")
LOGIC = ("AND", "&", "OR", "XOR")
COMPARISON = ("=", "<>", "<", ">", "<=", ">=")


def _time_scaled(op: str, ns: int, k) -> int:
    """A folded TIME * number or TIME / number, in integer nanoseconds as the
    runtime computes it (`values.time_mul`/`time_div`: a real factor rounds
    to the nearest ns, ties to even; T#10ns * 0.25 is T#2ns, not 2.5)."""
    from ..values import time_div, time_mul

    return time_mul(ns, k) if op == "*" else time_div(ns, k)


def is_untyped_constant(e, memo: dict | None = None) -> bool:
    """Whether `e` is made only of untyped literals and + - * / MOD (see above); `memo`
    keeps the answers for operations (a leaf is answered from its class at once)."""
    maybe = _MAYBE_UNTYPED.get(type(e))
    if maybe is None:
        return False
    if maybe is _LITERAL:
        return e.type_prefix is None
    if memo is not None:
        known = memo.get(id(e))
        if known is not None:
            return known
    if type(e) is ast.Unary:
        result = e.op in ("-", "+") and is_untyped_constant(e.operand, memo)
    else:
        # Right first: in a long left-deep sum `a + b + c ...` it fails at once.
        result = e.op in ARITHMETIC and is_untyped_constant(e.right, memo) \
            and is_untyped_constant(e.left, memo)
    if memo is not None:
        memo[id(e)] = result
    return result


#: The IEC time arithmetic of `+` and `-`: (left type's name, right type's name) -> result.
_TIME_SUMS = {
    "+": {("TIME", "TIME"): T.TIME, ("TIME_OF_DAY", "TIME"): T.TOD, ("DATE_AND_TIME", "TIME"): T.DT},
    "-": {("TIME", "TIME"): T.TIME, ("TIME_OF_DAY", "TIME"): T.TOD, ("DATE_AND_TIME", "TIME"): T.DT,
          ("DATE", "DATE"): T.TIME, ("TIME_OF_DAY", "TIME_OF_DAY"): T.TIME,
          ("DATE_AND_TIME", "DATE_AND_TIME"): T.TIME},
}

#: The only nodes `is_untyped_constant` may find true (others need no look): a literal is
#: untyped when it has no prefix, an operation when `is_untyped_constant` says so.
_LITERAL, _OPERATION = "literal", "operation"
_MAYBE_UNTYPED = {ast.IntLiteral: _LITERAL, ast.RealLiteral: _LITERAL,
                  ast.Unary: _OPERATION, ast.Binary: _OPERATION}


def start_pos(e) -> ast.Pos:
    """Where an expression starts in the source (a Binary's own pos is its operator)."""
    while True:
        if isinstance(e, ast.Binary):
            e = e.left
        elif isinstance(e, (ast.Member, ast.Index)):
            e = e.base
        elif isinstance(e, ast.Call):
            e = e.callee
        else:
            return getattr(e, "pos", ast.NOWHERE)


def _is_plain_literal(e) -> bool:
    while isinstance(e, ast.Unary) and e.op in ("-", "+"):
        e = e.operand
    return isinstance(e, ast.IntLiteral)


#: The classes of a type that `require_assignable` takes as assignable to itself: all but
#: FB instances (never copied), references and interfaces (their own rules), strings
#: (a literal may be truncated) and subranges (a constant's limits).
_SELF_ASSIGNABLE = frozenset((T.ElementaryType, T.EnumType, T.StructType, T.ArrayType))

def _typer(cls: type) -> tuple:
    """`_TYPERS[cls]`, found on a class's first node: whether a node of `cls` may be an
    untyped constant (`_MAYBE_UNTYPED`'s answer, None for most), and the ExprChecker method
    that types it (`_` + the class name), or `_untypable` (a node that is no expression).
    One look-up gives `infer` both."""
    return _MAYBE_UNTYPED.get(cls), getattr(ExprChecker, "_" + cls.__name__, _untypable)


def _untypable(checker, e, expected):
    return checker.record(e, ts.ERROR)


_TYPERS = PerClass(_typer)


def _range(t) -> str:
    return f"{t.min}..{t.max}" if isinstance(t, T.ElementaryType) else "?"


# The part a bit access selects: `x.3` and `x.%X3` a BOOL, `.%B1` a BYTE, ...
PARTS = {"": T.BOOL, "X": T.BOOL, "B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}

def same_referenced(a, b) -> bool:
    """Whether a reference to `a` may be stored in a REF_TO `b` (IEC 61131-3 3rd ed.
    6.4.4.10: a reference refers to a variable of its declared type): the same
    type, string lengths included.  (Issue 16: `same_type` alone let a REF_TO
    STRING[20] refer to a STRING[4], and 12 characters written through it
    stayed in the STRING[4].)"""
    if isinstance(a, T.StringType) and isinstance(b, T.StringType):
        return a.wide == b.wide and a.length == b.length
    if isinstance(a, T.ArrayType) and isinstance(b, T.ArrayType):
        return a.dims == b.dims and same_referenced(a.element, b.element)
    if isinstance(a, T.SubrangeType) or isinstance(b, T.SubrangeType):
        # its limits are part of the type (6.4.4.4): a REF_TO INT to an INT(1..5)
        # would write 100 into it (same_type compares the base types only)
        return str(a) == str(b)
    return a is b or ts.same_type(a, b) or str(a) == str(b)


#: calls.CallChecker, imported on first use (calls imports this module): once, not in
#: every ExprChecker (a function-level import costs microseconds, some 800 a corpus round).
_CALL_CHECKER = None


def _call_checker():
    global _CALL_CHECKER
    from .calls import CallChecker

    _CALL_CHECKER = CallChecker
    return CallChecker


class ExprChecker:
    """Types expressions inside one scope."""

    def __init__(self, ctx: Context, scope: Scope, declared: bool = False):
        """`declared`: every name of `scope` is declared (a body's checker, after the
        declarations): a variable it names is then kept (`_variables`) for the next
        name of the same spelling.  Not so while the declarations are checked: a name
        looked up there may be declared after, or shadowed by a later local.  The
        declarations' checker becomes the body's by setting it (`Declarations.body_checker`)."""
        self.ctx = ctx
        self.scope = scope
        self.declared = declared
        self._variables: dict[str, object] = {}
        self.program = ctx.program
        self.loop_vars: list = []  # Symbols of the enclosing FOR loops
        self.storing = None        # the target check_store is typing (written, not read)
        self._untyped_memo: dict[int, bool] = {}
        self._calls = None

    @property
    def calls(self):
        """The CallChecker of this scope, made at its first call (most bodies' and
        declarations' checkers meet none)."""
        if self._calls is None:
            self._calls = (_CALL_CHECKER or _call_checker())(self)
        return self._calls

    def untyped(self, e) -> bool:
        return is_untyped_constant(e, self._untyped_memo)

    # ------------------------------------------------------------ recording
    def record(self, e, t, value=NOT_CONSTANT):
        if isinstance(t, T.SubrangeType):
            # A subrange variable reads as its base type; its limits are kept apart
            # (`subranges`) for a store into it and a reference to it.
            self.program.subranges[id(e)] = t
            t = T.ELEMENTARY[t.name]
        self.program.expr_types[id(e)] = t
        if value is NOT_CONSTANT or value is None or t is ts.ERROR:
            return t
        limits = ts.INT_RANGES.get(id(t))
        if limits is not None and type(value) is int and limits[0] <= value <= limits[1] \
                or id(t) in ts.STORED_AS_IS:
            self.program.constants[id(e)] = value    # (what either way below gives it)
        else:
            self.program.constants[id(e)] = value if self._keeps_exact(e, value, t) \
                else ts.coerce_constant(value, t)
        return t

    def _keeps_exact(self, e, value, t) -> bool:
        """Whether a folded `+ - * / MOD` (or unary minus) keeps its value unrounded.

        A folded constant must be the value the same expression has at run
        time.  The run time computes integers exactly (`INT#-32768 / -1` is
        32768) and wraps them only where they are stored, unless the dialect
        wraps inside expressions (`Dialect.wraps_in_expressions`, the NJ):
        under `iec`, `(C + 1) / 2` with C = INT#32767 is 16384 whether C is a
        CONSTANT or a variable.  Likewise a REAL result stays a double
        unless the dialect rounds each operation
        (`Dialect.rounds_real_operations`).
        """
        if not (isinstance(e, (ast.Binary, ast.Unary)) and e.op in ("+", "-", "*", "/", "MOD")
                and isinstance(t, T.ElementaryType)):
            return False
        if isinstance(value, int) and not isinstance(value, bool) and t.kind == "int":
            return not self.ctx.rules.wraps_in_expressions
        # A REAL result: a double until stored, unless the dialect rounds each operation.
        return isinstance(value, float) and t.kind == "real" and not self.ctx.rules.rounds_real_operations

    def constant(self, e):
        return self.program.constants.get(id(e), NOT_CONSTANT)

    # ------------------------------------------------------------- entries
    def infer(self, e, expected=None, strict: bool = False):
        """The type of `e`; `expected` is the context's type (a hint for
        untyped literals and enumeration values); `strict` makes an untyped
        constant that does not fit `expected` an error."""
        if e is None:
            return ts.ERROR
        maybe, typer = _TYPERS[type(e)]
        if maybe and (e.type_prefix is None if maybe is _LITERAL
                      else is_untyped_constant(e, self._untyped_memo)):
            settled = self.settle(e, expected, strict)
            if settled is not None:
                return settled
        return typer(self, e, expected)

    def check_value(self, e, dst, what: str):
        """Type `e` for storing into type `dst`; report when it cannot be."""
        src = self.infer(e, dst, strict=True)
        if src is dst and type(dst) in _SELF_ASSIGNABLE:
            return src       # (what `require_assignable` finds at once; no string to shorten)
        if self.require_assignable(src, dst, start_pos(e), what) and isinstance(e, ast.StringLiteral) \
                and isinstance(dst, T.StringType) and T.string_size(e.value, self.ctx.dialect) > dst.length:
            size, unit = T.string_size(e.value, self.ctx.dialect), T.STRING_UNITS[self.ctx.dialect]
            self.ctx.warning("W-TYPE-001", f"{what}: string of {size} {unit}s is truncated to {dst}", e.pos)
        return src

    def require_assignable(self, src, dst, pos, what: str) -> bool:
        if src is ts.ERROR or dst is ts.ERROR:
            return True
        if isinstance(dst, (T.RefType, T.InterfaceType)) and src is T.NULL:
            return True
        if isinstance(dst, T.RefType):
            if isinstance(src, T.RefType) and same_referenced(src.target, dst.target):
                return True
            self.ctx.error("E-TYPE-004", f"{what}: expected {dst}, found {src}"
                           + ("; take a reference with REF(...)" if not isinstance(src, T.RefType) else ""),
                           pos)
            return False
        if isinstance(dst, T.InterfaceType):
            if assignable_reference(src, dst):
                return True     # the variable now refers to that instance (no copy)
            self.ctx.error("E-TYPE-004", f"{what}: expected an instance of an FB that implements "
                           f"{dst}, found {src}", pos)
            return False
        if isinstance(src, T.FBType) or isinstance(dst, T.FBType):
            self.ctx.error("E-TYPE-016", f"{what}: function block instances cannot be copied "
                           f"(found {src}, expected {dst})", pos)
            return False
        if ts.implicitly_converts(src, dst) or self._dialect_casts(src, dst):
            return True
        self.ctx.error("E-TYPE-004", f"{what}: expected {dst}, found {src}"
                       f"{ts.conversion_hint(src, dst)}", pos)
        return False

    def _dialect_casts(self, src, dst) -> bool:
        """An assignment the dialect casts where IEC 61131-3 needs a conversion
        (`Dialect.signed_to_unsigned_assignment`: `UintVar := IntVar` on the NJ)."""
        return (self.ctx.rules.signed_to_unsigned_assignment and ts.is_int(src) and ts.is_int(dst)
                and src.signed and not dst.signed and dst.bits >= src.bits)

    # --------------------------------------------- untyped constant folding
    def _fold_exact(self, e, values: dict):
        """Exact value of an untyped constant expression; fills `values`."""
        if isinstance(e, ast.IntLiteral):
            v = e.value
        elif isinstance(e, ast.RealLiteral):
            v = float(e.value)
        elif isinstance(e, ast.Unary):
            v = apply_unary(e.op, self._fold_exact(e.operand, values))
        else:
            v = apply_binary(e.op, self._fold_exact(e.left, values), self._fold_exact(e.right, values))
        values[id(e)] = v
        if v is NOT_CONSTANT:
            raise _Unfoldable()
        return v

    def settle(self, e, expected, strict: bool):
        """Type an untyped constant expression (see the module docstring).

        Returns None when it cannot be folded (e.g. `1.5 MOD 2`): the caller
        then types it operator by operator and reports what is wrong.
        """
        if type(e) is ast.IntLiteral:
            if expected is T.BOOL and e.value in (0, 1):
                # IEC 61131-3 6.3.2: a BOOL literal is 0, 1, TRUE or FALSE (Annex F
                # writes `BOOL := 0`); only the bare digit, not `1 - 0`.
                return self.record(e, T.BOOL, bool(e.value))
            if isinstance(expected, T.ElementaryType) and expected.kind in ("int", "bits") \
                    and ts.fits(e.value, expected):
                # A lone literal that fits the integer type it is expected as (`x + 1`, `n := 5`),
                # the commonest case: that type, what `_settle_folded` gives it.
                return self.record(e, expected, e.value)
        return self._settle_folded(e, expected, strict)

    def _settle_folded(self, e, expected, strict: bool):
        """`settle` the general way: the exact value of every node, then the type."""
        values: dict[int, object] = {}
        try:
            value = self._fold_exact(e, values)
        except DivisionByZero:
            self.ctx.error("E-TYPE-017", "division by zero in a constant expression", e.pos)
            self._record_tree(e, lambda n: ts.ERROR, {})
            return ts.ERROR
        except _Unfoldable:
            return None
        if isinstance(value, float):
            t = expected if ts.is_real(expected) else T.LREAL
            too_large = _beyond_real_range(value, t, e) if strict else None
            if too_large:
                what, where = too_large
                self.ctx.error("E-TYPE-005", f"{what} does not fit {t} "
                               f"(largest magnitude {_REAL_MAX[t.bits]})", where.pos)
                self._record_tree(e, lambda n: ts.ERROR, {})
                return ts.ERROR
            self._record_tree(e, lambda n: t, values)
            return t
        ints = [v for v in values.values() if isinstance(v, int)]
        if ts.is_real(expected) and _is_plain_literal(e):
            t = expected
        elif isinstance(expected, T.ElementaryType) and expected.kind in ("int", "bits"):
            if ts.fits(value, expected):
                t = expected
            elif strict:
                self.ctx.error("E-TYPE-005", f"constant {value} does not fit {expected} "
                               f"(range {_range(expected)})", e.pos)
                self._record_tree(e, lambda n: ts.ERROR, {})
                return ts.ERROR
            else:
                t = ts.smallest_int_type(*ints)
        else:
            t = ts.smallest_int_type(*ints)
        if t is None:
            self.ctx.error("E-TYPE-005", f"integer constant {value} is larger than any integer "
                           f"type (ULINT holds up to {T.ULINT.max})", e.pos)
            self._record_tree(e, lambda n: ts.ERROR, {})
            return ts.ERROR

        def node_type(n):
            v = values.get(id(n))
            if not isinstance(v, int) or ts.is_real(t) or ts.fits(v, t):
                return t
            own = ts.smallest_int_type(v) or T.ULINT
            return ts.common_type(t, own) or own

        self._record_tree(e, node_type, values)
        return t

    def _record_tree(self, e, type_for, values):
        self.record(e, type_for(e), values.get(id(e), NOT_CONSTANT))
        if isinstance(e, ast.Unary):
            self._record_tree(e.operand, type_for, values)
        elif isinstance(e, ast.Binary):
            self._record_tree(e.left, type_for, values)
            self._record_tree(e.right, type_for, values)

    # ------------------------------------------------------------ literals
    def _IntLiteral(self, e, expected):
        t = T.ELEMENTARY.get(key(e.type_prefix or "DINT"))
        if t is None:
            self.ctx.error("E-DECL-004", f"unknown type prefix {e.type_prefix}# on a literal", e.pos)
            return self.record(e, ts.ERROR)
        if t.kind in ("int", "bits", "bool"):
            if not ts.fits(e.value, t):
                self.ctx.error("E-TYPE-005", f"literal {e.value} does not fit {t} (range {_range(t)})", e.pos)
                return self.record(e, ts.ERROR)
            value = bool(e.value) if t is T.BOOL else e.value
            return self.record(e, t, value)
        if t.kind == "real":
            return self.record(e, t, float(e.value))
        self.ctx.error("E-TYPE-004", f"integer literal with prefix {t}#: expected a numeric "
                       f"or bit-string type, found {t}", e.pos)
        return self.record(e, ts.ERROR)

    def _RealLiteral(self, e, expected):
        t = T.ELEMENTARY.get(key(e.type_prefix or "LREAL"))
        if t is None or t.kind != "real":
            found = t if t is not None else e.type_prefix
            self.ctx.error("E-TYPE-004", f"real literal {e.value}: expected a REAL or LREAL "
                           f"prefix, found {found}#", e.pos)
            return self.record(e, ts.ERROR)
        return self.record(e, t, float(e.value))

    def _BoolLiteral(self, e, expected):
        return self.record(e, T.BOOL, bool(e.value))

    def _StringLiteral(self, e, expected):
        size = len(e.value) if e.wide else T.string_size(e.value, self.ctx.dialect)
        return self.record(e, T.StringType(max(size, 1), e.wide), e.value)

    def _TimeLiteral(self, e, expected):
        return self.record(e, T.TIME, e.nanoseconds)

    def _DateTimeLiteral(self, e, expected):
        t = {"DATE": T.DATE, "TOD": T.TOD, "DT": T.DT}.get(e.kind, T.DT)
        return self.record(e, t, e.nanoseconds)

    def _EnumLiteral(self, e, expected, written=None):
        """`Color#Red`; `written` is the node to type when the value was written
        otherwise (CODESYS's `Color.Red`)."""
        t = self.program.types.get(key(e.type_name))
        node = e if written is None else written
        if not isinstance(t, T.EnumType):
            if t is None:
                self.ctx.error("E-DECL-004", f"unknown enumeration type '{e.type_name}'", e.pos)
            else:
                self.ctx.error("E-TYPE-015", f"'{e.type_name}#{e.value_name}': expected an "
                               f"enumeration type before '#', found {t}", e.pos)
            return self.record(node, ts.ERROR)
        entry = t.values.get(key(e.value_name))
        if entry is None:
            names = ", ".join(n for n, _ in t.values.values())
            self.ctx.error("E-TYPE-015", f"'{e.value_name}' is not a value of {t.name} "
                           f"(values: {names})", e.pos)
            return self.record(node, ts.ERROR)
        return self.record(node, t, entry[1])

    # ------------------------------------------------------------- names
    def _Name(self, e, expected):
        sym = self._variables.get(e.name)
        if sym is not None:     # met before: what the look-up and `record` give it, at once
            self.program.name_refs[id(e)] = sym
            self.program.expr_types[id(e)] = t = sym.type
            return t
        sym = self.scope.lookup(e.name)
        if sym is not None:
            self.program.name_refs[id(e)] = sym
            value = self.ctx.symbol_values.get(id(sym), NOT_CONSTANT)
            t = sym.type
            if value is NOT_CONSTANT and not isinstance(t, T.SubrangeType):     # a plain variable
                if self.declared:
                    self._variables[e.name] = sym
                self.program.expr_types[id(e)] = t      # (all `record` does with it)
                return t
            return self.record(e, t, value)
        enums = self.ctx.enum_values.get(key(e.name))
        if enums:
            if expected in enums:
                enum = expected
            elif len(enums) == 1:
                enum = enums[0]
            else:
                names = " or ".join(f"{t.name}#{e.name}" for t in enums)
                self.ctx.error("E-TYPE-015", f"enumeration value '{e.name}' is ambiguous: "
                               f"write {names}", e.pos)
                return self.record(e, ts.ERROR)
            value = enum.values[key(e.name)][1]
            self.program.name_refs[id(e)] = value
            return self.record(e, enum, value)
        self.report_not_a_value(e)
        return self.record(e, ts.ERROR)

    def report_not_a_value(self, e: ast.Name) -> None:
        k = key(e.name)
        pou = self.program.pous.get(k)
        if pou is not None:
            self.ctx.error("E-TYPE-016", f"'{e.name}' is a {pou.kind}, not a variable"
                           + (f"; call it as {e.name}(...)" if pou.kind == "FUNCTION" else ""), e.pos)
            return
        if k in self.program.types or k in T.ELEMENTARY:
            self.ctx.error("E-TYPE-016", f"'{e.name}' is a type, not a variable", e.pos)
            return
        hint = self._suggest(e.name)
        self.ctx.error("E-DECL-001", f"undeclared name '{e.name}'{hint}", e.pos)

    def _suggest(self, name: str) -> str:
        candidates = {}
        if self.scope.pou is not None:
            candidates.update({k: s.name for k, s in self.scope.pou.variables.items()})
        candidates.update({k: s.name for k, s in self.program.globals.items()})
        close = difflib.get_close_matches(key(name), list(candidates), n=1, cutoff=0.8)
        return f" (did you mean '{candidates[close[0]]}'?)" if close else ""

    def _Member(self, e, expected):
        if isinstance(e.base, ast.Name) and self._enum_type_before_dot(e):
            if not self.ctx.accepts("ENUM_DOT", e.pos):          # CODESYS's E_Color.Red
                return self.record(e, ts.ERROR)
            return self._EnumLiteral(ast.EnumLiteral(e.base.name, e.name, pos=e.pos), expected, e)
        if isinstance(e.base, ast.Name) and key(e.base.name) in self.ctx.namespaces \
                and self.scope.lookup(e.base.name) is None:
            return self._namespace_member(e)
        base = self.infer(e.base)
        if base is ts.ERROR:
            return self.record(e, ts.ERROR)
        k = key(e.name)
        if isinstance(base, T.StructType):
            entry = base.fields.get(k)
            if entry is None:
                names = ", ".join(n for n, _ in base.fields.values())
                self.ctx.error("E-TYPE-009", f"struct {base.name} has no member '{e.name}' "
                               f"(members: {names})", e.pos)
                return self.record(e, ts.ERROR)
            return self.record(e, entry[1])
        if isinstance(base, T.FBType):
            sym = base.variables.get(k)
            if sym is None and base.info is not None:
                getter, setter = find_property(base.info, e.name)
                if getter is not None or setter is not None:       # a PROPERTY
                    accessor = getter or setter
                    if not may_call(accessor, self.scope.fb):
                        self.ctx.error("E-CALL-012", f"property {base.name}.{e.name} is "
                                       f"{accessor.access}", e.pos)
                    if getter is None and e is not self.storing:    # read, not written
                        self.ctx.error("E-TYPE-018", f"property {base.name}.{e.name} has no GET "
                                       "and cannot be read", e.pos)
                    self.program.properties[id(e)] = (getter, setter)
                    t = getter.return_type if getter is not None else \
                        next(iter(setter.variables.values())).type
                    return self.record(e, t)
            if sym is None:
                foreign = self.ctx.foreign_pin(base.name, e.name)
                if foreign is not None:
                    self.ctx.error("E-PIN-001", foreign, e.pos)
                else:
                    self.ctx.error("E-TYPE-009", f"function block {base.name} has no variable "
                                   f"'{e.name}'", e.pos)
                return self.record(e, ts.ERROR)
            # IEC 61131-3 2nd ed. Table 2.5.2.1a / 3rd ed. 6.6.3.2: an in-out may
            # be read outside the instance (`IF FB1.INOUT THEN`), not assigned.
            inside = isinstance(e.base, ast.Name) and key(e.base.name) == "THIS"
            if sym.kind not in ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT") and not inside \
                    and not self.ctx.open_instances:
                self.ctx.error("E-TYPE-009", f"'{e.name}' is a {sym.kind} of {base.name}: only "
                               f"inputs, outputs and in-outs are visible outside the instance", e.pos)
                return self.record(e, ts.ERROR)
            return self.record(e, sym.type)
        self.ctx.error("E-TYPE-009", f"'.{e.name}': expected a struct or function block "
                       f"instance, found {base}", e.pos)
        return self.record(e, ts.ERROR)

    def _namespace_member(self, e: ast.Member):
        """`NS.X` read as a value, NS a NAMESPACE: X names an element declared in NS (IEC
        61131-3 3rd ed. 6.9), a POU or a type, never a variable (a call `NS.F()` is the
        call checker's): say which, rather than "undeclared name 'NS'"."""
        written = f"{e.base.name}.{e.name}"
        item = self.ctx.in_namespace(e.base.name, e.name)
        if isinstance(item, ast.Pou):
            hint = {"FUNCTION_BLOCK": f": declare an instance (inst : {written};) and use the instance",
                    "FUNCTION": f"; call it as {written}(...)"}.get(item.kind, "")
            self.ctx.error("E-TYPE-016", f"'{written}' is a {item.kind}, not a variable{hint}", e.pos)
        elif item is not None:
            self.ctx.error("E-TYPE-016", f"'{written}' is a type, not a variable", e.pos)
        else:
            self.ctx.error("E-DECL-001", f"NAMESPACE {e.base.name} declares no '{e.name}'", e.pos)
        return self.record(e, ts.ERROR)

    def _enum_type_before_dot(self, e: ast.Member) -> bool:
        """`Light.Red` names an enumeration value: `Light` is an enumeration type and
        no variable, or a variable of an enumeration type (which has no members)
        spelled like the type, whose values include `Red` (`state : State :=
        State.Idle` in a case-insensitive language)."""
        enum = self.program.types.get(key(e.base.name))
        if not isinstance(enum, T.EnumType):
            return False
        sym = self.scope.lookup(e.base.name)
        return sym is None or (isinstance(T.resolve_alias(sym.type), T.EnumType)
                               and key(e.name) in enum.values)

    def _Deref(self, e, expected):
        base = self.infer(e.base)
        if base is ts.ERROR:
            return self.record(e, ts.ERROR)
        if not isinstance(base, T.RefType):
            self.ctx.error("E-TYPE-001", f"^: expected a reference (REF_TO or POINTER TO), "
                           f"found {base}", e.pos)
            return self.record(e, ts.ERROR)
        return self.record(e, base.target)

    def _BitAccess(self, e, expected):
        base = self.infer(e.base)
        if base is ts.ERROR:
            return self.record(e, ts.ERROR)
        part = PARTS[e.size]
        width = part.bits
        if not (ts.is_int(base) or ts.is_bits(base)) or (e.bit + 1) * width > base.bits:
            self.ctx.error("E-TYPE-009", f".{'%' + e.size if e.size else ''}{e.bit}: expected an "
                           f"integer or bit string holding part {e.bit} of {width} bit(s), "
                           f"found {base}", e.pos)
            return self.record(e, ts.ERROR)
        return self.record(e, part)

    def _DirectVar(self, e, expected):
        """`%IX0.0` in code: the type declared AT it, else the plain type of its size."""
        address, problem = parse_address(e.address)
        if address is None:
            self.ctx.error("E-DECL-015", problem or f"{e.address}: %I* has no place in the "
                           f"process image to read", e.pos)
            return self.record(e, ts.ERROR)
        t = self.ctx.direct_types.get(address.text) or T.ELEMENTARY[PLAIN_TYPES[address.size]]
        return self.record(e, t)

    def _NullLiteral(self, e, expected):
        return self.record(e, T.NULL)

    def _Index(self, e, expected):
        base = self.infer(e.base)
        index_types = [self.infer(i, T.DINT) for i in e.indices]
        if base is ts.ERROR:
            return self.record(e, ts.ERROR)
        if not isinstance(base, T.ArrayType):
            self.ctx.error("E-TYPE-006", f"indexing: expected an array, found {base}", e.pos)
            return self.record(e, ts.ERROR)
        if len(e.indices) != len(base.dims):
            self.ctx.error("E-TYPE-006", f"{base} has {len(base.dims)} dimension(s), "
                           f"found {len(e.indices)} index(es)", e.pos)
            return self.record(e, ts.ERROR)
        for n, (index, t, (lo, hi)) in enumerate(zip(e.indices, index_types, base.dims), 1):
            if t is ts.ERROR:
                continue
            if not ts.is_int(t):
                self.ctx.error("E-TYPE-007", f"array index: expected an integer, found {t}", index.pos)
                continue
            value = self.constant(index)
            if isinstance(value, int) and lo is not None and not lo <= value <= hi:
                where = f" of dimension {n}" if len(base.dims) > 1 else ""
                self.ctx.error("E-TYPE-008", f"index {value} is out of bounds {lo}..{hi}{where}", index.pos)
        return self.record(e, base.element)

    # --------------------------------------------------------- operators
    def _Unary(self, e, expected):
        t = self.infer(e.operand, expected)
        if t is ts.ERROR:
            return self.record(e, ts.ERROR)
        value = self.constant(e.operand)
        if e.op == "NOT":
            if not (ts.is_bool(t) or ts.is_bits(t)):
                self.ctx.error("E-TYPE-001", f"NOT: expected BOOL or a bit string, found {t}", e.pos)
                return self.record(e, ts.ERROR)
            if isinstance(value, bool):
                return self.record(e, t, not value)
            if isinstance(value, int):
                return self.record(e, t, ~value & t.max)
            return self.record(e, t)
        if not (ts.is_num(t) or t is T.TIME):
            self.ctx.error("E-TYPE-001", f"unary {e.op}: expected a number or TIME, found {t}", e.pos)
            return self.record(e, ts.ERROR)
        return self.record(e, t, apply_unary(e.op, value))

    def _Binary(self, e, expected):
        op = e.op
        left_untyped = is_untyped_constant(e.left, self._untyped_memo)
        right_untyped = is_untyped_constant(e.right, self._untyped_memo)
        if left_untyped and not right_untyped:
            rt = self.infer(e.right)
            lt = self.infer(e.left, self._hint(op, rt, expected, left=True))
        else:   # the base of ** takes the context's real type (`r := 2.0 ** 3` is REAL)
            lt = self.infer(e.left, self._hint(op, None, expected, left=True) if op == "**" else None)
            rt = self.infer(e.right, self._hint(op, lt, expected, left=False))
        t = self._binary_type(e, lt, rt)
        if t is ts.ERROR:
            return self.record(e, ts.ERROR)
        value = NOT_CONSTANT
        left, right = self.constant(e.left), self.constant(e.right)
        if op in ("/", "MOD") and ts.is_int(t) and self.ctx.rules.omron_integer_ranking:
            # UDINT / DINT divides as UDINT: a DINT -1 is 4294967295 there
            left, right = (v if v is NOT_CONSTANT else ts.coerce_constant(v, t) for v in (left, right))
        try:
            value = apply_binary(op, left, right)
        except DivisionByZero:
            self.ctx.error("E-TYPE-017", "division by zero in a constant expression", e.pos)
            return self.record(e, ts.ERROR)
        if op in ("/", "MOD") and ts.is_int(rt) and self.constant(e.right) == 0:
            self.ctx.error("E-TYPE-017", "division by zero in a constant expression", e.right.pos)
            return self.record(e, ts.ERROR)
        if t is T.TIME and op in ("*", "/") and value is not NOT_CONSTANT:
            ns, k = self.constant(e.left), self.constant(e.right)
            value = _time_scaled(op, *((ns, k) if lt is T.TIME else (k, ns)))
        return self.record(e, t, value)

    def _hint(self, op, other, expected, left: bool):
        """The context type for an operand, given the other operand's type."""
        if op == "**":
            if left:
                return expected if ts.is_real(expected) else T.LREAL
            return None
        if other is ts.ERROR or other is T.TIME:
            return None
        if isinstance(other, (T.ElementaryType, T.EnumType)):
            return other
        return None

    def _binary_type(self, e, lt, rt):
        op = e.op
        if lt is ts.ERROR or rt is ts.ERROR:
            return ts.ERROR
        shown = "AND" if op == "&" else op
        if op in LOGIC:
            for t in (lt, rt):
                if not (ts.is_bool(t) or ts.is_bits(t)):
                    self.ctx.error("E-TYPE-001", f"{shown}: expected BOOL or bit-string operands, "
                                   f"found {t}", e.pos)
                    return ts.ERROR
            return self._common(e, lt, rt)
        if op in COMPARISON:
            return self._comparison(e, lt, rt)
        time_result = self._time_arithmetic(op, lt, rt)
        if time_result is not None:
            return time_result
        if op == "**":
            if not ts.is_real(lt):
                self.ctx.error("E-TYPE-001", f"**: expected a REAL or LREAL base, found {lt}"
                               f"{ts.conversion_hint(lt, T.LREAL)}", e.pos)
                return ts.ERROR
            if not ts.is_num(rt):
                self.ctx.error("E-TYPE-001", f"**: expected a numeric exponent, found {rt}", e.pos)
                return ts.ERROR
            return lt
        if op == "MOD":
            for t in (lt, rt):
                if not ts.is_int(t):
                    self.ctx.error("E-TYPE-001", f"MOD: expected integer operands, found {t}", e.pos)
                    return ts.ERROR
            return self._common(e, lt, rt)
        for t in (lt, rt):
            if not ts.is_num(t):
                self.ctx.error("E-TYPE-001", f"{op}: expected numeric operands (ANY_NUM), found {t}"
                               + self._time_hint(op, lt, rt), e.pos)
                return ts.ERROR
        return self._common(e, lt, rt)

    @staticmethod
    def _time_hint(op, lt, rt) -> str:
        if T.TIME in (lt, rt):
            return "; TIME allows TIME + TIME, TIME - TIME, TIME * number, TIME / number"
        return ""

    @staticmethod
    def _time_arithmetic(op, lt, rt):
        """Result of IEC time arithmetic, or None if this is not one."""
        table = _TIME_SUMS.get(op)
        if table is not None:
            return table.get((getattr(lt, "name", None), getattr(rt, "name", None)))
        if op in ("*", "/"):
            if lt is T.TIME and ts.is_num(rt):
                return T.TIME
            if op == "*" and rt is T.TIME and ts.is_num(lt):
                return T.TIME
        return None

    def _common(self, e, lt, rt):
        if self.ctx.rules.omron_integer_ranking and e.op in ARITHMETIC \
                and ts.is_int(lt) and ts.is_int(rt):
            return ts.omron_ranked(lt, rt)
        c = ts.common_type(lt, rt)
        if c is None:
            self.ctx.error("E-TYPE-002", f"{e.op}: operands {lt} and {rt} have no common type; "
                           f"convert one explicitly (e.g. {ts.short_name(lt)}_TO_{ts.short_name(rt)})"
                           if isinstance(lt, T.ElementaryType) and isinstance(rt, T.ElementaryType)
                           else f"{e.op}: operands {lt} and {rt} have no common type", e.pos)
            return ts.ERROR
        return c

    def _comparison(self, e, lt, rt):
        def comparable(t):
            return isinstance(t, (T.ElementaryType, T.StringType, T.EnumType))

        references = (T.RefType, T.NullType, T.InterfaceType)
        if e.op in ("=", "<>") and isinstance(lt, references) and isinstance(rt, references):
            return T.BOOL       # the same variable / instance, or both NULL

        for t in (lt, rt):
            if not comparable(t):
                self.ctx.error("E-TYPE-001", f"{e.op}: expected elementary, string or enumeration "
                               f"operands, found {t}", e.pos)
                return ts.ERROR
        if isinstance(lt, T.EnumType) or isinstance(rt, T.EnumType):
            if lt is not rt:
                self.ctx.error("E-TYPE-002", f"{e.op}: cannot compare {lt} with {rt}", e.pos)
                return ts.ERROR
            return T.BOOL
        if ts.is_string(lt) and ts.is_string(rt) and lt.wide == rt.wide:
            return T.BOOL
        c = ts.common_type(lt, rt)
        if c is None:
            self.ctx.error("E-TYPE-002", f"{e.op}: cannot compare {lt} with {rt}"
                           + (f"; convert one explicitly (e.g. {ts.short_name(lt)}_TO_{ts.short_name(rt)})"
                              if isinstance(lt, T.ElementaryType) and isinstance(rt, T.ElementaryType)
                              else ""), e.pos)
            return ts.ERROR
        return T.BOOL

    # ---------------------------------------------------------------- calls
    def _Call(self, e, expected):
        return self.calls.check_call(e, expected, statement=False)


class _Unfoldable(Exception):
    pass



_REAL_MAX = {32: "3.4028235e+38", 64: "1.7976931348623157e+308"}


def _beyond_real_range(value: float, t, e) -> tuple[str, object] | None:
    """(what, node) beyond the range of REAL/LREAL `t` in a constant: the
    value, finite but rounding to infinity as a REAL (1e40), or a literal no
    double holds (1e400).  A folded 1.0 / 0.0 is +inf on purpose, as at run time."""
    if math.isfinite(value):
        if t.bits == 32 and math.isinf(to_real32(value)):
            return f"constant {value!r}", e
        return None
    literal = _infinite_literal(e)
    return ("a real literal", literal) if literal is not None else None


def _infinite_literal(e):
    if isinstance(e, ast.RealLiteral):
        return e if math.isinf(e.value) else None
    if isinstance(e, ast.Unary):
        return _infinite_literal(e.operand)
    if isinstance(e, ast.Binary):
        return _infinite_literal(e.left) or _infinite_literal(e.right)
    return None

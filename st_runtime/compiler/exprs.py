"""Expressions: ST expressions to Python expressions, with IEC semantics.

Each method returns Python source text.  The rules that keep it fast:
variables are Python locals where the body allows it (see `scope.py`);
array bounds are checked by an inline chained comparison, skipped when a
static range proves the index inside; integer wrapping and float32
rounding happen on stores (`convert`), and only when the value may need it.
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import ast
from ..dialects import DIALECTS
from ..objects import is_aggregate, store_value
from ..process_image import ImageCell, parse_address
from ..types import (
    AliasType,
    SubrangeType,
    ArrayType,
    ElementaryType,
    FBType,
    StringType,
    StructType,
    Type,
    resolve_alias,
    string_size,
)
from .initial import CompileError
from .optimise import Optimisations, absolute, fold, sets, shortcut, wraps
from .pysrc import pyliteral, pyident

_NUMBER_LITERALS = frozenset({ast.IntLiteral, ast.RealLiteral})
_VALUE_LITERALS = _NUMBER_LITERALS | {ast.BoolLiteral, ast.StringLiteral}

# Python source of the comparison/arithmetic operators that map one to one.
_PLAIN_OPS = {"+": "+", "-": "-", "*": "*", "<": "<", ">": ">", "<=": "<=", ">=": ">=",
              "=": "==", "<>": "!="}
_BIT_OPS = {"AND": "&", "&": "&", "OR": "|", "XOR": "^"}


@dataclass
class LValue:
    """A place a value can be stored.

    kind "local": a Python local `name`; "attr": `obj.attr`; "item":
    `obj[key]`; "ref": a `Ref` held in local `name` (elementary VAR_IN_OUT).
    """

    kind: str
    type: Type
    name: str = ""
    obj: str = ""
    key: str = ""
    inner: "LValue | None" = None     # kind "bit": the integer holding the bit `key`

    @property
    def target(self) -> str:
        if self.kind == "local":
            return self.name
        if self.kind == "attr":
            return f"{self.obj}.{self.key}"
        if self.kind == "item":
            return f"{self.obj}[{self.key}]"
        raise AssertionError("a ref has no Python target")

    def read(self) -> str:
        if self.kind == "prop":            # a PROPERTY: its getter
            return f"{self.obj}.{self.name}(_ctx)"
        if self.kind == "ref":
            return f"{self.name}.get()"
        if self.kind == "bit":
            width = self.type.bits
            shift = int(self.key) * width
            if width == 1:
                return f"({self.inner.read()} >> {shift} & 1 == 1)"
            return f"({self.inner.read()} >> {shift} & {(1 << width) - 1})"
        return self.target

    def _with_bit(self, value: str) -> str:
        t = self.inner.type
        width = self.type.bits
        return (f"_setbit({self.inner.read()}, {int(self.key) * width}, {width}, {value}, "
                f"{t.bits}, {bool(t.signed)})")

    def store(self, value: str) -> str:
        if self.kind == "prop":            # its setter
            return f"{self.obj}.{self.key}(_ctx, {value})"
        if self.kind == "ref":
            return f"{self.name}.set({value})"
        if self.kind == "bit":
            return self.inner.store(self._with_bit(value))
        return f"{self.target} = {value}"

    def store_expr(self, value: str) -> str:
        """An expression that stores `value` (inside a larger expression)."""
        if self.kind == "bit":
            return self.inner.store_expr(self._with_bit(value))
        if self.kind == "prop":
            return self.store(value)
        if self.kind == "local":
            return f"({self.name} := {value})"
        if self.kind == "attr":
            return f"_setattr({self.obj}, {self.key!r}, {value})"
        if self.kind == "item":
            return f"{self.obj}.__setitem__({self.key}, {value})"
        return f"{self.name}.set({value})"

    def ref(self) -> str:
        """An expression for a reference to this place (VAR_IN_OUT)."""
        if self.kind == "attr":
            return f"_AttrRef({self.obj}, {self.key!r})"
        if self.kind == "item":
            return f"_ItemRef({self.obj}, {self.key})"
        if self.kind == "ref":
            return self.name
        raise AssertionError("a plain local cannot be referenced; the scope makes it a cell")


def elementary(t) -> ElementaryType | None:
    while isinstance(t, AliasType):         # (resolve_alias, inline: asked of every operand)
        t = t.target
    return t if isinstance(t, ElementaryType) else None


def is_int_like(t) -> bool:
    e = elementary(t)
    return e is not None and e.kind in ("int", "bits", "time", "date", "tod", "dt")


def is_real(t) -> bool:
    e = elementary(t)
    return e is not None and e.kind == "real"


def int_bounds(t) -> tuple[int, int] | None:
    """The stored range of an integer-like type, None for others."""
    e = elementary(t)
    if e is None:
        return None
    if e.kind in ("int", "bits"):
        return e.min, e.max
    if e.kind in ("time", "date", "tod", "dt"):
        return -(1 << 63), (1 << 63) - 1
    if e.kind == "bool":
        return 0, 1
    return None


_UNTYPED = object()      # (`ExprCompiler.ty`: no type looked up yet)


class ExprCompiler:
    """Compiles expressions of one POU body; `scope` says where names live."""

    def __init__(self, program, pou, scope, unit):
        self.program = program
        self.pou = pou
        self.scope = scope
        self.unit = unit              # the CompileUnit: namespace, functions, classes
        self.temp_count = 0
        self.temp_floor = 0           # temps up to this one stay taken (`lasting_temp`)
        self.temp_high = 0            # the highest temp given
        self.known_ranges: dict[str, tuple[int, int]] = {}   # upper var name -> range
        self._index_probe: dict[str, list] = {}   # FOR variable -> (lo, hi) of checks on it (statements._versioned)
        self.loops: list = []      # FOR loops being compiled, innermost last (hoisting)
        self.opt = getattr(unit, "optimise", None) or Optimisations.none()
        self.unrolled: dict[str, int] = {}   # FOR variable -> its value in this unrolled copy
        self.unrolled_stores: dict[str, tuple] = {}  # FOR variable -> (LValue, type): RETURN stores it
        self.region = None                   # optimise.cse.Region while one is compiled
        self.reuse = None                    # optimise.reuse.Reuse of a body (statements.py)
        self.logic_parts: dict[int, tuple[str, str]] = {}   # optimise/shortcut.py
        self.logic_short: set[int] = set()                   # ids of AND/ORs compiled as and/or (shortcut)
        self.plain_chains: set[int] = set()  # ids of OR/AND chains without a run for optimise/sets.py
        # Memos of one body's compile (an unrolled loop compiles its body once per copy):
        self._types: dict[int, Type | None] = {}    # id(expr) -> `ty` (the checker's types do not change)
        self._wheres: dict[tuple, str] = {}         # (file, line, col) -> `where`
        self._x_methods: dict[type, object] = {}    # node class -> its x_ method (`expr`)
        self._arrays: dict[int, tuple] = {}         # id(Index of a name) -> (Index, its type, its code)
        dialect = DIALECTS[getattr(program, "dialect", "iec")]
        self._wraps = dialect.wraps_in_expressions       # (`settled`)
        self._rounds = dialect.rounds_real_operations    # (`rounds_real`)

    # ------------------------------------------------------------ helpers

    def temp(self) -> str:
        self.temp_count += 1
        self.temp_high = max(self.temp_high, self.temp_count)
        return f"_t{self.temp_count}"

    def lasting_temp(self) -> str:
        """A temp set where other statements run too (a loop's hoisted value, before the
        loop; a per-iteration value, at the top of its body): a number no statement had,
        and none takes again (`temps`, statements.py)."""
        self.temp_high += 1
        self.temp_count = self.temp_floor = self.temp_high
        return f"_t{self.temp_count}"

    def ty(self, expr) -> Type | None:
        key = id(expr)
        t = self._types.get(key, _UNTYPED)
        if t is _UNTYPED:       # (half the asks are the first for their node: no KeyError raised)
            t = self.program.expr_types.get(key)
            t = self._types[key] = resolve_alias(t) if t is not None else None
        return t

    def where(self, node) -> str:
        """A constant tuple naming the position of `node` for fault records."""
        pos = node.pos
        place = (pos.file, pos.line, pos.col)
        text = self._wheres.get(place)
        if text is None:
            text = self._wheres[place] = pyliteral((self.pou.name,) + place)
        return text

    def fail(self, message: str, node):
        raise CompileError(message, node.pos)

    # --------------------------------------------------------- constants

    def folded(self, expr):
        """The checker's folded value of `expr` when it fits the expression's type.

        (The checker folds TIME * real to whole nanoseconds as `values.time_mul`
        does; a non-integral float for an integer or TIME expression would be
        a checker bug, and is left to the compiled code, which rounds.)
        """
        value = self.program.constants.get(id(expr))
        if isinstance(value, float) and not value.is_integer() and is_int_like(self.ty(expr)):
            return None
        return value

    def constant_of(self, expr):
        """The folded value of `expr`, or None when it is not constant."""
        value = self.program.constants.get(id(expr))       # (`folded`, inline: asked most often)
        if value is not None and not (isinstance(value, float) and not value.is_integer()
                                      and is_int_like(self.ty(expr))):
            return value
        cls = type(expr)            # (the node classes have no subclasses)
        if cls is ast.Name:
            return self.unrolled.get(expr.name.upper()) if self.unrolled else None
        if cls is ast.Index:
            return fold.constant_element(self, expr) if self.opt.fold else None
        if cls in _VALUE_LITERALS:
            return expr.value
        if cls is ast.TimeLiteral or cls is ast.DateTimeLiteral:
            return expr.nanoseconds
        if cls is ast.Unary and expr.op == "-" and type(expr.operand) in _NUMBER_LITERALS:
            return -expr.operand.value
        if cls is ast.Binary and self.unrolled and expr.op in ("+", "-", "*"):
            return fold.constant_integer(self, expr)     # `Row - 1` in an unrolled copy
        return None

    def literal(self, value, t) -> str:
        """A constant as Python source, in the representation of type `t`."""
        e = elementary(t)
        if e is not None:
            if e.kind == "real":
                value = float(value)
                if e.bits == 32:
                    from .support import f32
                    value = f32(value)
            elif e.kind == "bool":
                value = bool(value)
            elif isinstance(value, float) and value.is_integer():
                value = int(value)
        return pyliteral(value)

    def static_range(self, expr) -> tuple[int, int] | None:
        """A range that contains every value `expr` can take, when known."""
        value = self.constant_of(expr)
        if isinstance(value, int) and not isinstance(value, bool):
            return value, value
        if isinstance(expr, ast.Name):
            return self.known_ranges.get(expr.name.upper())
        if isinstance(expr, ast.Index) and isinstance(expr.base, ast.Name):
            return self.constant_array_range(expr.base)
        if isinstance(expr, ast.Binary) and expr.op in ("+", "-"):
            a = self.static_range(expr.left)
            b = self.static_range(expr.right)
            if a and b:
                if expr.op == "+":
                    return a[0] + b[0], a[1] + b[1]
                return a[0] - b[1], a[1] - b[0]
        return None

    def settled(self, expr, code: str) -> str:
        """`code` of `expr` as a value of the expression's own integer type.

        `+ - *` and unary minus run on exact Python integers, wrapped when
        stored: the stored result of any chain of them in one type (and of
        bit operations on them) is the same as with a wrap after every
        operation; an operand of a narrower type is settled where a wider
        `+ - *` takes it (`settled_narrower`).  Where the exact value itself
        would be seen (a comparison, a division or MOD, a conversion, an
        argument of a standard function, a CASE selector, an array index, a
        store into a wider type) it is wrapped first; so is a quotient,
        whose one overflow is `INT#-32768 / -1` (the same rule, not shown on
        its own in W501).  The NJ evaluates the right-hand
        side in the data type of its highest-ranked operand, and a result
        out of that type's range overflows ("NJ-series CPU Unit Software
        User's Manual" W501, 6-5-3 Structured Text, Implicit Casts:
        `(UdintVar + DintVar) / DINT#2` with UDINT#16#FFFF_FFFF and 1
        assigns 0 to a LINT: the checker types that sum UDINT by OMRON's
        ranking, `Dialect.omron_integer_ranking`).
        Only under a dialect that says so (`Dialect.wraps_in_expressions`).
        """
        if not self._wraps:
            return code
        if not ((isinstance(expr, ast.Binary) and expr.op in ("+", "-", "*", "/"))
                or (isinstance(expr, ast.Unary) and expr.op == "-")):
            return code
        e = elementary(self.ty(expr))
        bounds = int_bounds(e)
        if bounds is None or e.kind == "bool" or isinstance(e, SubrangeType):
            return code
        known = self.static_range(expr)
        if known is not None and bounds[0] <= known[0] and known[1] <= bounds[1]:
            return code
        return _wrapped(code, e)

    def settled_expr(self, expr) -> str:
        """`expr` compiled where its exact value would be seen (`settled`)."""
        return self.settled(expr, self.expr(expr))

    def settled_narrower(self, operand, code: str, t) -> str:
        """`settled` for an operand of a `+ - *` of type `t` whose own type is narrower."""
        own, target = elementary(self.ty(operand)), elementary(t)
        if own is None or target is None or own.kind != "int" or own.bits >= target.bits:
            return code
        return self.settled(operand, code)

    def cast_operand(self, operand, code: str, t) -> str:
        """An integer operand of `/` or MOD as a value of the operation's type `t`.

        Only OMRON's ranking (`Dialect.omron_integer_ranking`) gives an
        operation a type that does not hold its operand's values: UDINT / DINT
        is UDINT, and a DINT -1 divides as UDINT 4294967295 (W501 6-5-3).
        """
        target, source = elementary(t), elementary(self.ty(operand))
        if target is None or target.kind != "int" or source is None or source.kind != "int":
            return code
        (lo, hi), (src_lo, src_hi) = int_bounds(target), int_bounds(source)
        if lo <= src_lo and src_hi <= hi:
            return code
        return _wrapped(code, target)

    def constant_array_range(self, name) -> tuple[int, int] | None:
        """(min, max) of the elements of a CONSTANT integer array, else None."""
        try:
            place = self.scope.place_of(name)
        except CompileError:
            return None
        symbol = place.symbol
        if symbol.kind == "VAR_EXTERNAL":       # the global's declaration holds the values
            symbol = self.program.globals.get(name.name.upper(), symbol)
        t = resolve_alias(symbol.type)
        if symbol.init is None or not symbol.constant or not isinstance(t, ArrayType) or int_bounds(t.element) is None:
            return None
        cache = self.unit.constant_ranges
        if id(symbol) not in cache:
            values = self.unit.initial.of_symbol(symbol).maker()
            cache[id(symbol)] = (min(values), max(values)) if values else None
        return cache[id(symbol)]

    # ------------------------------------------------------- expressions

    def expr(self, e) -> str:
        value = self.program.constants.get(id(e))          # (`folded`, inline)
        if value is not None and not isinstance(e, ast.Call) and not (
                isinstance(value, float) and not value.is_integer() and is_int_like(self.ty(e))):
            t = self.ty(e)
            if isinstance(e, ast.Binary) and is_real(t) and not self.rounds_real(t):
                return pyliteral(float(value))     # a REAL operation's result stays a double (iec)
            return self.literal(value, t)
        method = self._x_methods.get(type(e))
        if method is None:
            method = getattr(self, "x_" + type(e).__name__, None)
            if method is None:
                self.fail(f"expression {type(e).__name__} is not supported by the runtime", e)
            self._x_methods[type(e)] = method
        return method(e)

    def x_IntLiteral(self, e):
        return self.literal(e.value, self.ty(e))

    def x_RealLiteral(self, e):
        t = self.ty(e)
        return self.literal(e.value, t if t is not None else None)

    def x_BoolLiteral(self, e):
        return pyliteral(bool(e.value))

    def x_StringLiteral(self, e):
        return pyliteral(e.value)

    def x_TimeLiteral(self, e):
        return pyliteral(e.nanoseconds)

    def x_DateTimeLiteral(self, e):
        return pyliteral(e.nanoseconds)

    def x_EnumLiteral(self, e):
        return pyliteral(self.unit.initial.enum_value(e.type_name, e.value_name, e.pos))

    def x_Name(self, e):
        if self.unrolled and e.name.upper() in self.unrolled:
            return self.literal(self.unrolled[e.name.upper()], self.ty(e))
        ref = self.program.name_refs.get(id(e))
        if isinstance(ref, int) and not isinstance(ref, bool):
            return pyliteral(ref)      # an enumeration value
        if ref is not None and getattr(ref, "constant", False) and ref.init is not None \
                and not is_aggregate(ref.type):
            try:
                return self.literal(self.unit.initial.const(ref.init), ref.type)
            except CompileError:
                pass
        return self._name_read(e)

    def _name_read(self, e) -> str:
        """`self.lvalue(e).read()` of a Name; a Python local's name without an LValue."""
        place = self.scope.place_of(e)
        if place.how == "local" or place.how == "alias":
            return place.name           # (scope.lvalue_of_name's "local" LValue reads its name)
        return self.scope.lvalue_of_name(self, e).read()

    def x_Member(self, e):
        return self.lvalue(e).read()

    def x_Index(self, e):
        if self.opt.fold:
            value = fold.constant_element(self, e)
            if value is not None:
                return self.literal(value, self.ty(e))
        _, obj, key = self._index_place(e)         # (`lvalue(e).read()`, no LValue made)
        code = f"{obj}[{key}]"
        if self.region is not None:
            return self.region.read(code)
        return self.reuse.element(e, code) if self.reuse is not None else code

    def x_Unary(self, e):
        operand = self.expr(e.operand)
        if e.op == "-":
            return f"(-{operand})"
        if e.op == "+":
            return operand
        t = elementary(self.ty(e.operand))
        if t is None or t.kind == "bool":
            return f"(not {operand})"
        return f"({operand} ^ {(1 << t.bits) - 1})"

    def x_Binary(self, e):
        code = self._binary(e)
        if self._rounds and e.op in ("+", "-", "*", "/", "**") and self.rounds_real(self.ty(e)):
            return f"_f32({code})"
        return code

    def rounds_real(self, t) -> bool:
        """Whether a REAL result is rounded to single precision where it is computed
        (`Dialect.rounds_real_operations`, the NJ: W501 6-5-3)."""
        e = elementary(t)
        return (e is not None and e.kind == "real" and e.bits == 32
                and self._rounds)

    def _binary(self, e):
        op = e.op
        if self.opt.sets and op in ("OR", "AND"):
            tests = sets.chain(self, e)         # `X = a OR X = b`: `X in (a, b)`
            if tests is not None:
                return tests
        t = self.ty(e)
        left, right = self.expr(e.left), self.expr(e.right)
        if op not in _BIT_OPS and not (op in ("+", "-", "*") and is_int_like(t)):
            # The exact value of an integer operand is seen here (settled).
            if self._wraps:
                left, right = self.settled(e.left, left), self.settled(e.right, right)
            if op in ("/", "MOD"):
                left, right = self.cast_operand(e.left, left, t), self.cast_operand(e.right, right, t)
        elif op not in _BIT_OPS:
            # An operand of a narrower type is seen by this wider + - *: `DintVar + (IntVar + IntVar)`.
            left, right = self.settled_narrower(e.left, left, t), self.settled_narrower(e.right, right, t)
        if op in _BIT_OPS:
            if self.opt.shortcut:
                shortcut.record(self, e, left, right)      # an IF condition's `and`/`or`
                short = shortcut.of_comparisons(self, e, left, right)
                if short is not None:
                    return short
            return f"({left} {_BIT_OPS[op]} {right})"
        if op == "*" and elementary(t) is not None and elementary(t).kind == "time" \
                and (is_real(self.ty(e.left)) or is_real(self.ty(e.right))):
            # TIME * REAL rounds to the nearest ns, as the NJ's MULTIME (values.time_mul).
            return f"_time_mul({left}, float({right}))" if elementary(self.ty(e.left)).kind == "time" \
                else f"_time_mul({right}, float({left}))"
        if self.opt.inline and op in ("<", "<=", ">", ">="):
            chained = absolute.bounded(self, e, left, right)     # ABS(x) <= C: no call
            if chained is not None:
                return chained
        if op in _PLAIN_OPS:
            if self.reuse is not None:
                kept = self.reuse.binary(e, op, left, right)      # computed before: its name
                if kept is not None:
                    return kept
            shared = self.region.binary(op, left, right, self.out, e is not self.region.whole) \
                if self.region is not None else None
            return shared or f"({left} {_PLAIN_OPS[op]} {right})"
        if op == "/":
            if is_int_like(t):
                if is_real(self.ty(e.right)):   # TIME / REAL: nearest ns, zero is F-DIV-ZERO (values.time_div)
                    return f"_time_div({left}, float({right}))"
                return f"_idiv({left}, {right}, {self.where(e)})"
            divisor = self.constant_of(e.right)
            if isinstance(divisor, (int, float)) and not isinstance(divisor, bool) and divisor != 0:
                return f"({left} / {right})"
            # IEEE 754 on a zero divisor (inf, nan) instead of ZeroDivisionError.
            if right.isidentifier():
                return f"({left} / {right} if {right} else _rdiv({left}, {right}))"
            tmp = self.temp()
            return f"({left} / {tmp} if ({tmp} := {right}) else _rdiv({left}, {tmp}))"
        if op == "MOD":
            return f"_imod({left}, {right}, {self.where(e)})"
        if op == "**":     # as the standard function EXPT (IEEE results, no fault)
            return f"{self.unit.bind_function('EXPT', e.pos)}(float({left}), {right})"
        self.fail(f"operator {op} is not supported by the runtime", e)

    def x_Call(self, e):
        return self.unit.calls.call_expr(self, e)

    def x_Deref(self, e):
        return self.lvalue(e).read()

    def x_BitAccess(self, e):
        return self.lvalue(e).read()

    def x_DirectVar(self, e):
        return self.lvalue(e).read()

    def x_NullLiteral(self, e):
        return "None"

    # ----------------------------------------------------------- places

    def lvalue(self, e) -> LValue:
        """Where a Name/Member/Index expression lives."""
        if isinstance(e, ast.Name):
            return self.scope.lvalue_of_name(self, e)
        if isinstance(e, ast.Member) and id(e) in self.program.properties:
            from . import method_attr      # (compiler/__init__ imports this module)

            getter, setter = self.program.properties[id(e)]
            base = self.aggregate(e.base)
            return LValue("prop", self.ty(e), obj=base,
                          name=method_attr(getter.name, "GET") if getter else "",
                          key=method_attr(setter.name, "SET") if setter else "")
        if isinstance(e, ast.Member):
            base_t = self.ty(e.base)
            base = self.aggregate(e.base)
            t = self.member_type(base_t, e.name, e)
            fb = resolve_alias(base_t) if base_t is not None else None
            if isinstance(fb, FBType) and not is_aggregate(t) and \
                    getattr(fb.variables.get(e.name.upper()), "kind", None) == "VAR_IN_OUT":
                # An elementary in-out read from outside: the Ref the last call connected.
                return LValue("ref", t, name=f"{base}.{pyident(e.name)}")
            return LValue("attr", t, obj=base, key=pyident(e.name))
        if isinstance(e, ast.Index):
            return self.index_lvalue(e)
        if isinstance(e, ast.DirectVar):      # an ImageCell: get/set like a Ref
            t = self.ty(e)
            cell = ImageCell(self.unit.image, parse_address(e.address)[0], t)
            return LValue("ref", t, name=self.unit.register_constant(cell))
        if isinstance(e, ast.BitAccess):
            inner = self.lvalue(e.base)
            inner.type = elementary(inner.type) or inner.type
            return LValue("bit", self.ty(e), key=str(e.bit), inner=inner)
        if isinstance(e, ast.Deref):
            # What a reference refers to: a Ref (elementary) or the object itself;
            # `_deref` faults on NULL.  A REF_TO a subrange stores within its limits
            # (the dereference reads as the base type).
            t = self.program.subranges.get(id(e)) or self.ty(e)
            target = f"_deref({self.expr(e.base)})"
            return LValue("local", t, name=target) if is_aggregate(t) else LValue("ref", t, name=target)
        self.fail("this expression cannot be assigned or referenced", e)

    def aggregate(self, e) -> str:
        """Python source that evaluates to the object/list of an aggregate."""
        if type(e) is ast.Name:
            return self._name_read(e)
        if isinstance(e, (ast.Member, ast.Index)):
            place = self.lvalue(e)
            return place.read()
        return self.expr(e)

    def member_type(self, base_t, name: str, node) -> Type:
        base_t = resolve_alias(base_t) if base_t is not None else None
        key = name.upper()
        if isinstance(base_t, StructType) and key in base_t.fields:
            return base_t.fields[key][1]
        if isinstance(base_t, FBType) and key in base_t.variables:
            return base_t.variables[key].type
        t = self.program.expr_types.get(id(node))
        if t is not None:
            return t
        self.fail(f"unknown member '{name}'", node)

    def index_lvalue(self, e) -> LValue:
        element, obj, key = self._index_place(e)
        return LValue("item", element, obj=obj, key=key)

    def _index_place(self, e) -> tuple:
        """(element type, list, index) of the element `e` reads: `list[index]` in Python."""
        known = self._arrays.get(id(e))
        if known is not None and known[0] is e:     # (a named array's type and code, as found before)
            _, arr_t, base = known
        else:
            arr_t = self.ty(e.base)
            if not isinstance(arr_t, ArrayType):
                self.fail("indexing needs an array", e)
            if len(e.indices) != len(arr_t.dims):
                self.fail(f"{len(arr_t.dims)} indices expected, found {len(e.indices)}", e)
            base = self.aggregate(e.base)
            if arr_t.is_open:        # ARRAY[*]: an _ArrayView, its bounds known at run time
                indices = ", ".join(self.expr(i) for i in e.indices)
                key = f"{base}.offset(({indices},), {_describe(e.base)!r}, {self.where(e)})"
                return arr_t.element, f"{base}.seq", key
            if type(e.base) is ast.Name:
                self._arrays[id(e)] = (e, arr_t, base)
        consts = [self.constant_of(index) for index in e.indices]     # (pure: any order)
        offset = 0
        for const, (lo, hi) in zip(consts, arr_t.dims):     # all constant (an unrolled copy's reads)
            if not (isinstance(const, int) and not isinstance(const, bool) and lo <= const <= hi):
                break
            offset = offset * (hi - lo + 1) + const - lo
        else:
            self._invariant_terms = []      # (as below: an enclosing index's hoisting sees it reset)
            return arr_t.element, base, str(offset)
        name = _describe(e.base)
        checks: list[str] = []
        terms: list[str] = []
        values: list[str] = []
        offset = 0
        stride = 1
        strides = []
        for lo, hi in reversed(arr_t.dims):
            strides.append(stride)
            stride *= hi - lo + 1
        strides.reverse()
        self._invariant_terms = []
        for index, (lo, hi), k, const in zip(e.indices, arr_t.dims, strides, consts):
            offset -= lo * k
            if isinstance(const, int) and not isinstance(const, bool) and lo <= const <= hi:
                offset += const * k
                values.append(pyliteral(const))
                continue
            known = self.static_range(index)
            code = self.settled_expr(index)
            if k != 1 and self.is_loop_invariant(index):
                self._invariant_terms.append(f"{code} * {k}")
            if known is not None and lo <= known[0] and known[1] <= hi:
                terms.append(code if k == 1 else self.scaled_loop_term(index, code, k))
                values.append(code)
                continue
            if self._index_probe and isinstance(index, ast.Name) and index.name.upper() in self._index_probe:
                self._index_probe[index.name.upper()].append((lo, hi))
            if not _is_simple(code):
                tmp = self.temp()
                checks.append(f"{lo} <= ({tmp} := {code}) <= {hi}")
                code = tmp
            else:
                checks.append(f"{lo} <= {code} <= {hi}")
            terms.append(code if k == 1 else self.scaled_loop_term(index, code, k))
            values.append(code)
        terms, offset = self.hoist_invariant(e, terms, offset)
        key = " + ".join(terms) if terms else ""
        if offset:
            key = f"{key} - {-offset}" if key and offset < 0 else (f"{key} + {offset}" if key else str(offset))
        if not key:
            key = "0"
        if self.opt.offsets and offset and len(terms) == 1 and len(e.indices) == 1 and terms[0] == values[0] \
                and self._innermost_variable(e.indices[0]):
            key = self._per_iteration(key)       # `A[i]` of ARRAY[1..n]: `i - 1` once per iteration
        if checks:
            if len(arr_t.dims) == 1:
                fault = f"_index_fault({values[0]}, {arr_t.dims[0][0]}, {arr_t.dims[0][1]}, {name!r}, {self.where(e)})"
            else:
                fault = (f"_index_fault_n(({', '.join(values)},), {pyliteral(tuple(arr_t.dims))}, "
                         f"{name!r}, {self.where(e)})")
            # `&`, not `and`: every index's temp is set before the fault names the first bad one
            test = checks[0] if len(checks) == 1 else " & ".join(f"({check})" for check in checks)
            key = f"({key}) if {test} else {fault}"
        return arr_t.element, base, key

    def is_loop_invariant(self, index) -> bool:
        """A Python local the innermost FOR body never assigns."""
        if not self.loops or not self.loops[-1].hoistable or not isinstance(index, ast.Name):
            return False
        key = index.name.upper()
        loop = self.loops[-1]
        if key == loop.variable or key in loop.assigned:
            return False
        place = self.scope.places.get(key)
        return place is not None and place.how == "local"

    def scaled_loop_term(self, index, code: str, k: int) -> str:
        """`i * k` for the innermost FOR variable `i`: computed once per iteration.

        Returns a placeholder the FOR compiler replaces by a temp set at the
        top of the body (when used twice or more) or by the product itself.
        """
        text = f"{code} * {k}"
        return self._per_iteration(text) if self._innermost_variable(index) else text

    def _innermost_variable(self, index) -> bool:
        """`index` is the variable of the innermost FOR, a range-based one (`hoistable`)."""
        return bool(self.loops) and self.loops[-1].hoistable and isinstance(index, ast.Name) \
            and index.name.upper() == self.loops[-1].variable

    def _per_iteration(self, text: str) -> str:
        """A placeholder for `text`, a value of the innermost FOR's variable, that the FOR
        compiler replaces by a temp set at the top of the body (used twice or more) or by
        `text` itself."""
        entry = self.loops[-1].scaled.get(text)
        if entry is None:
            entry = self.loops[-1].scaled[text] = [f"\x00{self.lasting_temp()}\x00", 0]
        entry[1] += 1
        return entry[0]

    def hoist_invariant(self, e, terms: list[str], offset: int):
        """Compute the loop-invariant part of a flat index once, before the loop.

        `m[k, j]` inside `FOR j` becomes `m[_h + j]` with `_h = k * 6 - 7`
        computed before the loop (k is not assigned in its body).
        """
        invariant = [t for t in self._invariant_terms if t in terms]
        if not invariant or len(invariant) == len(terms) and not offset and len(invariant) == 1:
            return terms, offset
        code = " + ".join(invariant)
        if offset:
            code = f"{code} - {-offset}" if offset < 0 else f"{code} + {offset}"
        loop = self.loops[-1]
        name = loop.hoisted.get(code)
        if name is None:
            name = self.lasting_temp()
            loop.hoisted[code] = name
        rest = [t for t in terms if t not in invariant]
        return [name] + rest, 0

    # ------------------------------------------------------------ stores

    def convert(self, value: str, src, dst, node=None) -> str:
        """`value` (of type `src`) as stored in a variable of type `dst`."""
        dst_r = resolve_alias(dst) if dst is not None else None
        src_r = resolve_alias(src) if src is not None else None
        e = elementary(dst_r)
        plain_read = node is not None and isinstance(node, (ast.Name, ast.Member, ast.Index))
        if e is not None and node is not None:
            const = self.constant_of(node)
            outside = isinstance(e, SubrangeType) and isinstance(const, int) and not e.lo <= const <= e.hi
            if isinstance(const, (bool, int, float)) and not outside:
                try:                  # a constant is stored as the literal it becomes
                    return self.literal(store_value(e, const), e)
                except (TypeError, ValueError, OverflowError):
                    pass
        if e is not None:
            if e.kind == "bool":
                return value
            if e.kind == "real":
                s = elementary(src_r)
                if s is not None and s.kind != "real" and node is not None:
                    value = self.settled(node, value)
                if e.bits == 64:
                    return f"float({value})" if s is not None and s.kind != "real" else value
                if s is not None and s.kind == "real" and s.bits == 32 and plain_read:
                    return value
                if node is not None and self.constant_of(node) is not None:
                    return value      # literals are rounded when written
                return f"_f32({value})"
            bounds = int_bounds(e)
            if node is not None:
                known = self.static_range(node)
                if known is None and self.opt.wraps:
                    known = wraps.selection_range(self, node)       # MIN(SyncCalls + 1, 2)
                if known is not None and bounds[0] <= known[0] and known[1] <= bounds[1]:
                    return value
                if plain_read:
                    sb = int_bounds(src_r)
                    if sb is not None and bounds[0] <= sb[0] and sb[1] <= bounds[1]:
                        return value
            if isinstance(e, SubrangeType):
                return f"_subrange({value}, {e.lo}, {e.hi})"
            if node is not None and not plain_read:
                source = int_bounds(src_r)
                if source is not None and not (bounds[0] <= source[0] and source[1] <= bounds[1]) \
                        and bounds[1] - bounds[0] <= source[1] - source[0]:
                    return _wrapped(value, e)      # the target is no wider: its wrap settles it
                value = self.settled(node, value)
            if self.opt.wraps and (checked := wraps.tested(value, e, self.temp)) is not None:
                return checked
            return _wrapped(value, e)
        if isinstance(dst_r, StringType):
            if node is not None and isinstance(self.constant_of(node), str) \
                    and string_size(self.constant_of(node), self.program.dialect) <= dst_r.length:
                return value
            if plain_read and isinstance(src_r, StringType) and src_r.length <= dst_r.length:
                return value
            return f"_truncate({value}, {dst_r.length})"
        return value


def _wrapped(value: str, e) -> str:
    """Python source of the integer `value` wrapped to the width and signedness of `e`."""
    bits = 64 if e.kind in ("time", "date", "tod", "dt") else e.bits
    signed = e.signed or e.kind in ("time", "date", "tod", "dt")
    mask = (1 << bits) - 1
    if signed:
        half = 1 << (bits - 1)
        return f"((({value}) + {half} & {mask}) - {half})"
    return f"(({value}) & {mask})"


def _is_simple(code: str) -> bool:
    """A Python name or literal: cheap to evaluate twice, no side effects."""
    return code.isidentifier() or code.lstrip("-").isdigit()


def _describe(e) -> str:
    """A short ST rendering of an array expression for fault messages."""
    if isinstance(e, ast.Name):
        return e.name
    if isinstance(e, ast.Member):
        return f"{_describe(e.base)}.{e.name}"
    if isinstance(e, ast.Index):
        return f"{_describe(e.base)}[...]"
    return "array"

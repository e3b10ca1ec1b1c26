"""Calls: user functions, standard functions, conversions and FB instances.

Conventions of the generated code:

* A user FUNCTION `F` becomes `_fn_F(_ctx, <inputs and in-outs in declaration
  order>)`.  It returns its result, or the tuple (result, outputs...) when it
  has VAR_OUTPUT variables (OMRON NJ allows them).  Inputs a call leaves out
  take their declared initial value.
* A standard function is the library's Python callable bound as `_sf_NAME`
  (`stdlib.functions.FUNCTIONS`), arguments in IEC order; SHL/SHR/ROL/ROR/NOT
  get the bit width of IN as a trailing argument.  `A_TO_B` is `_cv_A_TO_B`.
* An FB call stores the given inputs into the instance (`inst.v_IN = ...`),
  connects VAR_IN_OUTs (the aggregate itself, or a `Ref`), calls
  `inst.execute(_ctx)` and then copies the `=>` outputs.  With `inline`, a
  native FB whose class has a `CALL_NEEDED` test is called only when that
  test is true (an idle MC_Stop would change nothing), only while its `REST`
  test does not say it was found at rest before, and one whose class has
  a `HOT_PATH` runs that path's statements in place of the call when its test
  holds (MC_Power, and MC_SyncMoveAbsolute while synchronized).
"""

from __future__ import annotations

import re

from .. import ast
from ..objects import is_aggregate
from ..types import BOOL, ArrayType, ElementaryType, FBType, StructType, resolve_alias
from .exprs import elementary, is_real
from .initial import CompileError
from .optimise import dormant, shortcut
from .pysrc import finite_test, pyliteral, safe_name, pyident

# Standard functions that map to a Python builtin or to their argument.
_INLINE = {"ABS": "abs"}

# Optimisations.inline: MIN and MAX of two or more inputs as Python's min/max of
# the arguments (the library's MIN(*values) is min(values): the same comparisons
# in the same order, without the call of the wrapper).
_SELECTION = {"MIN": "min", "MAX": "max"}

# Optimisations.inline: MIN and MAX of two integers or two reals without the call of min or
# max.  min(a, b) keeps a unless `b < a` (max: `b > a`), and for Python's int and float
# `a > b` is `b < a` (NaN included: both false), so MIN(a, b) is `(b if a > b else a)`:
# a, then b, evaluated once each, one comparison, which CPython 3.11 specialises.
_PAIR_TEST = {"MIN": ">", "MAX": "<"}

# Optimisations.inline: the math function itself where the library's wrapper
# (stdlib/functions.py) would only call it, with the wrapper kept for the rest:
# SIN/COS/TAN raise ValueError only for an infinite argument (the wrapper gives
# NaN), SQRT returns NaN below zero.  `{x}` is the argument, evaluated once, `{t}`
# the temporary it is kept in.  `t - t == 0.0` is finiteness (an infinity or NaN
# gives NaN), a float subtraction and one comparison: cheaper than the chained
# `-inf < t < inf`.
_GUARDED = {
    "SIN": ("_m_sin", finite_test("{x}", "{t}")),
    "COS": ("_m_cos", finite_test("{x}", "{t}")),
    "TAN": ("_m_tan", finite_test("{x}", "{t}")),
    "SQRT": ("_m_sqrt", "{x} >= 0.0"),
}


def _read_back(lines: list[str], instance: str, stored: dict[str, str]) -> list[str]:
    """`lines` (the tests and hot path after an FB call's input stores) reading each input
    stored from a Python name (`stored`: attribute -> name) as that name: the same object,
    as nothing in them stores that input again, one attribute load fewer."""
    text = "\n".join(lines)
    for attr, name in stored.items():
        member = rf"(?<![\w.]){re.escape(instance)}\.{attr}\b"
        if not re.search(member + r"\s*=(?!=)", text):
            text = re.sub(member, name, text)
    return text.split("\n")


def _native_class(ec, target, call):
    """The Python class of the FB a call statement calls, or None (an ST FB)."""
    return target.pou.native if target.pou is not None else getattr(ec.ty(call.callee), "native", None)


def _rest_test(ec, target, call):
    """The RestTest the call's site makes (`inline`: a native FB with CALL_NEEDED and REST,
    no HOT_PATH), or None."""
    native = _native_class(ec, target, call)
    if not ec.opt.inline or getattr(native, "CALL_NEEDED", None) is None or getattr(native, "HOT_PATH", None):
        return None
    return getattr(native, "REST", None)


def _stores_a_float(ec, symbol, arg) -> bool:
    """Whether the call stores a Python float into input `symbol`: a REAL or LREAL input given
    an elementary value, which `convert` makes one (a literal as a float literal, an integer
    through `float()` or `_f32()`, a REAL or LREAL value as the float it is)."""
    target = elementary(symbol.type)
    return symbol.kind == "VAR_INPUT" and target is not None and target.kind == "real" \
        and elementary(ec.ty(arg.value)) is not None


def _selected_pair(test: str, first: str, second: str, temp) -> str:
    """`(second if first <test> second else first)`, each code evaluated once, in order: a
    temporary (from `temp()`) holds one that is not a Python name or literal."""
    def held(code: str) -> tuple[str, str]:
        if code.isidentifier() or code.lstrip("-").isdigit():
            return code, code
        name = temp()
        return f"({name} := {code})", name

    (first_code, first_value), (second_code, second_value) = held(first), held(second)
    return f"({second_value} if {first_code} {test} {second_code} else {first_value})"


def _sum_of_squares(ec, node) -> bool:
    """`node` is a REAL/LREAL sum of squares of variables (`X * X + Y * Y`, the IK's leg
    lengths): each square +0.0 or more, +inf or NaN (a variable read twice is one value),
    and so their sum; never below zero, where alone SQRT's wrapper does more than
    `math.sqrt` (NaN gives NaN either way, +inf +inf)."""
    if not (isinstance(node, ast.Binary) and is_real(ec.ty(node))):
        return False
    if node.op == "*":
        return isinstance(node.left, ast.Name) and isinstance(node.right, ast.Name) \
            and node.left.name.upper() == node.right.name.upper()
    return node.op == "+" and _sum_of_squares(ec, node.left) and _sum_of_squares(ec, node.right)


class Calls:
    def __init__(self, unit):
        self.unit = unit

    # ------------------------------------------------------------ params

    def target(self, ec, call):
        target = ec.program.call_targets.get(id(call))
        if target is None:
            raise CompileError("call was not resolved by the checker", call.pos)
        return target

    def user_params(self, pou) -> list:
        """Positional parameters of a user POU: inputs and in-outs, in order."""
        return [s for s in pou.variables.values() if s.kind in ("VAR_INPUT", "VAR_IN_OUT")]

    def fb_variables(self, ec, call, target) -> dict:
        if target.pou is not None:
            return target.pou.variables
        t = ec.ty(call.callee)
        if isinstance(t, FBType):
            return t.variables
        raise CompileError("cannot find the FB type of this call", call.pos)

    def bind(self, call, params: list, variables: dict):
        """Match the arguments of `call` to parameters.

        Returns (inputs: {KEY: Arg}, outputs: [(symbol, Arg)]).
        """
        inputs: dict = {}
        outputs: list = []
        position = 0
        for arg in call.args:
            if arg.direction == "out" and arg.value is None:
                continue          # `Q =>`: the output is left unconnected
            if arg.direction == "out":
                symbol = variables.get(arg.name.upper())
                if symbol is None:
                    raise CompileError(f"no output '{arg.name}'", arg.pos)
                outputs.append((symbol, arg))
            elif arg.name is not None:
                inputs[arg.name.upper()] = arg
            else:
                if position >= len(params):
                    raise CompileError("too many arguments", arg.pos)
                inputs[params[position].name.upper()] = arg
                position += 1
        return inputs, outputs

    # ------------------------------------------------------------- values

    def argument(self, ec, symbol, arg) -> str:
        """Python source passing `arg` to parameter `symbol`."""
        if symbol.kind == "VAR_IN_OUT":
            open_array = isinstance(symbol.type, ArrayType) and symbol.type.is_open
            if open_array and not ec.ty(arg.value).is_open:      # ARRAY[*]: bounds travel along
                return f"_ArrayView({ec.aggregate(arg.value)}, {pyliteral(ec.ty(arg.value).dims)})"
            if is_aggregate(symbol.type):
                return ec.aggregate(arg.value)
            return ec.lvalue(arg.value).ref()
        code = ec.expr(arg.value)
        return ec.convert(code, ec.ty(arg.value), symbol.type, arg.value)

    def default_argument(self, ec, symbol) -> str:
        initial = self.unit.initial.of_symbol(symbol)
        if initial.is_const:
            return ec.literal(initial.const, symbol.type)
        return self.unit.register_maker(initial.maker) + "()"

    def store_output(self, ec, source: str, symbol, arg) -> str:
        """A statement copying output `source` of `symbol` into the `=>` target."""
        target = ec.lvalue(arg.value)
        if is_aggregate(symbol.type):
            return copy_statement(target.read(), source, symbol.type)
        value = f"(not {source})" if arg.negated else source
        return target.store(ec.convert(value, symbol.type, target.type))

    # -------------------------------------------------------- statements

    def call_statement(self, ec, call) -> list[str]:
        """Python statements for a call used as a statement."""
        enable = ec.program.enables.get(id(call))
        if enable is not None:
            en, eno, inner = enable
            flag = ec.temp()
            lines = [f"{flag} = {ec.expr(en) if en is not None else 'True'}", f"if {flag}:"]
            lines += ["    " + line for line in self.call_statement(ec, inner)]
            if eno is not None:
                lines.append(self._store_eno(ec, eno, flag, statement=True))
            return lines
        if id(call) in ec.program.lowered:
            return [self.call_expr(ec, call)]
        target = self.target(ec, call)
        if target.kind == "fb":
            return self.fb_call(ec, call, target)
        if target.kind == "super_body":          # SUPER^(): the base's body on this instance
            owner = self.unit.register_constant(self.unit.classes[target.name.upper()])
            return [f"{owner}.execute(self, _ctx)"]
        if target.kind in ("function", "method") and target.pou is not None and target.pou.outputs:
            return self.user_call_with_outputs(ec, call, target)
        return [self.call_expr(ec, call)]

    def fb_call(self, ec, call, target) -> list[str]:
        variables = self.fb_variables(ec, call, target)
        params = [s for s in variables.values() if s.kind in ("VAR_INPUT", "VAR_IN_OUT")]
        inputs, outputs = self.bind(call, params, variables)
        instance = ec.aggregate(call.callee)
        lines, stored, floats, codes = [], {}, set(), {}
        callee = instance
        if not instance.isidentifier():
            tmp = ec.temp()
            lines.append(f"{tmp} = {instance}")
            instance = tmp
        for key, arg in inputs.items():
            symbol = variables.get(key)
            if symbol is None:
                raise CompileError(f"no input '{arg.name}'", arg.pos)
            attr = f"{instance}.{pyident(symbol.name)}"
            if symbol.kind != "VAR_IN_OUT" and is_aggregate(symbol.type):
                lines.append(copy_statement(attr, ec.aggregate(arg.value), symbol.type))
            else:
                value = self.argument(ec, symbol, arg)
                codes[key] = shortcut.stored(ec, arg.value, value) if symbol.kind == "VAR_INPUT" else value
                lines.append(f"{attr} = {codes[key]}")
                if value.isidentifier() and value != instance:
                    stored[pyident(symbol.name)] = value
                if _stores_a_float(ec, symbol, arg):
                    floats.add(pyident(symbol.name))
        body = _read_back(self._execute(ec, target, call, instance, frozenset(floats)), instance, stored)
        for symbol, arg in outputs:
            body.append(self.store_output(ec, f"{instance}.{pyident(symbol.name)}", symbol, arg))
        rest = _rest_test(ec, target, call)
        if rest is not None and ec.opt.dormant and not outputs:
            execute = dormant.guard(ec, call, inputs, variables, codes)
            if execute is not None:     # the whole site skipped while the FB is at rest
                forget = _read_back(dormant.forget_lines(instance, rest), instance, stored)
                return dormant.site(ec, call, execute, callee, rest, lines, body + forget)
        return lines + body

    def _execute(self, ec, target, call, instance: str, floats: frozenset[str]) -> list[str]:
        """The call of the body (see the module docstring for `CALL_NEEDED`); `floats`: the
        inputs the call site has just stored as Python floats (`_stores_a_float`)."""
        native = _native_class(ec, target, call)
        needed = getattr(native, "CALL_NEEDED", None) if ec.opt.inline else None
        hot = getattr(native, "HOT_PATH", None) if ec.opt.inline else None
        rest = _rest_test(ec, target, call)
        call = f"{instance}.execute(_ctx)"
        if rest is not None:
            return [f"if {rest.awake.format(fb=instance)}:", f"    if {needed.format(fb=instance)}:",
                    f"        {call}", "    else:", f"        {rest.note.format(fb=instance)}"]
        if hot is None:
            return [call] if needed is None else [f"if {needed.format(fb=instance)}:", f"    {call}"]
        test, statements = hot.inline(instance, ec.temp, floats)
        otherwise = "else:" if needed is None else f"elif {needed.format(fb=instance)}:"
        return [f"if {test}:", *("    " + line for line in statements), otherwise, f"    {call}"]

    def user_call_with_outputs(self, ec, call, target) -> list[str]:
        tmp = ec.temp()
        code, outputs = self.user_call(ec, call, target)
        lines = [f"{tmp} = {code}"]
        out_syms = target.pou.outputs
        for symbol, arg in outputs:
            i = 1 + [s.name.upper() for s in out_syms].index(symbol.name.upper())
            lines.append(self.store_output(ec, f"{tmp}[{i}]", symbol, arg))
        return lines

    # ------------------------------------------------------- expressions

    def _store_eno(self, ec, eno, flag: str, statement: bool) -> str:
        place = ec.lvalue(eno.value)
        value = ec.convert(f"(not {flag})" if eno.negated else flag, BOOL, place.type)
        return place.store(value) if statement else place.store_expr(value)

    def enabled_call_expr(self, ec, call, enable) -> str:
        """`F(EN := c, ..., ENO => ok)`: with c FALSE, F is not called, its value
        is its type's initial value and ok is FALSE (IEC 61131-3 6.6.1.2)."""
        en, eno, inner = enable
        if en is None:
            code = self.call_expr(ec, inner)
            return code if eno is None else f"({code}, {self._store_eno(ec, eno, 'True', False)})[0]"
        initial = self.unit.initial.of(ec.ty(inner), self._result_init(ec, inner), inner.pos)
        default = ec.literal(initial.const, ec.ty(inner)) if initial.is_const \
            else self.unit.register_maker(initial.maker) + "()"
        flag, result = ec.temp(), ec.temp()
        chosen = f"({self.call_expr(ec, inner)} if ({flag} := {ec.expr(en)}) else {default})"
        if eno is None:
            return chosen
        return f"({result} := {chosen}, {self._store_eno(ec, eno, flag, False)}, {result})[-1]"

    def _result_init(self, ec, call):
        """The initial value of a user FUNCTION's or METHOD's result: its derived type's, which
        the checker's RETURN symbol carries (the resolved result type has lost it), or None."""
        pou = getattr(ec.program.call_targets.get(id(call)), "pou", None)
        result = pou.result if pou is not None else None
        return result.init if result is not None else None

    def call_expr(self, ec, call) -> str:
        enable = ec.program.enables.get(id(call))
        if enable is not None:
            return self.enabled_call_expr(ec, call, enable)
        lowered = ec.program.lowered.get(id(call))
        if lowered is not None:      # ADD(a, b) and the like: the operator's expression
            return ec.expr(lowered)
        target = self.target(ec, call)
        if target.kind == "conversion":
            return self.conversion(ec, call, target)
        if target.kind in ("function", "method") and target.pou is not None and target.pou.node is not None:
            code, outputs = self.user_call(ec, call, target)
            if not target.pou.outputs:
                return code
            if not outputs:
                return f"{code}[0]"
            tmp = ec.temp()
            out_syms = [s.name.upper() for s in target.pou.outputs]
            stores = []
            for symbol, arg in outputs:
                i = 1 + out_syms.index(symbol.name.upper())
                place = ec.lvalue(arg.value)
                value = f"{tmp}[{i}]"
                if is_aggregate(symbol.type):    # copied into the target, as by store_output
                    stores.append(copy_expr(place.read(), value, symbol.type))
                    continue
                if arg.negated:
                    value = f"(not {value})"
                stores.append(place.store_expr(ec.convert(value, symbol.type, place.type)))
            return f"({tmp} := {code}, {', '.join(stores)}, {tmp}[0])[-1]"
        if target.kind == "function":     # a REAL result rounded where the NJ computes in REAL
            code = self.standard(ec, call, target)
            return f"_f32({code})" if ec.rounds_real(ec.ty(call)) else code
        if target.kind == "bound":               # LOWER_BOUND / UPPER_BOUND
            array, dim = call.args[0].value, ec.constant_of(call.args[1].value)
            t = ec.ty(array)
            side = 0 if target.name == "LOWER_BOUND" else 1
            if not t.is_open:
                return pyliteral(t.dims[dim - 1][side])
            return f"{ec.aggregate(array)}.dims[{dim - 1}][{side}]"
        if target.kind == "ref":                 # REF(x) / ADR(x)
            value = call.args[0].value
            return ec.aggregate(value) if is_aggregate(ec.ty(value)) else ec.lvalue(value).ref()
        raise CompileError("an FB instance call is a statement, not a value", call.pos)

    def user_call(self, ec, call, target):
        pou = target.pou
        params = self.user_params(pou)
        inputs, outputs = self.bind(call, params, pou.variables)
        args = ["_ctx"]
        for symbol in params:
            arg = inputs.get(symbol.name.upper())
            if arg is None:
                if symbol.kind == "VAR_IN_OUT":
                    raise CompileError(f"VAR_IN_OUT '{symbol.name}' needs a variable", call.pos)
                args.append(self.default_argument(ec, symbol))
            else:
                args.append(self.argument(ec, symbol, arg))
        if target.kind == "method":
            return self.method_callee(ec, call, target, args), outputs
        name = safe_name("_fn_" + pou.name.upper())
        return f"{name}({', '.join(args)})", outputs

    def method_callee(self, ec, call, target, args: list) -> str:
        """`obj.mNAME(_ctx, ...)`: Python's attribute lookup on the instance's
        class is the dynamic dispatch (a derived FB's class overrides)."""
        from . import method_attr

        method = target.pou
        attr = method_attr(method.name)
        how = target.name
        if how == "super":       # the base's own method, whatever the instance's class
            owner = self.unit.register_constant(self.unit.classes[method.owner.name.upper()])
            return f"{owner}.{attr}(self, {', '.join(args)})"
        if how == "self":
            return f"self.{attr}({', '.join(args)})"
        if how == "interface":   # the variable may refer to no instance
            return f"_method({ec.expr(call.callee.base)}, {attr!r})({', '.join(args)})"
        return f"{ec.aggregate(call.callee.base)}.{attr}({', '.join(args)})"

    def conversion(self, ec, call, target) -> str:
        if len(call.args) != 1 or call.args[0].direction == "out":
            raise CompileError(f"{target.name} takes one input", call.pos)
        fn = self.unit.bind_conversion(target.name, call.pos)
        return f"{fn}({ec.settled_expr(call.args[0].value)})"

    def standard(self, ec, call, target) -> str:
        from ..checker.builtins import STANDARD_FUNCTIONS, extra_param

        name = target.name.upper()
        spec = STANDARD_FUNCTIONS.get(name)
        if spec is None:
            raise CompileError(f"unknown standard function {name}", call.pos)
        ordered: list = []
        named = {}
        for i, arg in enumerate(call.args):
            if arg.direction == "out":
                raise CompileError(f"{name} has no outputs", arg.pos)
            if arg.name is None:
                ordered.append(arg)
            else:
                named[arg.name.upper()] = arg
        if named:
            count = max(len(spec.params), len(ordered) + len(named))
            params = [extra_param(spec, i) for i in range(count)]
            for i, p in enumerate(params):
                if i >= len(ordered) and p.name.upper() in named:
                    ordered.append(named.pop(p.name.upper()))
            if named:
                raise CompileError(f"{name} has no input '{next(iter(named))}'", call.pos)
        codes = []
        generic = resolve_alias(target.generic_type) if target.generic_type is not None else None
        for i, arg in enumerate(ordered):
            code = ec.settled_expr(arg.value)
            p = extra_param(spec, i)
            if p.generic and is_real(generic) and not is_real(ec.ty(arg.value)):
                code = f"float({code})"
            codes.append(code)
        if name in _INLINE:
            return f"{_INLINE[name]}({', '.join(codes)})"
        if name == "MOVE" and len(codes) == 1:
            return codes[0]
        if name in ("SHL", "SHR", "ROL", "ROR", "NOT"):
            t = elementary(ec.ty(ordered[0].value)) or generic
            codes.append(pyliteral(t.bits if isinstance(t, ElementaryType) else 64))
        if name in _SELECTION and len(codes) >= 2 and ec.opt.inline:
            if len(codes) == 2 and isinstance(generic, ElementaryType) and generic.kind in ("int", "real"):
                return _selected_pair(_PAIR_TEST[name], *codes, ec.temp)
            return f"{_SELECTION[name]}({', '.join(codes)})"
        fn = self.unit.bind_function(name, call.pos)
        if name in _GUARDED and len(codes) == 1 and ec.opt.inline:
            fast, test = _GUARDED[name]
            if name == "SQRT" and _sum_of_squares(ec, ordered[0].value):
                text = f"{fast}({codes[0]})"        # never below zero: the wrapper would only call it
            elif name != "SQRT" and ec.reuse is not None \
                    and (finite := ec.reuse.finite(ordered[0].value, codes[0])) is not None:
                text = f"({fast}({codes[0]}) if {finite} else {fn}({codes[0]}))"     # a local, tested once
            else:
                tmp = ec.temp()
                text = f"({fast}({tmp}) if {test.format(x=f'({tmp} := {codes[0]})', t=tmp)} else {fn}({tmp}))"
            return ec.reuse.math(name, ordered[0].value, codes[0], text) if ec.reuse is not None else text
        return f"{fn}({', '.join(codes)})"


def copy_statement(target: str, source: str, t) -> str:
    """`target := source` for an aggregate: copy in place.

    An array of elementary elements is a slice store, `target[_WHOLE] = source`: `_WHOLE` is
    the namespace's `slice(None)`, the very slice `target[:]` builds (CPython 3.11 makes and
    frees a new one each time, `BUILD_SLICE`); the store is the same `__setitem__` call."""
    t = resolve_alias(t)
    if isinstance(t, ArrayType):
        if is_aggregate(t.element):
            return f"_assign_list({target}, {source})"
        return f"{target}[_WHOLE] = {source}"
    if isinstance(t, (StructType, FBType)):
        return f"{target}._assign({source})"
    raise AssertionError(f"not an aggregate: {t}")


def copy_expr(target: str, source: str, t) -> str:
    """`copy_statement` as an expression, for a store inside a larger expression."""
    if isinstance(resolve_alias(t), ArrayType):
        return f"_assign_list({target}, {source})"
    return copy_statement(target, source, t)     # a call already

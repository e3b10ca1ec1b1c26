"""Calls: user functions, function block instances, standard functions and
`A_TO_B` conversions.  Arguments are bound to parameters (pins) and checked:
unknown pin, pin given twice, wrong direction, too many or too few, and
VAR_IN_OUT arguments that must be variables of exactly the parameter's type.
"""

from __future__ import annotations

from .. import ast
from .. import types as T
from ..ast import key
from ..symbols import CallTarget, PouInfo
from . import builtins as B
from .loop_writes import note_argument, note_call, note_in_out, note_method_call
from .oo import find_method, interface_methods, may_call
from .operator_calls import OPERATOR_FUNCTIONS, lower, ordered_inputs
from . import typesys as ts
from .expressions import start_pos
from .stores import check_store, in_out_problem, is_variable_path, no_address, root_name

_PIN_KINDS = ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT")
# _namespaced's answer for `NS.F` when NAMESPACE NS declares no F (already reported).
_NOT_IN_NAMESPACE = object()
# _method_target's answer for `SUPER.M` when there is no M to call (already reported).
_NO_SUPER_METHOD = object()



class CallChecker:
    def __init__(self, ex):
        self.ex = ex
        self.ctx = ex.ctx
        self.program = ex.program

    # ------------------------------------------------------------ dispatch
    def check_call(self, call: ast.Call, expected=None, statement: bool = False):
        enable = self._enable_args(call)
        if enable is None:
            return self._dispatch(call, expected, statement)
        en, eno, inner = enable
        if en is not None and en.value is not None:
            self.ex.check_value(en.value, T.BOOL, "EN")
        if eno is not None and eno.value is not None:
            t = check_store(self.ex, eno.value, "ENO")
            if t is not ts.ERROR:
                self.ex.require_assignable(T.BOOL, t, eno.value.pos, "ENO")
        t = self._dispatch(inner, expected, statement)
        self.program.enables[id(call)] = (en.value if en is not None else None, eno, inner)
        return self.ex.record(call, t) if id(inner) in self.program.expr_types else t

    def _enable_args(self, call: ast.Call):
        """(EN arg, ENO arg, the call without them) when the call gives EN or ENO.

        IEC 61131-3 6.6.1.2: every function and FB has the BOOL input EN and
        output ENO; with EN FALSE the body is not executed and ENO is FALSE.
        A callee that declares its own EN / ENO keeps them as ordinary pins.
        """
        en = next((a for a in call.args if a.name and key(a.name) == "EN" and a.direction == "in"), None)
        eno = next((a for a in call.args if a.name and key(a.name) == "ENO" and a.direction == "out"), None)
        if en is None and eno is None:
            return None
        callee = call.callee
        pou = None
        if isinstance(callee, ast.Member) and self._namespace_of(callee) is not None:
            pou = self.program.pous.get(key(callee.name))
        elif isinstance(callee, ast.Name) and self._not_a_variable(callee):
            pou = self.program.pous.get(key(callee.name))
        else:
            t = self.ex.infer(callee)
            if isinstance(t, T.FBType):
                pou = self.program.pous.get(key(t.name))
        if pou is not None and ("EN" in pou.variables or "ENO" in pou.variables):
            return None
        rest = tuple(a for a in call.args if a is not en and a is not eno)
        return en, eno, ast.Call(callee, rest, pos=call.pos)

    def _dispatch(self, call: ast.Call, expected=None, statement: bool = False):
        callee = call.callee
        short = self._namespaced(callee)
        if short is _NOT_IN_NAMESPACE:      # one root cause, one diagnostic
            return self._give_up(call)
        if short is not None:       # NS.F(x): the POU F of namespace NS
            inner = ast.Call(short, call.args, call.trailing_comma, pos=call.pos)
            self.program.lowered[id(call)] = inner
            written = f"{self._namespace_of(callee)}.{short.name}"
            t = self._pou_call(inner, self.program.pous[key(short.name)], statement, written)
            return self.ex.record(call, t) if id(inner) in self.program.expr_types else t
        if isinstance(callee, ast.Deref) and isinstance(callee.base, ast.Name) \
                and key(callee.base.name) == "SUPER" and self.ex.scope.lookup("SUPER") is None:
            return self._super_body(call, statement)
        method = self._method_target(callee)
        if method is _NO_SUPER_METHOD:      # one root cause, one diagnostic
            return self._give_up(call)
        if method is not None:
            return self._method_call(call, method[0], method[1], statement)
        if isinstance(callee, ast.Name) and self._not_a_variable(callee):
            k = key(callee.name)
            pou = self.program.pous.get(k)
            if pou is not None:
                return self._pou_call(call, pou, statement, callee.name)
            if k in ("__NEW", "__DELETE"):
                self.ctx.error("E-CALL-013", f"{callee.name}: dynamic memory (CODESYS __NEW / "
                               f"__DELETE) is not supported; declare the instance or array as a "
                               f"variable instead", callee.pos)
                return self.ex.record(call, ts.ERROR)     # (its argument is a type: not typed)
            if k in ("LOWER_BOUND", "UPPER_BOUND"):
                return self._bound(call, k)
            if k in ("REF", "ADR"):
                if k == "ADR" and not self.ctx.accepts("ADR", callee.pos):
                    return self.ex.record(call, ts.ERROR)
                return self._reference(call, k)
            if k in OPERATOR_FUNCTIONS:
                return self._operator_call(call, k, OPERATOR_FUNCTIONS[k], expected)
            if k in B.STANDARD_FUNCTIONS:
                return self._standard(call, B.STANDARD_FUNCTIONS[k], expected)
            conv = B.conversion(k)
            if conv is not None:
                return self._conversion(call, k, *conv)
            if k in self.program.types or k in T.ELEMENTARY:
                self.ctx.error("E-CALL-001", f"'{callee.name}' is a type, not a function", callee.pos)
            else:
                self.ctx.error("E-DECL-001", f"undeclared function '{callee.name}'", callee.pos)
            return self._give_up(call)
        t = self.ex.infer(callee)
        if t is ts.ERROR:
            return self._give_up(call)
        if not isinstance(t, T.FBType):
            self.ctx.error("E-CALL-001", f"call: expected a function or a function block "
                           f"instance, found a variable of type {t}", callee.pos)
            return self._give_up(call)
        return self._fb_call(call, t, statement)

    def _pou_call(self, call, pou: PouInfo, statement: bool, written: str):
        """A call naming POU `pou` itself (written `written`): a FUNCTION is
        called; an FB type, a PROGRAM or an INTERFACE is refused."""
        if pou.kind == "FUNCTION":
            return self._user_function(call, pou, statement)
        if pou.kind == "FUNCTION_BLOCK":
            type_name = written if "." in written else pou.name    # qualified if called so
            msg = (f"'{written}' is a FUNCTION_BLOCK type: declare an instance "
                   f"(inst : {type_name};) and call the instance")
        elif pou.kind == "PROGRAM":
            msg = f"'{written}' is a PROGRAM: programs are run by tasks, not called"
        else:
            msg = f"'{written}' is an INTERFACE: call a method of an instance that implements it"
        self.ctx.error("E-CALL-001", msg, call.callee.pos)
        return self._give_up(call)

    # ---------------------------------------------------------- array bounds
    def _bound(self, call, name: str):
        """LOWER_BOUND(A, n) / UPPER_BOUND(A, n) (3rd ed. 6.5.3): a bound of dimension n."""
        args = [a.value for a in call.args if a.direction != "out"]
        if len(args) != 2 or len(call.args) != 2:
            self.ctx.error("E-CALL-009" if len(call.args) < 2 else "E-CALL-006",
                           f"{name}: expected an array and a dimension number, found "
                           f"{len(call.args)} argument(s)", call.pos)
            return self._give_up(call)
        t = self.ex.infer(args[0])
        self.ex.infer(args[1], T.DINT)
        dim = self.ex.constant(args[1])
        if t is ts.ERROR:
            return self.ex.record(call, ts.ERROR)
        if not isinstance(t, T.ArrayType):
            self.ctx.error("E-TYPE-006", f"{name}: expected an array, found {t}", start_pos(args[0]))
            return self.ex.record(call, ts.ERROR)
        if not isinstance(dim, int) or isinstance(dim, bool) or not 1 <= dim <= len(t.dims):
            self.ctx.error("E-TYPE-008", f"{name}: expected a constant dimension 1..{len(t.dims)}, "
                           f"found {dim if isinstance(dim, int) else 'a non-constant value'}",
                           start_pos(args[1]))
            return self.ex.record(call, ts.ERROR)
        self.program.call_targets[id(call)] = CallTarget("bound", name)
        return self.ex.record(call, T.DINT)

    # --------------------------------------------------------- references
    def _reference(self, call, name: str):
        """REF(x) (3rd ed. 6.6.1.7; ADR(x) in the codesys dialect): a reference to x."""
        args = call.args
        if len(args) != 1 or args[0].direction == "out" or args[0].value is None:
            self.ctx.error("E-CALL-009" if not args else "E-CALL-006",
                           f"{name}: expected one variable, found {len(args)} argument(s)", call.pos)
            return self._give_up(call)
        value = args[0].value
        t = check_store(self.ex, value, f"{name}(...)")
        if t is ts.ERROR:
            return self.ex.record(call, ts.ERROR)
        unaddressable = no_address(self.ex, value)
        if unaddressable is not None:
            self.ctx.error("E-TYPE-014", f"{name}(...): expected a variable, found {unaddressable}",
                           start_pos(value))
            return self.ex.record(call, ts.ERROR)
        t = self.program.subranges.get(id(value), t)     # a subrange's limits go with it
        self.program.call_targets[id(call)] = CallTarget("ref", name)
        return self.ex.record(call, T.RefType(t, name == "ADR"))

    def _namespaced(self, callee):
        """Name(F) for a callee `NS.Sub.F` whose prefix is a NAMESPACE, else None
        (_NOT_IN_NAMESPACE, reported, when that NAMESPACE declares no F).

        A qualified name names an element declared in the namespace (IEC 61131-3
        3rd ed. 6.9), never a variable or a method of the calling POU named F:
        the caller dispatches the Name to the POU itself."""
        space = self._namespace_of(callee)
        if space is None:
            return None
        if not isinstance(self.ctx.in_namespace(space, callee.name), ast.Pou):
            self.ctx.error("E-DECL-001", f"NAMESPACE {space} declares no POU '{callee.name}'", callee.pos)
            return _NOT_IN_NAMESPACE
        return ast.Name(callee.name, pos=callee.pos)

    def _namespace_of(self, callee: ast.Member) -> str | None:
        """`NS.Sub` for a callee `NS.Sub.F` whose prefix is a declared NAMESPACE, else None."""
        parts = []
        e = callee
        while isinstance(e, ast.Member):
            parts.append(e.name)
            e = e.base
        if not parts or not isinstance(e, ast.Name) or self.ex.scope.lookup(e.name) is not None:
            return None
        space = ".".join([e.name, *reversed(parts[1:])])
        return space if key(space) in self.ctx.namespaces else None

    # ------------------------------------------------------------ methods
    def _method_target(self, callee):
        """("super" | "virtual" | "interface" | "self", method PouInfo) or None
        (_NO_SUPER_METHOD, reported, for a SUPER.M with no M to call)."""
        fb = self.ex.scope.fb
        if isinstance(callee, ast.Member) and isinstance(callee.base, ast.Name) \
                and key(callee.base.name) == "SUPER" and self.ex.scope.lookup("SUPER") is None:
            parent = fb.parent if fb is not None else None
            m = find_method(parent, callee.name)
            if m is None:
                self.ctx.error("E-DECL-016", f"SUPER.{callee.name}: " + (
                    f"{fb.name} extends no FB with a method {callee.name}" if fb is not None
                    else "SUPER is only valid inside a FUNCTION_BLOCK or its methods"), callee.pos)
                return _NO_SUPER_METHOD
            return "super", m
        if isinstance(callee, ast.Member):
            t = self.ex.infer(callee.base)
            if isinstance(t, T.FBType) and key(callee.name) not in t.variables:
                m = find_method(t.info, callee.name)
                return ("virtual", m) if m is not None else None
            if isinstance(t, T.InterfaceType):
                m = interface_methods(t.info).get(key(callee.name))
                return ("interface", m) if m is not None else None
            return None
        if isinstance(callee, ast.Name) and fb is not None and self.ex.scope.lookup(callee.name) is None:
            m = find_method(fb, callee.name)
            return ("self", m) if m is not None else None
        return None

    def _super_body(self, call, statement: bool):
        """CODESYS's `SUPER^()` in the body of a derived FB: run the base FB's body
        on this instance (CODESYS online help, SUPER: "SUPER^() calls the body of
        the base function block")."""
        if not self.ctx.accepts("SUPER_BODY", call.callee.pos):
            return ts.ERROR
        fb, pou = self.ex.scope.fb, self.ex.scope.pou
        if fb is None or pou is not fb or fb.parent is None:
            self.ctx.error("E-DECL-016", "SUPER^(): only in the body of a FUNCTION_BLOCK that "
                           "EXTENDS another", call.callee.pos)
            return ts.ERROR
        if call.args:
            self.ctx.error("E-CALL-006", "SUPER^() takes no arguments (the base body runs on "
                           "this instance's variables)", call.args[0].pos)
            return ts.ERROR
        if not statement:
            self.ctx.error("E-TYPE-016", "SUPER^() returns no value and cannot be used in an "
                           "expression", call.pos)
            return ts.ERROR
        self.program.call_targets[id(call)] = CallTarget("super_body", fb.parent.name, fb.parent)
        return ts.ERROR            # a statement: no value

    def _method_call(self, call, how: str, method: PouInfo, statement: bool):
        name = f"{method.owner.name}.{method.name}"
        if not may_call(method, self.ex.scope.fb):
            self.ctx.error("E-CALL-012", f"method {name} is {method.access}: it may be called "
                           + ("only inside " + method.owner.name if method.access == "PRIVATE"
                              else f"only inside {method.owner.name} and the FBs extending it"),
                           call.callee.pos)
        if how == "super" and "ABSTRACT" in method.modifiers:
            self.ctx.error("E-DECL-016", f"SUPER.{method.name}: the method of {method.owner.name} "
                           f"is ABSTRACT (it has no body to call)", call.callee.pos)
        self.program.call_targets[id(call)] = CallTarget("method", how, method)
        note_method_call(self.ex, method, call.callee, how, call.pos)
        return self._bind_and_type(call, method, f"method {name}", statement)

    def _not_a_variable(self, name: ast.Name) -> bool:
        sym = self.ex.scope.lookup(name.name)
        # Inside a FUNCTION its own name is its result variable; a call of it
        # is a (recursive) call of the function.
        return sym is None or sym.kind == "RETURN"

    def _give_up(self, call):
        """Type the arguments (so every node has a type) and yield ERROR."""
        for arg in call.args:
            if arg.value is not None:
                self.ex.infer(arg.value)
        return self.ex.record(call, ts.ERROR)

    # ------------------------------------------------------ user POUs
    def _user_function(self, call, pou: PouInfo, statement: bool):
        self.program.call_targets[id(call)] = CallTarget("function", key(pou.name), pou)
        note_call(self.ex, pou, call.pos)
        return self._bind_and_type(call, pou, f"function {pou.name}", statement)

    def _bind_and_type(self, call, pou: PouInfo, what: str, statement: bool):
        """Bind the arguments of a function or method call; its result type."""
        self._bind(call, pou, is_function=True)
        if pou.return_type is None:
            if not statement:
                self.ctx.error("E-TYPE-016", f"{what} returns no value and cannot be used in "
                               f"an expression", call.pos)
                return self.ex.record(call, ts.ERROR)
            return ts.ERROR
        return self.ex.record(call, pou.return_type)

    def _fb_call(self, call, fb: T.FBType, statement: bool):
        pou = self.program.pous.get(key(fb.name))
        self.program.call_targets[id(call)] = CallTarget("fb", key(fb.name), pou)
        if pou is not None:
            note_call(self.ex, pou, call.pos)
        if not statement:
            self.ctx.error("E-CALL-010", f"function block instance of {fb.name} called inside an "
                           f"expression: call it as a statement, then read its outputs", call.pos)
            return self._give_up(call)
        if pou is not None:
            self._bind(call, pou, is_function=False)
        return ts.ERROR

    def _bind(self, call, pou: PouInfo, is_function: bool) -> None:
        positional = [s for s in pou.variables.values() if s.kind in ("VAR_INPUT", "VAR_IN_OUT")]
        seen: set[str] = set()
        formal_seen = False
        n_positional = 0
        for arg in call.args:
            if arg.name is None:
                if formal_seen:
                    self._refuse("E-CALL-008", f"call of {pou.name}: positional argument after "
                                 f"a formal (name := value) argument", arg)
                    continue
                if n_positional >= len(positional):
                    self._refuse("E-CALL-006", f"call of {pou.name}: expected at most "
                                 f"{len(positional)} positional argument(s), found "
                                 f"{sum(1 for a in call.args if a.name is None)}", arg)
                    n_positional += 1
                    continue
                sym = positional[n_positional]
                n_positional += 1
            else:
                formal_seen = True
                sym = pou.variables.get(key(arg.name))
                if sym is None or sym.kind not in _PIN_KINDS:
                    foreign = self.ctx.foreign_pin(pou.name, arg.name)
                    if foreign is not None:
                        self._refuse("E-PIN-001", foreign, arg)
                        continue
                    pins = ", ".join(s.name for s in pou.variables.values() if s.kind in _PIN_KINDS)
                    self._refuse("E-CALL-002", f"{pou.name} has no parameter '{arg.name}' "
                                 f"(parameters: {pins or 'none'})", arg)
                    continue
            k = key(sym.name)
            if k in seen:
                self._refuse("E-CALL-003", f"call of {pou.name}: parameter '{sym.name}' is "
                             f"given twice", arg)
                continue
            seen.add(k)
            self._pass(call, pou, arg, sym)
        for sym in pou.in_outs:
            if key(sym.name) not in seen:
                self.ctx.error("E-CALL-004", f"call of {pou.name}: VAR_IN_OUT '{sym.name}' "
                               f"({sym.type}) is missing; in-out parameters are required at "
                               f"every call", call.pos)
        if is_function and n_positional and not formal_seen and n_positional < len(positional):
            self.ctx.error("E-CALL-009", f"call of {pou.name}: expected {len(positional)} "
                           f"argument(s), found {n_positional}", call.pos)

    def _pass(self, call, pou, arg, sym) -> None:
        if arg.value is None:
            return
        what = f"argument '{sym.name}' of {pou.name}"
        if arg.direction == "out":
            if sym.kind != "VAR_OUTPUT":
                self._refuse("E-CALL-005", f"'{sym.name}' is a {sym.kind} of {pou.name}: pass "
                             f"it with :=, not =>", arg)
                return
            target = check_store(self.ex, arg.value, f"output '{sym.name}' of {pou.name}")
            if target is not ts.ERROR and arg.negated and not ts.is_bool(sym.type):
                self.ctx.error("E-TYPE-001", f"NOT on output '{sym.name}': expected BOOL, found "
                               f"{sym.type}", arg.pos)
                return
            self.ex.require_assignable(sym.type, target, start_pos(arg.value),
                                       f"output '{sym.name}' of {pou.name}")
            return
        if sym.kind == "VAR_OUTPUT":
            self._refuse("E-CALL-005", f"'{sym.name}' is an output of {pou.name}: read it "
                         f"with =>, not :=", arg)
            return
        if sym.kind == "VAR_IN_OUT":
            self._in_out(pou, arg.value, sym)
            note_in_out(self.ex, arg.value)
            return
        self.ex.check_value(arg.value, sym.type, what)
        note_argument(self.ex, pou, sym, arg.value, call.pos)

    def _in_out(self, pou, value, sym) -> None:
        if not is_variable_path(value):
            self.ex.infer(value)
            self.ctx.error("E-CALL-007", f"VAR_IN_OUT '{sym.name}' of {pou.name}: expected a "
                           f"variable, found an expression", start_pos(value))
            return
        t = self.ex.infer(value)
        if t is ts.ERROR:
            return
        unaddressable = no_address(self.ex, value)
        if unaddressable is not None:       # passed by reference
            self.ctx.error("E-CALL-007", f"VAR_IN_OUT '{sym.name}' of {pou.name}: expected a "
                           f"variable, found {unaddressable}", start_pos(value))
            return
        ref = self.program.name_refs.get(id(root_name(value)))
        if not hasattr(ref, "kind"):
            self.ctx.error("E-CALL-007", f"VAR_IN_OUT '{sym.name}' of {pou.name}: expected a "
                           f"variable, found an enumeration value", start_pos(value))
            return
        problem = in_out_problem(self.ex, value, ref)
        if problem is not None:
            self.ctx.error("E-CALL-007", f"VAR_IN_OUT '{sym.name}' of {pou.name}: expected a "
                           f"writable variable, found {problem}", start_pos(value))
            return
        if isinstance(sym.type, T.ArrayType) and sym.type.is_open and isinstance(t, T.ArrayType) \
                and len(t.dims) == len(sym.type.dims) and ts.same_type(t.element, sym.type.element):
            return                  # ARRAY[*]: any bounds, same rank and element type
        if not ts.same_type(t, sym.type):
            self.ctx.error("E-CALL-011", f"VAR_IN_OUT '{sym.name}' of {pou.name}: expected a "
                           f"variable of type {sym.type}, found {t} (in-out parameters are passed "
                           f"by reference, without conversion)", start_pos(value))

    def _refuse(self, code: str, message: str, arg) -> None:
        """Report a bad argument, still typing its value (its own errors show)."""
        self.ctx.error(code, message, arg.pos)
        self._infer_arg(arg)

    def _infer_arg(self, arg) -> None:
        if arg.value is not None:
            self.ex.infer(arg.value)

    # ------------------------------------- operators in call form (ADD, GT)
    def _operator_call(self, call, name: str, fn, expected):
        values, problem = ordered_inputs(name, fn, call.args)
        if problem:
            self.ctx.error(problem[0], problem[1], call.pos)
            return self._give_up(call)
        for i, (value, want) in enumerate(zip(values, fn.operands), start=1):
            wanted = T.ELEMENTARY.get(want)
            t = self.ex.infer(value, wanted)
            if t is ts.ERROR:
                return self._give_up(call)
            if not (ts.is_num(t) if want == "ANY_NUM" else t is wanted):
                self.ctx.error("E-TYPE-004", f"{name}: argument IN{i}: expected "
                               f"{B.describe(want) if want == 'ANY_NUM' else want}, found {t}",
                               start_pos(value))
                return self._give_up(call)
        lowered = lower(fn, values, call.pos)
        self.program.lowered[id(call)] = lowered
        return self.ex.record(call, self.ex.infer(lowered, expected), self.ex.constant(lowered))

    # ------------------------------------------------- standard functions
    def _standard(self, call, fn: B.Builtin, expected):
        bound: list[tuple[B.Param, ast.Arg]] = []
        seen: set[str] = set()
        formal_seen = False
        ok = True
        for i, arg in enumerate(call.args):
            if arg.direction == "out":
                self._refuse("E-CALL-005", f"{fn.name} has no outputs: '{arg.name}' cannot be "
                             f"read with =>", arg)
                ok = False
                continue
            if arg.name is None:
                if formal_seen:
                    self._refuse("E-CALL-008", f"call of {fn.name}: positional argument after "
                                 f"a formal argument", arg)
                    ok = False
                    continue
                if i >= len(fn.params) and not fn.extensible:
                    self._refuse("E-CALL-006", f"{fn.name}: expected {len(fn.params)} "
                                 f"argument(s), found {len(call.args)}", arg)
                    ok = False
                    continue
                param = B.extra_param(fn, i)
            else:
                formal_seen = True
                param = self._standard_param(fn, arg.name)
                if param is None:
                    pins = ", ".join(p.name for p in fn.params)
                    self._refuse("E-CALL-002", f"{fn.name} has no parameter '{arg.name}' "
                                 f"(parameters: {pins}{', ...' if fn.extensible else ''})", arg)
                    ok = False
                    continue
            if param.name in seen:
                self._refuse("E-CALL-003", f"call of {fn.name}: parameter '{param.name}' is "
                             f"given twice", arg)
                ok = False
                continue
            seen.add(param.name)
            bound.append((param, arg))
        if ok and len(bound) < fn.min_args:
            self.ctx.error("E-CALL-009", f"{fn.name}: expected {'at least ' if fn.extensible else ''}"
                           f"{fn.min_args} argument(s), found {len(bound)}", call.pos)
            ok = False
        generic_t = self._instantiate(fn, bound, expected)
        for param, arg in bound:
            if not param.generic:
                ok &= self._standard_fixed(fn, param, arg)
        if generic_t is ts.ERROR or not ok:
            for param, arg in bound:
                if id(arg.value) not in self.program.expr_types and arg.value is not None:
                    self.ex.infer(arg.value)
            return self.ex.record(call, ts.ERROR)
        result = self._standard_result(fn, generic_t, bound, expected)
        self.program.call_targets[id(call)] = CallTarget("function", fn.name, None, generic_t)
        return self.ex.record(call, result)

    @staticmethod
    def _standard_param(fn: B.Builtin, name: str):
        k = key(name)
        for p in fn.params:
            if p.name == k:
                return p
        if fn.extensible and k.startswith("IN") and k[2:].isdigit():
            n = int(k[2:])
            index = n + 1 if fn.name == "MUX" else n - 1
            if index >= len(fn.params):
                return B.extra_param(fn, index)
        return None

    def _instantiate(self, fn, bound, expected):
        """The type T of the generic parameters, or None if there are none."""
        generic = [(p, a) for p, a in bound if p.generic and a.value is not None]
        if not generic:
            return None
        category = generic[0][0].category
        typed = [(p, a) for p, a in generic if not self.ex.untyped(a.value)]
        untyped = [(p, a) for p, a in generic if self.ex.untyped(a.value)]
        t = None
        for p, a in typed:
            at = self.ex.infer(a.value, expected)
            if at is ts.ERROR:
                t = ts.ERROR
                continue
            if t is None:
                t = at
            elif t is not ts.ERROR:
                c = ts.common_type(t, at) if not (ts.is_string(t) and ts.is_string(at)) else t
                if c is None and isinstance(t, T.EnumType) and at is t:
                    c = t
                if c is None:
                    self.ctx.error("E-TYPE-002", f"{fn.name}: arguments of types {t} and {at} "
                                   f"have no common type", start_pos(a.value))
                    t = ts.ERROR
                else:
                    t = c
        hint = t if t is not None else (expected if B.in_category(expected, category) else None)
        if hint is None and category == "ANY_REAL":
            hint = T.LREAL
        for p, a in untyped:
            at = self.ex.infer(a.value, hint)
            if category in ("ANY_BITS", "ANY_BIT") and hint is None and ts.is_int(at):
                value = self.ex.constant(a.value)
                bits = ts.smallest_bits_type(value) if isinstance(value, int) else None
                if bits is not None:
                    at = self.ex.record(a.value, bits, value)
            if t is None:
                t = at
            elif t is not ts.ERROR and at is not ts.ERROR:
                t = ts.common_type(t, at) or t
        if t is ts.ERROR or t is None:
            return ts.ERROR if t is ts.ERROR else None
        if not B.in_category(t, category):
            suggestion = {"ANY_REAL": T.LREAL, "ANY_BITS": _bits_for(t)}.get(category)
            self.ctx.error("E-TYPE-004", f"{fn.name}: expected {B.describe(category)}, found {t}"
                           + (ts.conversion_hint(t, suggestion) if suggestion is not None else ""),
                           start_pos(generic[0][1].value))
            return ts.ERROR
        return t

    def _standard_fixed(self, fn, param, arg) -> bool:
        if arg.value is None:
            return True
        category = param.category
        hint = {"BOOL": T.BOOL, "ANY_INT": T.DINT, "STRING": T.StringType(),
                "ANY_NUM": None}.get(category, T.ELEMENTARY.get(category))
        t = self.ex.infer(arg.value, hint, strict=category == "BOOL")
        if t is ts.ERROR:
            return False
        if not B.in_category(t, category):
            self.ctx.error("E-TYPE-004", f"{fn.name}: argument {param.name}: expected "
                           f"{B.describe(category)}, found {t}", start_pos(arg.value))
            return False
        return True

    def _standard_result(self, fn, generic_t, bound, expected):
        if fn.result == "T":
            return generic_t
        if fn.result == "INT":
            return T.INT
        if fn.result == "STRING":
            return T.StringType()
        if fn.result == "ANY_INT":
            return expected if ts.is_int(expected) else T.DINT
        return T.ELEMENTARY.get(fn.result, ts.ERROR)

    # --------------------------------------------------------- conversions
    def _conversion(self, call, name, src, dst):
        canonical = f"{_short(src)}_TO_{_short(dst)}"
        args = list(call.args)
        bad = [a for a in args if a.direction == "out" or (a.name is not None and key(a.name) != "IN")]
        if bad or len(args) != 1:
            for a in bad:
                self.ctx.error("E-CALL-002", f"{canonical} has one input, IN; found "
                               f"'{a.name}'", a.pos)
            if not bad:
                self.ctx.error("E-CALL-009" if not args else "E-CALL-006",
                               f"{canonical}: expected 1 argument, found {len(args)}", call.pos)
            return self._give_up(call)
        value = args[0].value
        t = self.ex.infer(value, src, strict=True)
        if t is ts.ERROR:
            return self.ex.record(call, ts.ERROR)
        if not ts.implicitly_converts(t, src):
            self.ctx.error("E-TYPE-004", f"argument of {canonical}: expected {src}, found {t}"
                           + _conversion_hint(t, dst), start_pos(value))
            return self.ex.record(call, ts.ERROR)
        self.program.call_targets[id(call)] = CallTarget("conversion", canonical, None, dst)
        return self.ex.record(call, dst)


def _short(t) -> str:
    if isinstance(t, T.StringType):
        return "STRING"
    return ts.short_name(t)


def _conversion_hint(t, dst) -> str:
    """The conversion to use instead for an argument of type `t`; none from a type to
    itself (issue 16: INT_TO_DINT of a DINT suggested DINT_TO_DINT, no such function)."""
    if not isinstance(t, T.ElementaryType):
        return ""
    if _short(t) == _short(dst):
        return f"; the value is a {dst} already: no conversion is needed"
    return f"; use {_short(t)}_TO_{_short(dst)}"


def _bits_for(t):
    """The bit string of the same width as an integer type (for a hint), else None."""
    if ts.is_int(t):
        return {8: T.BYTE, 16: T.WORD, 32: T.DWORD, 64: T.LWORD}.get(t.bits)
    return None

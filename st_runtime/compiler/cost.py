"""Estimated NJ501 execution time of ST code, per basic block.

The compiler gives every basic block of the ST source (a run of assignments
and calls, with the condition, selector or bounds that ends it) a cost at
compile time and charges it when the block runs: one subtraction from the
scan's remaining time (`_ctx.budget`).  The estimate therefore belongs to
the ST text, not to the Python that runs it, and stays the same under any
later change of the generated Python.  The controller reports the time per
scan per task and ends a scan whose estimate exceeds the task period with
F-PERIOD (which also ends a runaway loop at once).

The weights.  OMRON publishes instruction execution times for the NJ501 in
the NJ/NX-series Instructions Reference Manual (W502), appendix
"Instruction execution times" (NJ501-1x00 columns).  That table could not
be found in any public source this project can reach (searches of OMRON
manual mirrors found only the CJ2 and CV-series tables and the NJ W501
task-time appendix), so the RELATIVE weights below are an ASSUMPTION, not
a measurement: unit costs in proportions typical of compiled floating-point
code (an elementary load/store/integer step 1, an LREAL add or multiply 2,
a division 8, SQRT 8, a trigonometric/exponential function 30, an array
subscript with its bounds check 2).  Only their
proportions matter: ONE overall scale (`PICOSECONDS_PER_UNIT`) is fitted so
that one Newton-Raphson iteration of the generated SP_ForwardKinematics
(Leibniz-table variant) costs the study's 49.5 us on an NJ501-1300 (SPEC 3
and 7); tests/test_cost_model.py holds that calibration and checks the
model against the study's end points (3 iterations 0.149 ms, 13 iterations
0.644 ms).  docs/nj501.md, "What a scan costs", states the uncertainty.
"""

from __future__ import annotations

from .. import ast
from ..native import NATIVE_FBS
from ..types import ArrayType, ElementaryType, FBType, StringType, StructType, resolve_alias

# ---------------------------------------------------------------- the weights
# Relative cost of one operation, in units (see the module docstring: an
# assumption in the proportions of a compiled FPU program; one scale below).
WEIGHTS: dict[str, float] = {
    "load": 1,          # read a variable or a literal operand
    "store": 1,         # write an elementary variable
    "int_op": 1,        # integer / bit-string + - * AND OR XOR NOT, negation
    "int_div": 4,       # integer / and MOD
    "real_add": 2,      # REAL/LREAL + and -
    "real_mul": 2,      # REAL/LREAL *
    "real_div": 8,      # REAL/LREAL /
    "compare": 1,       # = <> < <= > >=
    "index": 2,         # one array subscript: offset arithmetic and bounds check
    "sqrt": 8,          # SQRT
    "transcendental": 30,  # SIN COS TAN ASIN ACOS ATAN ATAN2 EXP LN LOG EXPT
    "function": 4,      # any other standard function or conversion (ABS, MIN, LREAL_TO_INT, ...)
    "call": 10,         # call and return of a user FUNCTION or FUNCTION_BLOCK
    "argument": 1,      # one parameter passed (aggregates: per element)
    "element": 2,       # one element moved by an array or structure assignment (a load and a store)
    "branch": 1,        # an IF / ELSIF test's jump, a CASE label compared
    "loop": 2,          # one loop iteration: increment, end test, jump back
    "standard_fb": 20,  # a standard FB instruction (TON, R_TRIG, CTU, ...)
    "motion_fb": 100,   # a PLCopen motion instruction (MC_Power, MC_SyncMoveAbsolute, ...)
}

# The one overall scale: picoseconds of NJ501 time per unit.  Fitted so that
# one Newton-Raphson iteration of generated/iec SP_ForwardKinematics (Leibniz
# table variant) costs the study's 49.5 us (SPEC 3): with the weights above
# an iteration is 82,816.5 units (the slope between solves of 1 and 3
# iterations in one scan; tests/test_cost_model.py recomputes it), and
# 49.5e6 ps / 82,816.5 = 597.7, rounded to 598 (iteration 49.52 us).
PICOSECONDS_PER_UNIT = 598

_TRANSCENDENTAL = {"SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "ATAN2", "EXP", "LN", "LOG", "EXPT"}


def picoseconds(units: float) -> int:
    """Units of the weights table as NJ501 picoseconds (the budget's unit)."""
    return int(round(units * PICOSECONDS_PER_UNIT))


def elements(t) -> int:
    """Elementary values an assignment of type `t` moves (arrays and structures by element)."""
    t = resolve_alias(t)
    if isinstance(t, ArrayType):
        return t.size * elements(t.element)
    if isinstance(t, StructType):
        return sum(elements(ft) for _, ft in t.fields.values()) or 1
    if isinstance(t, FBType):
        return sum(elements(s.type) for s in t.variables.values()) or 1
    if isinstance(t, StringType):
        return 1 + t.length // 8       # moved 8 bytes at a time
    return 1


class CostModel:
    """Units of ST expressions and statements, from the checker's types and calls."""

    def __init__(self, program):
        self.program = program
        w = WEIGHTS
        self.w = w

    def ty(self, e):
        t = self.program.expr_types.get(id(e))
        return resolve_alias(t) if t is not None else None

    def _is_real(self, e) -> bool:
        t = self.ty(e)
        return isinstance(t, ElementaryType) and t.kind == "real"

    # ------------------------------------------------------------ expressions

    def expr(self, e) -> float:
        if e is None:
            return 0
        w = self.w
        if isinstance(e, (ast.IntLiteral, ast.RealLiteral, ast.BoolLiteral, ast.StringLiteral,
                          ast.TimeLiteral, ast.DateTimeLiteral, ast.EnumLiteral, ast.Name)):
            return w["load"]
        if isinstance(e, ast.Member):
            return self.expr(e.base)            # a member is a constant offset
        if isinstance(e, ast.Index):
            return self.expr(e.base) + sum(self.expr(i) + w["index"] for i in e.indices)
        if isinstance(e, ast.Unary):
            return self.expr(e.operand) + (w["real_add"] if self._is_real(e) else w["int_op"])
        if isinstance(e, ast.Binary):
            return self.expr(e.left) + self.expr(e.right) + self._binary(e)
        if isinstance(e, ast.Call):
            return self.call(e)
        return w["load"]

    def _binary(self, e) -> float:
        w = self.w
        op = e.op.upper()
        if op in ("=", "<>", "<", "<=", ">", ">="):
            return w["compare"]
        real = self._is_real(e)
        if op in ("+", "-"):
            return w["real_add"] if real else w["int_op"]
        if op == "*":
            return w["real_mul"] if real else w["int_op"]
        if op == "/":
            return w["real_div"] if real else w["int_div"]
        if op == "MOD":
            return w["int_div"]
        if op == "**":
            return w["transcendental"]
        return w["int_op"]                      # AND, OR, XOR, &

    def _arguments(self, call, variables: dict) -> float:
        """Passing the arguments: by value element by element, a VAR_IN_OUT by
        reference (one element).  Positional arguments count by value."""
        w = self.w
        total = 0.0
        for arg in call.args:
            if arg.value is None:
                continue
            symbol = variables.get(arg.name.upper()) if arg.name else None
            if symbol is not None and symbol.kind == "VAR_IN_OUT":
                total += w["argument"] + self._address(arg.value)
                continue
            t = self.ty(arg.value)
            n = elements(t) if t is not None else 1
            total += w["argument"] * n + (self.expr(arg.value) if n == 1 else self._address(arg.value))
        return total

    def call(self, call) -> float:
        """A call: its own instruction and the arguments passed; the body of a
        user POU is charged by the callee's own blocks when it runs."""
        lowered = self.program.lowered.get(id(call))
        if lowered is not None:     # ADD(a, b) and the like: compiled as the operator, charged so
            return self.expr(lowered)
        w = self.w
        target = self.program.call_targets.get(id(call))
        pou = getattr(target, "pou", None)
        variables = pou.variables if pou is not None else getattr(self.ty(call.callee), "variables", {})
        args = self._arguments(call, variables or {})
        if target is None:
            return w["call"] + args
        if target.kind == "conversion":
            return w["function"] + args
        if target.kind == "fb":
            name = str(target.name).upper()
            # An FB written in ST, a project's own TON (W-DECL-001) too: a user POU call,
            # its blocks charge themselves (docs/nj501.md, the weights).
            if name not in NATIVE_FBS or (pou is not None and pou.native is None):
                return w["call"] + args
            return (w["motion_fb"] if name.startswith("MC_") else w["standard_fb"]) + args
        if target.pou is not None and target.pou.node is not None:
            return w["call"] + args
        name = str(target.name).upper()
        if name == "SQRT":
            return w["sqrt"] + args
        if name in _TRANSCENDENTAL:
            return w["transcendental"] + args
        return w["function"] + args

    # ------------------------------------------------------------- statements

    def simple(self, s) -> float:
        """An assignment or a call statement (EXIT, CONTINUE, RETURN: a jump)."""
        w = self.w
        if isinstance(s, ast.Assign):
            t = self.ty(s.target)
            if t is None:
                t = self.ty(s.value)
            n = elements(t) if t is not None else 1
            if n > 1:           # an array or structure: moved element by element
                return n * w["element"] + self._address(s.target) + self._address(s.value)
            return self.expr(s.value) + self._address(s.target) + w["store"]
        if isinstance(s, ast.CallStmt):
            return self.call(s.call)
        return w["branch"]

    def _address(self, e) -> float:
        """Locating an lvalue or aggregate operand: its subscripts, not a load."""
        if isinstance(e, ast.Index):
            return self._address(e.base) + sum(self.expr(i) + self.w["index"] for i in e.indices)
        if isinstance(e, ast.Member):
            return self._address(e.base)
        if isinstance(e, ast.Call):
            return self.call(e)
        return 0

    def condition(self, e) -> float:
        """A test that decides a jump (IF, ELSIF, WHILE, UNTIL)."""
        return self.expr(e) + self.w["branch"]

    def for_setup(self, s) -> float:
        """FOR before its first iteration: bounds (and step) evaluated, variable set."""
        return self.expr(s.start) + self.expr(s.end) + self.expr(s.step) + self.w["store"]

    def loop(self) -> float:
        return self.w["loop"]

    def case_labels(self, clause) -> int:
        return sum(1 for _ in clause.labels)

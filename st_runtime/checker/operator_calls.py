"""Standard functions that are operators in call form: ADD(a, b) is a + b.

IEC 61131-3 (Tables 29, 30, 31) gives the arithmetic and comparison
operators a function form (ADD, SUB, MUL, DIV, MOD, GT, GE, EQ, NE, LE, LT;
Beremiz's FBD-to-ST output calls them) and names the time arithmetic
(ADD_TIME, MULTIME, SUB_DT_DT, ...; the 3rd edition also spells MUL_TIME,
DIV_TIME).  The checker lowers such a call to the operator's expression
(`CheckedProgram.lowered`), types that, and the compiler compiles it: one
meaning for both spellings.  ADD and MUL take any number of inputs (left to
right); a comparison with more inputs is the chain `a > b AND b > c`.
These names are not reserved: a user FUNCTION named DIV (common in code
written before the 3rd edition) is called instead, as its declaration says.
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import ast


@dataclass(frozen=True, slots=True)
class OperatorFunction:
    op: str
    extensible: bool = False          # ADD, MUL: any number of inputs; comparisons chain
    operands: tuple[str, ...] = ()    # for the time functions: the operand types required
    result: str | None = None         # and the result type (by name)


_ARITH = {"ADD": OperatorFunction("+", True), "MUL": OperatorFunction("*", True),
          "SUB": OperatorFunction("-"), "DIV": OperatorFunction("/"),
          "MOD": OperatorFunction("MOD")}
_COMPARE = {name: OperatorFunction(op, True) for name, op in
            (("GT", ">"), ("GE", ">="), ("EQ", "="), ("NE", "<>"), ("LE", "<="), ("LT", "<"))}
_COMPARE["NE"] = OperatorFunction("<>")      # NE is not extensible (Table 31)


def _time(op, left, right, result) -> OperatorFunction:
    return OperatorFunction(op, False, (left, right), result)


_TIME = {
    "ADD_TIME": _time("+", "TIME", "TIME", "TIME"),
    "SUB_TIME": _time("-", "TIME", "TIME", "TIME"),
    "MULTIME": _time("*", "TIME", "ANY_NUM", "TIME"),
    "MUL_TIME": _time("*", "TIME", "ANY_NUM", "TIME"),
    "DIVTIME": _time("/", "TIME", "ANY_NUM", "TIME"),
    "DIV_TIME": _time("/", "TIME", "ANY_NUM", "TIME"),
    "ADD_TOD_TIME": _time("+", "TIME_OF_DAY", "TIME", "TIME_OF_DAY"),
    "ADD_DT_TIME": _time("+", "DATE_AND_TIME", "TIME", "DATE_AND_TIME"),
    "SUB_DATE_DATE": _time("-", "DATE", "DATE", "TIME"),
    "SUB_TOD_TIME": _time("-", "TIME_OF_DAY", "TIME", "TIME_OF_DAY"),
    "SUB_TOD_TOD": _time("-", "TIME_OF_DAY", "TIME_OF_DAY", "TIME"),
    "SUB_DT_TIME": _time("-", "DATE_AND_TIME", "TIME", "DATE_AND_TIME"),
    "SUB_DT_DT": _time("-", "DATE_AND_TIME", "DATE_AND_TIME", "TIME"),
}

OPERATOR_FUNCTIONS: dict[str, OperatorFunction] = {**_ARITH, **_COMPARE, **_TIME}


def ordered_inputs(name: str, fn: OperatorFunction, args) -> tuple[list, tuple | None]:
    """The input expressions in order (IN1, IN2, ...), or ([], (code, why not))."""
    positional, named = [], {}
    for arg in args:
        if arg.direction == "out":
            return [], ("E-CALL-005", f"{name} has no outputs: '{arg.name}' cannot be read with =>")
        if arg.name is None:
            if named:
                return [], ("E-CALL-008", f"call of {name}: positional argument after a formal argument")
            positional.append(arg.value)
        else:
            k = ast.key(arg.name)
            if not (k.startswith("IN") and k[2:].isdigit()) or int(k[2:]) < 1:
                return [], ("E-CALL-002", f"{name} has no parameter '{arg.name}' (parameters: "
                            f"IN1, IN2{', ...' if fn.extensible else ''})")
            if k in named:
                return [], ("E-CALL-003", f"call of {name}: parameter '{arg.name}' is given twice")
            named[k] = arg.value
    values = positional + [named.get(f"IN{i}") for i in range(len(positional) + 1,
                                                            len(positional) + len(named) + 1)]
    if any(v is None for v in values):
        return [], ("E-CALL-002", f"{name}: the inputs IN1, IN2, ... must be numbered without gaps")
    if len(values) < 2:
        return [], ("E-CALL-009", f"{name}: expected {'at least ' if fn.extensible else ''}"
                    f"2 argument(s), found {len(values)}")
    if len(values) > 2 and not fn.extensible:
        return [], ("E-CALL-006", f"{name}: expected 2 argument(s), found {len(values)}")
    return values, None


def lower(fn: OperatorFunction, values: list, pos: ast.Pos):
    """The operator expression of a call with these inputs."""
    if fn.op in ("+", "*") or len(values) == 2:
        result = values[0]
        for value in values[1:]:
            result = ast.Binary(fn.op, result, value, pos=pos)
        return result
    # A chained comparison: every neighbouring pair holds.
    result = None
    for left, right in zip(values, values[1:]):
        pair = ast.Binary(fn.op, left, right, pos=pos)
        result = pair if result is None else ast.Binary("AND", result, pair, pos=pos)
    return result

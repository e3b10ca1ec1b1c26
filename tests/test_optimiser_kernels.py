"""The `kernels` pass (st_runtime/compiler/optimise/kernels.py): a run of float assignments
computed by one native call gives every value Python's own lines give, bit for bit, and
where it cannot (an int, a short list, a value not finite, a negative SQRT argument) the
lines run in Python as written, with the same exception.

The references are Python's float arithmetic: the lines executed as they are (SP_InverseKinematics'
rotation and two legs as the compiler writes them on the wave, and a run whose SQRT argument
can be negative)."""

from __future__ import annotations

import math
import random
import re
import struct
import sys

import pytest

pytest.importorskip("llvmlite")

from st_runtime.compiler.optimise import kernels, native  # noqa: E402

#: SP_InverseKinematics' generated lines (the wave's body): the rotation (a unary minus),
#: leg 1 (list elements at literal indices, SQRT) and leg 2 (names of leg 1 read again).
IK = """\
v_R11 = (v_COSALPHA * v_COSBETA)
_c16 = (v_COSALPHA * v_SINBETA)
v_R12 = ((_c16 * v_SINGAMMA) - (v_SINALPHA * v_COSGAMMA))
v_R13 = ((_c16 * v_COSGAMMA) + (v_SINALPHA * v_SINGAMMA))
v_R21 = (v_SINALPHA * v_COSBETA)
_c24 = (v_SINALPHA * v_SINBETA)
v_R22 = ((_c24 * v_SINGAMMA) + (v_COSALPHA * v_COSGAMMA))
v_R23 = ((_c24 * v_COSGAMMA) - (v_COSALPHA * v_SINGAMMA))
v_R31 = (-v_SINBETA)
v_R32 = (v_COSBETA * v_SINGAMMA)
v_R33 = (v_COSBETA * v_COSGAMMA)
v_DONE = True
_c33 = (v_R11 * 385.00245915524675)
_c36 = (v_R13 * -115.0)
v_U = ((_c33 + (v_R12 * 55.273944534586455)) + _c36)
_c38 = (v_R21 * 385.00245915524675)
_c41 = (v_R23 * -115.0)
v_V = ((_c38 + (v_R22 * 55.273944534586455)) + _c41)
_c43 = (v_R31 * 385.00245915524675)
_c46 = (v_R33 * -115.0)
v_W = ((_c43 + (v_R32 * 55.273944534586455)) + _c46)
_c48 = v_POSE[0]
v_LEGX = (v_U + (_c48 - 315.006001127631))
_c51 = v_POSE[1]
v_LEGY = (v_V + (_c51 - 349.4201221360597))
_c56 = ((v_POSE[2] + 1374.0) - 95.0)
v_LEGZ = (v_W + _c56)
_c64 = (_m_sqrt((((v_LEGX * v_LEGX) + (v_LEGY * v_LEGY)) + (v_LEGZ * v_LEGZ))) - 1192.63)
v_POSITION[0] = _c64
v_U = (((v_R11 * -144.63258944329948) + (v_R12 * 361.0588824152176)) + _c36)
v_V = (((v_R21 * -144.63258944329948) + (v_R22 * 361.0588824152176)) + _c41)
v_W = (((v_R31 * -144.63258944329948) + (v_R32 * 361.0588824152176)) + _c46)
v_LEGX = (v_U + (_c48 - 145.10370179947358))
v_LEGY = (v_V + (_c51 - 447.51326038910787))
v_LEGZ = (v_W + _c56)
_c89 = (_m_sqrt((((v_LEGX * v_LEGX) + (v_LEGY * v_LEGY)) + (v_LEGZ * v_LEGZ))) - 1192.63)
v_POSITION[1] = _c89""".splitlines()
IK_INPUTS = ("v_COSALPHA", "v_COSBETA", "v_SINBETA", "v_SINGAMMA", "v_SINALPHA", "v_COSGAMMA")

#: A run whose SQRT argument is negative when A < B (math.sqrt raises ValueError, on its line).
SIGNED = """\
_c1 = ((v_A - v_B) * (v_A + v_B))
_c2 = ((_c1 * 0.5) + (v_A * v_A))
_c3 = ((_c2 - (v_B * v_B)) * 2.0)
_c4 = (_m_sqrt((_c1 - (_c3 * 0.25))) + 1.0)
_c5 = ((_c4 * _c4) - ((v_A * 3.0) + (v_B * -2.5)))
_c6 = (((_c5 * v_A) + (_c5 * v_B)) - ((_c4 - _c1) * (_c2 + 7.0)))""".splitlines()

SPECIAL = [math.inf, -math.inf, math.nan, 0.0, -0.0, 5e-324, -2.5e-310, 1e-300, 1e200, -1e200]


def _bits(x) -> bytes:
    return struct.pack("<d", x) if type(x) is float else repr(x).encode()


def _function(lines: list[str], params: tuple[str, ...], namespace: dict):
    """`lines` as a function of `params` returning its locals (or the exception it raised)."""
    body = "\n".join("    " + line for line in lines)
    source = (f"def run({', '.join(params)}):\n    v_POSITION = [0.0] * 6\n    try:\n"
              + "\n".join("    " + line for line in body.splitlines())
              + "\n    except Exception as exc:\n        return type(exc).__name__\n"
              "    return {k: v for k, v in locals().items() if k not in ('exc', '_kr')}\n")
    exec(compile(source, "<kernels test>", "exec"), namespace)
    return namespace["run"]


def _register(bound):
    names = iter(range(1000))

    def register(value):
        name = f"_k{next(names)}"
        bound[name] = value
        return name
    return register


def _passed(lines, read_after=True):
    """The pass's lines; with `read_after`, as if a line after them read every name they set
    (the kernel returns them all: the tests compare every local), that line left out."""
    names = dict.fromkeys(line.split(" = ")[0].strip() for line in lines if re.match(r" *\w+ = ", line))
    after, bound = list(lines) + [f"_live = ({', '.join(names)},)"] * read_after, {"_m_sqrt": math.sqrt}
    kernels.replace(after, 0, _register(bound), bound.__setitem__)
    return after[:len(after) - read_after], bound


def _same(want, got) -> bool:
    if isinstance(want, str) or isinstance(got, str):
        return want == got
    return want.keys() == got.keys() and all(
        _bits(want[k]) == _bits(got[k]) or (isinstance(want[k], list) and list(map(_bits, want[k])) == list(map(_bits, got[k])))
        for k in want)


def _ik_rows(rng: random.Random):
    """Angles' cosines and sines and a pose: ordinary, then with special values."""
    for k in range(200):
        angles = [rng.uniform(-0.6, 0.6) for _ in range(3)]
        values = [math.cos(angles[0]), math.cos(angles[1]), math.sin(angles[1]), math.sin(angles[2]),
                  math.sin(angles[0]), math.cos(angles[2])]
        pose = [rng.uniform(-200.0, 200.0), rng.uniform(-200.0, 200.0), rng.uniform(-100.0, 100.0)]
        if k >= 100:
            for _ in range(1 + k % 3):
                (values if k % 2 else pose)[rng.randrange(3)] = rng.choice(SPECIAL)
        yield values, pose


def _mismatches(lines, params, rows) -> list:
    after, bound = _passed(lines)
    python = _function(lines, params, {"_m_sqrt": math.sqrt})
    kernel = _function(after, params, bound)
    return [row for row in rows if not _same(python(*row), kernel(*row))]


def _ik_arguments(rng):
    return [(*values, pose) for values, pose in _ik_rows(rng)]


def test_the_pass_makes_one_kernel_across_the_stores_and_the_assignment_between():
    """The rotation, `v_DONE = True` and the two legs with a store after each are one span: the
    assignment and leg 1's store run after the kernel where it answers, leg 2's (after the
    last run line) stays after the span."""
    after, bound = _passed(IK)
    assert after.count("if _kr is None:") == 1
    assert after[0] == ("_kr = _k0(v_COSALPHA, v_COSBETA, v_SINBETA, v_SINGAMMA, v_SINALPHA, v_COSGAMMA,"
                        " v_POSE, v_POSITION)")
    assert after[-4:] == ["    v_R11, _c16, v_R12, v_R13, v_R21, _c24, v_R22, v_R23, v_R31, v_R32, v_R33, _c33, _c36,"
                          " v_U, _c38, _c41, v_V, _c43, _c46, v_W, _c48, v_LEGX, _c51, v_LEGY, _c56, v_LEGZ, _c64,"
                          " _c89, = _kr", "    v_DONE = True", "    v_POSITION[0] = _c64", "v_POSITION[1] = _c89"]
    assert native.layout_is_cpythons()


def test_a_run_of_exactly_the_minimum_makes_a_kernel_and_one_fewer_none():
    """MIN_OPERATIONS is 16 (kernels.py): a run of 15 binary operations and one SQRT (16)
    makes one kernel, written without spaces so that only the operators themselves can
    count; 15 makes none.  (The pass's gate counts `* + -` and `_m_sqrt(` in the body: a
    gate that missed the SQRT, or counted spaced operators only, skips the first.)"""
    assert kernels.MIN_OPERATIONS == 16
    lines = ["_c1 = ((v_A*v_B)+(v_A-v_B))", "_c2 = ((_c1*2.5)-(v_A*0.5))",
             "_c3 = ((_c2+_c1)*(_c2-v_B))", "_c4 = ((_c3*_c3)+(_c1*v_A))", "_c5 = (_m_sqrt(_c4)+_c2)",
             "_c6 = ((_c5*v_A)+v_B)"]
    assert sum(line.count(op) for line in lines for op in "*+-") == 15
    after, bound = _passed(lines)
    assert after[0].startswith("_kr = _k0(") and len(bound) == 2
    fewer = lines[:-1] + ["_c6 = (_c5*v_A)"]
    assert _passed(fewer)[0] == fewer


#: A block's run of exactly MIN_OPERATIONS operations, two of them SIN and COS, after a finite
#: test (its `-1e309` no operation), the body's other `+ - *` (the charges) after the block.
BLOCK_AT_THE_MINIMUM = """\
if v_GO:
    _c6 = (True if (v_A < 1e309 and v_A > -1e309) else False)
    v_S = (_m_sin(v_A) if _c6 else _sf_SIN(v_A))
    v_C = (_m_cos(v_A) if _c6 else _sf_COS(v_A))
    _c1 = ((v_S*v_C)+(v_S-v_C))
    _c2 = ((_c1*2.5)-(v_S*0.5))
    _c3 = ((_c2+_c1)*(_c2-v_C))
    _c4 = ((_c3*_c3)+(_c1*v_S))
    _c5 = ((_c4*v_S)+v_C)
_spent += 1
_spent += 1""".splitlines()


def test_a_block_of_exactly_the_minimum_with_sin_and_cos_makes_a_kernel():
    """The pass builds no span from a line whose block (its lines up to the first indented
    less) shows fewer than MIN_OPERATIONS operations (kernels.py `_operations_before`): 14
    binary operations, SIN and COS (16) make a kernel; a gate that missed SIN or COS, counted
    every `1e309` of the finite test out (a sign too many), ended the block a line early or
    skipped at the minimum itself makes none.  One operation fewer makes none."""
    assert sum(line.count(op) for line in BLOCK_AT_THE_MINIMUM[4:9] for op in "*+-") == 14
    after, bound = _passed(BLOCK_AT_THE_MINIMUM)
    assert after[1] == "    _kr = _k0(v_A)" and after.count("    if _kr is None:") == 1
    fewer = BLOCK_AT_THE_MINIMUM[:8] + ["    _c5 = (_c4*v_S)"] + BLOCK_AT_THE_MINIMUM[9:]
    assert _passed(fewer)[0] == fewer


def test_a_block_ends_before_the_first_line_indented_less():
    """`_block_ends`: the deeper lines and a blank line are in the block of line 0; a line
    of spaces, or whose first character after its spaces is a tab, ends no block (as blank);
    a line of the outermost indentation, or the last block, ends at the end."""
    body = ["    a = 1", "        b = 2", "", "    c = 3", "d = 4", "    e = 5"]
    assert [end for end, line in zip(kernels._block_ends(body), body) if line] == [4, 3, 4, 6, 6]
    body = ["        a", "  ", "    \tb", "      c", "    d"]
    assert [kernels._block_ends(body)[i] for i in (0, 3, 4)] == [3, 4, 5]
    assert kernels._block_ends([]) == []


def test_the_operations_before_each_line_count_each_assignment_once():
    """`_operations_before`: a `+ - *` each and a call of `_m_sqrt` in the lines holding ` = `
    before each line; a finite test's `> -1e309` is no operation, an `if` and a charge's
    `+=` count none (wrong answers: 1 at line 2 counting the test's sign, 3 at the `if`)."""
    body = ["x = ((a*b)+c)", "if x > -1e309 - 1:", "_c1 = (True if (y < 1e309 and y > -1e309) else False)",
            "_spent += 1", "z = _m_sqrt((x-y))", "w = (_m_sin(x) if _c1 else _sf_SIN(x))"]
    assert kernels._operations_before(body) == [0, 2, 2, 2, 2, 4, 5]


def test_ik_runs_give_pythons_floats_bit_for_bit():
    """Ordinary poses and ones with inf, NaN, -0.0, subnormal, tiny and huge values (squares
    that overflow): every local and the stored positions as Python's lines give them."""
    rows = _ik_arguments(random.Random(5))
    assert _mismatches(IK, IK_INPUTS + ("v_POSE",), rows) == []


def test_a_negative_sqrt_argument_raises_as_python_does():
    rows = [(a, b) for a in (3.0, 1.0, -2.0, 0.0, -0.0, 1e-310, 1e200, math.nan)
            for b in (1.0, 3.0, 0.5, -0.0, 2e-310, math.inf)]
    python = _function(SIGNED, ("v_A", "v_B"), {"_m_sqrt": math.sqrt})
    assert {python(*row) if isinstance(python(*row), str) else "values" for row in rows} == {"ValueError", "values"}
    assert _mismatches(SIGNED, ("v_A", "v_B"), rows) == []


def test_what_the_kernel_cannot_read_runs_in_python():
    """An int operand, a short list, a list element that is an int, a list that is a tuple:
    the lines in Python (their values, their IndexError and TypeError)."""
    values = [math.cos(0.1), math.cos(0.2), math.sin(0.2), math.sin(0.3), math.sin(0.1), math.cos(0.3)]
    rows = [(*values[:5], 1, [1.0, 2.0, 3.0]), (*values, [1.0, 2.0]), (*values, [1.0, 2, 3.0]),
            (*values, (1.0, 2.0, 3.0)), (*values, [1.0, 2.0, 3.0, 4.0])]
    after, bound = _passed(IK)
    kernel = _function(after, IK_INPUTS + ("v_POSE",), bound)
    python = _function(IK, IK_INPUTS + ("v_POSE",), {"_m_sqrt": math.sqrt})
    assert python(*rows[1]) == "IndexError"
    assert [_same(python(*row), kernel(*row)) for row in rows] == [True] * len(rows)


def test_the_first_call_compiles_and_binds_the_kernel(monkeypatch):
    """The pass writes no IR (a load stays compile-free); a run's first call writes it once."""
    written = []
    right = native.run_ir
    monkeypatch.setattr(native, "run_ir", lambda *a: written.append(1) or right(*a))
    after, bound = _passed(IK)
    assert bound["_k0"].__name__ == "first" and written == []
    kernel = _function(after, IK_INPUTS + ("v_POSE",), bound)
    kernel(*(0.5,) * 6, [1.0, 2.0, 3.0])
    assert len(written) == 1
    kernel(*(0.5,) * 6, [1.0, 2.0, 3.0])
    assert len(written) == 1
    assert type(bound["_k0"]).__name__ == "builtin_function_or_method"
    assert bound["_k0"](*(0.5,) * 5, 1, [1.0, 2.0, 3.0], [0.0] * 6) is None      # an int: the lines run


def _swap_first_fsub(ir: str) -> str:
    lines = ir.splitlines()
    for k, line in enumerate(lines):
        if " = fsub double " in line and "%" in line.split(", ")[1]:
            head, operands = line.split(" = fsub double ")
            a, b = operands.split(", ")
            lines[k] = f"{head} = fsub double {b}, {a}"
            return "\n".join(lines) + "\n"
    return ir                   # (a run without one: unchanged)


def _wrong_ir(monkeypatch, change) -> None:
    """Make every kernel from now on of the IR `change(ir)` (a hand-made wrong version)."""
    right = native.run_ir
    monkeypatch.setattr(native, "run_ir", lambda *a: change(right(*a)))


WRONG = {
    "operands swapped": _swap_first_fsub,
    "sqrt dropped": lambda ir: ir.replace("call double @llvm.sqrt.f64(double", "call double @llvm.fabs.f64(double"),
    "finite test dropped": lambda ir: ir.replace("fcmp olt double %abs", "fcmp une double %abs"),
}


@pytest.mark.parametrize("wrong", WRONG, ids=WRONG.keys())
def test_a_wrong_kernel_fails_a_row(wrong, monkeypatch):
    """Each hand-made wrong kernel gives a value (or a missing ValueError) Python does not."""
    _wrong_ir(monkeypatch, WRONG[wrong])
    ik = _mismatches(IK, IK_INPUTS + ("v_POSE",), _ik_arguments(random.Random(5)))
    signed = _mismatches(SIGNED, ("v_A", "v_B"), [(1.0, 3.0), (-2.0, 0.5), (3.0, 1.0)])
    assert ik or signed


#: SP_InverseKinematics' legs 1 and 2 as the compiler writes them on the wave: each leg's run,
#: its store, its finite test (a charge, `AllFinite := FALSE`) and its in-stroke test (a store
#: into another list, a test of it, charges); the rotation's values are the inputs.
LEGS = IK[12:29] + """\
if (not (_c64 < 1e309 and _c64 > -1e309)):
    _spent = 795938
    v_ALLFINITE = False
v_LEGINSTROKE[0] = (True if ((_c64 >= 0.0) and (_c64 <= 600.0)) else False)
if (not v_LEGINSTROKE[0]):
    _spent += 83720
    v_ALLINSTROKE = False
else:
    _spent += 82524""".splitlines() + IK[29:37] + """\
if (not (_c89 < 1e309 and _c89 > -1e309)):
    _spent += 1196
    v_ALLFINITE = False
v_LEGINSTROKE[1] = (True if ((_c89 >= 0.0) and (_c89 <= 600.0)) else False)
if (not v_LEGINSTROKE[1]):
    _spent += 1196
    v_ALLINSTROKE = False""".splitlines()
LEGS_INPUTS = ("v_R11", "v_R12", "v_R13", "v_R21", "v_R22", "v_R23", "v_R31", "v_R32", "v_R33", "v_POSE",
               "v_POSITION", "v_LEGINSTROKE")
LEGS_STATE = "_spent = 794742; v_ALLFINITE = True; v_ALLINSTROKE = True"

#: A store into a list the span reads again, at the stored index and at another.
STORED_AND_READ = """\
_c1 = ((v_A * v_A) + (v_B * 0.5))
_c2 = ((_c1 - v_B) * (_c1 + 3.0))
_c3 = ((_c2 * v_A) - (_c1 * v_B))
v_P[0] = _c3
_c4 = ((v_P[0] * 2.0) + (v_P[1] * _c1))
_c5 = ((_c4 - v_P[0]) * (_c2 + v_P[1]))
_c6 = (_m_sqrt(((_c5 * _c5) + (_c4 * _c4))) - v_Q[0])
v_P[1] = _c6
_c7 = ((v_P[1] * v_P[0]) + v_Q[0])""".splitlines()


def _stateful(lines: list[str], params: tuple[str, ...], namespace: dict, state: str = "", copy=True):
    """`lines` as a function of `params` (lists copied unless not `copy`) returning its locals
    and the lists."""
    body = "\n".join("        " + line for line in [state] + lines if line)
    source = (f"def run({', '.join(params)}):\n    try:\n{body}\n"
              "    except Exception as exc:\n        return type(exc).__name__\n"
              "    return {k: v for k, v in locals().items() if k not in ('exc', '_kr')}\n")
    exec(compile(source, "<kernels test>", "exec"), namespace)
    run = namespace["run"]
    return lambda *row: run(*[list(x) if isinstance(x, list) else x for x in row]) if copy else run(*row)


def _legs_rows(rng: random.Random):
    """The rotation of random angles, a pose (ordinary, then with special values), the lists."""
    for values, pose in _ik_rows(rng):
        ca, cb, sb, sg, sa, cg = values
        rotation = [ca * cb, ca * sb * sg - sa * cg, ca * sb * cg + sa * sg, sa * cb, sa * sb * sg + ca * cg,
                    sa * sb * cg - ca * sg, -sb, cb * sg, cb * cg]
        yield (*rotation, pose, [0.0] * 6, [False] * 6)
        yield (*rotation[:8], -1e200 if rng.random() < 0.5 else rotation[8], [p * 10.0 for p in pose], [0.0] * 6,
               [True] * 6)                     # out of stroke, or a square that overflows


def _legs_mismatches(lines, rows, change=lambda after: after) -> list:
    after, bound = _passed(lines)
    python = _stateful(lines, LEGS_INPUTS, {"_m_sqrt": math.sqrt}, LEGS_STATE)
    kernel = _stateful(change(after), LEGS_INPUTS, bound, LEGS_STATE)
    return [row for row in rows if not _same(python(*row), kernel(*row))]


def test_the_legs_are_one_kernel_their_tests_and_charges_after_it():
    """Both legs are one span: the kernel's path keeps the stores, in-stroke tests and charges
    in their order and drops the finite tests; the last leg's in-stroke test stays after."""
    after, _ = _passed(LEGS)
    assert after.count("if _kr is None:") == 1
    assert after[0] == ("_kr = _k0(v_R11, v_R13, v_R12, v_R21, v_R23, v_R22, v_R31, v_R33, v_R32, v_POSE,"
                        " v_POSITION, v_LEGINSTROKE)")
    path = after[after.index("else:") + 2:]
    assert path[:8] == ["    v_POSITION[0] = _c64", LEGS[20].join(["    ", ""]), "    if (not v_LEGINSTROKE[0]):",
                        "        _spent += 83720", "        v_ALLINSTROKE = False", "    else:", "        _spent += 82524",
                        "    v_POSITION[1] = _c89"]
    assert path[8:] == LEGS[-4:] and not any("1e309" in line for line in path)


def test_the_legs_give_pythons_values_charges_and_flags_bit_for_bit():
    """Ordinary poses, poses out of stroke and ones with inf, NaN, -0.0, subnormal and huge
    values: every local (the charge, AllFinite, AllInStroke) and both lists as Python's."""
    rows = list(_legs_rows(random.Random(7)))
    python = _stateful(LEGS, LEGS_INPUTS, {"_m_sqrt": math.sqrt}, LEGS_STATE)
    results = [python(*row) for row in rows]
    assert {r["v_ALLFINITE"] for r in results} == {True, False}            # both paths of the finite test
    assert {r["v_ALLINSTROKE"] for r in results} == {True, False}
    assert _legs_mismatches(LEGS, rows) == []


def test_a_list_the_kernel_stores_must_be_a_long_enough_list_of_its_own():
    """A short list to store into (IndexError on its line), a tuple, and the lists stored into
    being the one read (`v_POSE`): the lines in Python."""
    rotation = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    pose = [10.0, 20.0, 30.0]
    rows = [(*rotation, pose, [0.0], [False] * 6), (*rotation, pose, (0.0,) * 6, [False] * 6),
            (*rotation, pose, [0.0] * 6, [False])]
    assert _legs_mismatches(LEGS, rows) == []
    after, bound = _passed(LEGS)
    python = _stateful(LEGS, LEGS_INPUTS, {"_m_sqrt": math.sqrt}, LEGS_STATE, copy=False)
    kernel = _stateful(after, LEGS_INPUTS, bound, LEGS_STATE, copy=False)
    for shared in ([10.0, 20.0, 30.0, 0.0, 0.0, 0.0], [10.0, 20.0, 30.0, False, False, False]):
        want, got = python(*rotation, list(shared), *[list(shared)] * 2), kernel(*rotation, list(shared), *[list(shared)] * 2)
        assert _same(want, got)
        want, got = python(*rotation, *[list(shared)] * 2, [False] * 6), kernel(*rotation, *[list(shared)] * 2, [False] * 6)
        assert _same(want, got)
    one = list(shared)
    assert bound["_k0"](*rotation, one, one, [False] * 6) is None            # v_POSE and v_POSITION one list
    assert bound["_k0"](*rotation, [1.0] * 3, one, one) is None


def test_a_store_into_a_list_the_span_reads_keeps_its_order():
    rng = random.Random(11)
    rows = [(rng.uniform(-3, 3), rng.uniform(-3, 3), [rng.uniform(-5, 5), rng.uniform(-5, 5)], [rng.uniform(0, 9)])
            for _ in range(50)]
    rows += [(a, b, [1.0, c], [2.0]) for a in (0.5, math.inf, -0.0) for b in (1.0, math.nan) for c in (5e-324, -1e300)]
    after, bound = _passed(STORED_AND_READ)
    assert after.count("if _kr is None:") == 1 and after[-2:] == ["    v_P[0] = _c3", "    v_P[1] = _c6"]
    params = ("v_A", "v_B", "v_P", "v_Q")
    python = _stateful(STORED_AND_READ, params, {"_m_sqrt": math.sqrt})
    kernel = _stateful(after, params, bound)
    assert [row for row in rows if not _same(python(*row), kernel(*row))] == []
    python = _stateful(STORED_AND_READ, params, {"_m_sqrt": math.sqrt}, copy=False)
    kernel = _stateful(after, params, bound, copy=False)
    one, other = [1.0, 2.0], [1.0, 2.0]              # v_Q the list v_P: the store changes v_Q[0]
    assert _same(python(1.5, 0.5, one, one), kernel(1.5, 0.5, other, other))
    assert bound["_k0"](1.5, 0.5, one, one) is None


def _kernel_path(after: list[str]) -> int:
    return after.index("else:") + 2


WRONG_PASS = {
    "a store dropped": lambda after: after[:_kernel_path(after)] + after[_kernel_path(after) + 1:],
    "a store moved after its test": lambda after: (
        after[:_kernel_path(after) + 1] + after[_kernel_path(after) + 2:_kernel_path(after) + 7]
        + after[_kernel_path(after) + 1:_kernel_path(after) + 2] + after[_kernel_path(after) + 7:]),
    "a finite test dropped on the None path": lambda after: [
        line for k, line in enumerate(after) if not ("1e309" in line or "1e309" in after[k - 1] and "_spent" in line
                                                     or "1e309" in after[k - 2] and "ALLFINITE" in line)],
}


@pytest.mark.parametrize("wrong", WRONG_PASS, ids=WRONG_PASS.keys())
def test_a_wrong_span_fails_a_row(wrong):
    assert _legs_mismatches(LEGS, list(_legs_rows(random.Random(7))), WRONG_PASS[wrong])


def test_the_kernel_returns_only_the_names_read_after_it():
    """Without a line after them reading every name, IK's kernel returns the two names read
    after it (leg 1's position, stored on its path; leg 2's, stored after the span)."""
    after, bound = _passed(IK, read_after=False)
    path = after[after.index("else:") + 1:]
    assert path == ["    _c64, _c89, = _kr", "    v_DONE = True", "    v_POSITION[0] = _c64", "v_POSITION[1] = _c89"]
    python = _function(IK, IK_INPUTS + ("v_POSE",), {"_m_sqrt": math.sqrt})
    kernel = _function(after, IK_INPUTS + ("v_POSE",), bound)
    read = ("_c64", "_c89", "v_DONE", "v_POSITION")
    for k, row in enumerate(_ik_arguments(random.Random(3))):
        want, got = python(*row), kernel(*row)
        assert _same({name: want[name] for name in read}, {name: got[name] for name in read})
        assert k >= 100 or "v_R11" not in got                  # (ordinary rows: the kernel answered)


MIXED = """
FUNCTION Mix : LREAL
VAR_INPUT A, B : LREAL; N : DINT; END_VAR
VAR P, Q, R, Y : LREAL; M : {m}; END_VAR
M := N + 1;
P := (A * B + A - B) * (A + 2.5) - B * B;
Q := (P * A - B * 0.5) * (P + B) + A * A;
R := (Q * P + A) * (Q - B) - P * 3.0 + M * 1.5;
Y := R * A + Q * B - P * A;
Mix := Y * R + Q;
END_FUNCTION
"""


@pytest.mark.parametrize("m, kernels_made", [("LREAL", 1), ("DINT", 0)])
def test_a_run_reading_a_declared_int_makes_no_kernel(m, kernels_made):
    """26 operations in one run; with M a DINT (a Python int: the kernel would answer None at
    every call) the lines before it (13) and after it (6) are too short for a kernel."""
    from st_runtime import api
    from st_runtime.compiler import compile_program

    compiled = compile_program(api.load_text(MIXED.format(m=m)).program)
    assert compiled.python_sources["MIX"].count("_kr = ") == kernels_made


BETWEEN = {          # a statement between leg 1 and leg 2 -> whether the span goes on across it
    "v_DONE = (True if ((_c64 >= 0.0) and (_c64 <= -1.5)) else False)": True,
    "_spent += 1196": True,
    "v_DONE = (not -1.5)": True,
    "v_POSITION[0] = _c64": True,
    "if (not v_POSITION[0]):": False,                      # (a test of an element not stored)
    "v_DONE = ((_c64 - 1.0) > 0.0)": False,                # arithmetic (an int's could raise)
    "v_DONE = _c64(1.0)": False,                           # a call
    "if _ctx.budget < _spent: _overrun(1)": False,         # a budget check
    "v_DONE = (v_OTHER > 0.0)": False,                     # a name the run does not compute
    "v_U = True": False,                                   # a name the run sets again after
    "_c36 = True": False,                                  # a name the run reads after
    "_spent += 1.5": False,
    "v_DONE = (v_POSE[0] > 0.0)": False,
}


@pytest.mark.parametrize("between", BETWEEN)
def test_a_span_goes_on_across_a_statement_only_where_it_may_run_after(between):
    lines = IK[12:28] + [between] + IK[29:36]
    after, _ = _passed(lines)
    assert after.count("if _kr is None:") == (1 if BETWEEN[between] else 2)


#: SP_InverseKinematics' prologue as the compiler writes it on the wave (the angles are the
#: instance's variables; COS and SIN behind the compiler's finite test, the library's SIN and
#: COS where it fails), then the rotation: one span (h-native17-s23).
PROLOGUE = """\
self.v_ALPHA = (v_POSE[3] * 0.017453292519943295)
self.v_BETA = (v_POSE[4] * 0.017453292519943295)
self.v_GAMMA = (v_POSE[5] * 0.017453292519943295)
_c6 = (True if (self.v_ALPHA < 1e309 and self.v_ALPHA > -1e309) else False)
v_COSALPHA = (_m_cos(self.v_ALPHA) if _c6 else _sf_COS(self.v_ALPHA))
v_SINALPHA = (_m_sin(self.v_ALPHA) if _c6 else _sf_SIN(self.v_ALPHA))
_c9 = (True if (self.v_BETA < 1e309 and self.v_BETA > -1e309) else False)
v_COSBETA = (_m_cos(self.v_BETA) if _c9 else _sf_COS(self.v_BETA))
v_SINBETA = (_m_sin(self.v_BETA) if _c9 else _sf_SIN(self.v_BETA))
_c12 = (True if (self.v_GAMMA < 1e309 and self.v_GAMMA > -1e309) else False)
v_COSGAMMA = (_m_cos(self.v_GAMMA) if _c12 else _sf_COS(self.v_GAMMA))
v_SINGAMMA = (_m_sin(self.v_GAMMA) if _c12 else _sf_SIN(self.v_GAMMA))""".splitlines() + IK[:11]
#: Angles in degrees beyond the ordinary: special values, huge ones (SIN and COS of 1.7e298
#: rad: the C library's argument reduction), the largest finite double.
ANGLES = SPECIAL + [1e300, -1e300, 1.7976931348623157e308, 123456789.0, 5e-324]


def _trig_namespace() -> dict:
    from st_runtime.stdlib.functions import FUNCTIONS

    return {"_m_sqrt": math.sqrt, "_m_sin": math.sin, "_m_cos": math.cos,
            "_sf_SIN": FUNCTIONS["SIN"], "_sf_COS": FUNCTIONS["COS"]}


class _Instance:
    """The instance the generated body's `self` is: the angles its variables."""

    def __init__(self):
        self.v_ALPHA = self.v_BETA = self.v_GAMMA = 0.25


def _with_instance(lines: list[str], namespace: dict):
    """`lines` as a function of a pose: its locals and the instance's variables afterwards."""
    run = _function(lines, ("self", "v_POSE"), namespace)

    def call(pose):
        instance = _Instance()
        found = run(instance, list(pose))
        return found if isinstance(found, str) else {**found, "self": None, **vars(instance)}
    return call


def _prologue_rows(rng: random.Random):
    for k in range(300):
        pose = [rng.uniform(-100.0, 100.0) for _ in range(3)] + [rng.uniform(-30.0, 30.0) for _ in range(3)]
        if k >= 100:
            for _ in range(1 + k % 3):
                pose[3 + rng.randrange(3)] = rng.choice(ANGLES)
        yield pose


def _prologue_mismatches(lines=PROLOGUE, rows=None) -> list:
    after, bound = _passed(lines)
    python = _with_instance(lines, _trig_namespace())
    kernel = _with_instance(after, {**_trig_namespace(), **bound})
    rows = list(_prologue_rows(random.Random(11))) if rows is None else rows
    return [row for row in rows if not _same(python(row), kernel(row))]


def test_the_prologue_and_the_rotation_are_one_kernel():
    """The angles (the instance's variables, always returned), their finite tests (True where
    the kernel answers: set so after it), COS and SIN and the rotation: one call."""
    after, bound = _passed(PROLOGUE)
    assert after[0] == "_kr = _k0(v_POSE)" and after.count("if _kr is None:") == 1
    path = after[after.index("else:") + 1:]
    assert path[0].startswith("    self.v_ALPHA, self.v_BETA, self.v_GAMMA, v_COSALPHA, v_SINALPHA, v_COSBETA,")
    assert path[1:] == ["    _c6 = True", "    _c9 = True", "    _c12 = True"]
    ir = native.run_ir(*_kernel_arguments(PROLOGUE))
    assert ir.count("call double @cos(double") == 3 and ir.count("call double @sin(double") == 3


def _kernel_arguments(lines):
    """run_ir's arguments for the span the pass makes of `lines` (written by its first call)."""
    captured = []
    right = native.run_ir
    native.run_ir = lambda *a: captured.append(a) or right(*a)
    try:
        after, bound = _passed(lines)
        _with_instance(after, {**_trig_namespace(), **bound})([0.0] * 6)
    finally:
        native.run_ir = right
    return captured[0]


def test_the_prologue_gives_pythons_values_bit_for_bit():
    """Ordinary angles and inf, -inf, NaN, -0.0, subnormal, huge (1e300 degrees, the largest
    double) ones: every local and the instance's angles as Python's lines give them; a
    non-finite angle takes the library's SIN and COS in Python (the kernel answers None)."""
    assert _prologue_mismatches() == []
    after, bound = _passed(PROLOGUE)
    native.bind_symbols(native.libm_symbols())
    kernel = native.builtin(type("K", (), {})(), native.compiled(native.run_ir(*_kernel_arguments(PROLOGUE))))
    assert kernel([0.0, 0.0, 0.0, math.inf, 1.0, 2.0]) is None
    assert kernel([0.0, 0.0, 0.0, 1e300, 1.0, 2.0])[3] == math.cos(1e300 * 0.017453292519943295)


def test_sin_cos_and_atan_are_the_math_modules():
    """The kernel's `sin`, `cos` and `atan` are the addresses the process resolves for the
    names (the functions math.sin, math.cos and math.atan call: test_optimiser_loops.py's
    GOT check)."""
    import ctypes

    process = ctypes.CDLL(None)
    assert native.libm_symbols() == {name: ctypes.cast(getattr(process, name), ctypes.c_void_p).value
                                     for name in ("sin", "cos", "atan")}


def test_a_guard_of_another_value_or_a_test_read_as_a_float_ends_the_span():
    """SIN behind a test of another value, a test read in arithmetic, SIN and COS guarded
    crosswise: the span of the angles and the test ends before them (three operations: no
    kernel), where with SIN of the tested angle it goes on into the rotation."""
    base = PROLOGUE[:4]
    assert _passed(base + ["v_X = (_m_sin(self.v_ALPHA) if _c6 else _sf_SIN(self.v_ALPHA))"] + IK[:11])[0][0] \
        == "_kr = _k0(v_POSE, v_COSALPHA, v_COSBETA, v_SINBETA, v_SINGAMMA, v_SINALPHA, v_COSGAMMA)"
    for line in ("v_X = (_m_sin(self.v_BETA) if _c6 else _sf_SIN(self.v_BETA))",
                 "v_X = (_c6 * 2.0)",
                 "v_X = (_m_sin(self.v_ALPHA) if _c6 else _sf_COS(self.v_ALPHA))"):
        after, _ = _passed(base + [line] + IK[:11])
        assert after[:4] == base, line          # (a later span may start at the line itself)


WRONG_TRIG = {
    "sin and cos swapped": lambda ir: ir.replace("@sin(double %", "@tmp(double %").replace(
        "@cos(double %", "@sin(double %").replace("@tmp(double %", "@cos(double %"),
    "finite test dropped": lambda ir: ir.replace("fcmp olt double %abs", "fcmp une double %abs"),
}


@pytest.mark.parametrize("wrong", WRONG_TRIG, ids=WRONG_TRIG.keys())
def test_a_wrong_trigonometric_kernel_fails_a_row(wrong, monkeypatch):
    _wrong_ir(monkeypatch, WRONG_TRIG[wrong])
    assert _prologue_mismatches()


#: IK's rotation, the two flags, the budget check between the rotation and the legs (its
#: branch loads the variables the legs set: aliases.py `drop_unread`) and legs 1 and 2.
CHECK = ("if _ctx.budget < _spent: v_U = self.v_U; v_V = self.v_V; v_W = self.v_W; v_LEGX = self.v_LEGX;"
         " v_LEGY = self.v_LEGY; v_LEGZ = self.v_LEGZ; _overrun(('SP_InverseKinematics', 'SP_InverseKinematics.st', 104, 1))")
CHECKED = IK[:11] + ["v_ALLFINITE = True", "v_ALLINSTROKE = True", CHECK] + LEGS
CHECKED_INPUTS = IK_INPUTS + ("v_POSE", "v_POSITION", "v_LEGINSTROKE", "self", "_ctx")


class _Overrun(Exception):
    pass


def _overrun(where):
    raise _Overrun(where)


def _faulting(lines: list[str], namespace: dict):
    """`lines` as a function returning its locals, after a fault too (but reuse.py's shared
    values `_cN`: locals no store back writes, gone when the overrun ends the body), and the
    instance's variables."""
    body = "\n".join("        " + line for line in [LEGS_STATE] + lines)
    source = (f"def run({', '.join(CHECKED_INPUTS)}):\n    try:\n{body}\n"
              "    except _Overrun as exc:\n        return {'fault': exc.args, **{k: v for k, v in locals().items()"
              " if k not in ('exc', '_kr', 'self', '_ctx') and not _shared(k)}}\n"
              "    return {k: v for k, v in locals().items() if k not in ('_kr', 'self', '_ctx')}\n")

    def call(values, pose, budget):
        instance = type("Instance", (), {})()
        for name in ("v_U", "v_V", "v_W", "v_LEGX", "v_LEGY", "v_LEGZ"):
            setattr(instance, name, -7.5)
        context = type("Context", (), {"budget": budget})()
        exec(compile(source, "<kernels test>", "exec"),
             scope := {**namespace, "_Overrun": _Overrun, "_overrun": _overrun, "_shared": re.compile(r"_c\d+\Z").match})
        found = scope["run"](*values, list(pose), [0.0] * 6, [False] * 6, instance, context)
        return {**found, **{f"self.{k}": v for k, v in vars(instance).items()}}
    return call


def _checked_rows():
    for values, pose in _ik_rows(random.Random(13)):
        for budget in (10**9, 794741, 794742):           # passes, fails, passes at the charge
            yield values, pose, budget


def _checked_mismatches() -> list:
    after, bound = _passed(CHECKED)
    python = _faulting(CHECKED, {"_m_sqrt": math.sqrt})
    kernel = _faulting(after, {"_m_sqrt": math.sqrt, **bound})
    return [row for row in _checked_rows() if not _same(python(*row), kernel(*row))]


def test_the_rotation_and_the_legs_are_one_kernel_across_the_budget_check():
    """The check runs after the kernel where it answers, after the flags, before leg 1's
    store: in its place among the statements the kernel's path keeps."""
    after, _ = _passed(CHECKED)
    assert after.count("if _kr is None:") == 1
    path = after[after.index("else:") + 2:]
    assert path[:4] == ["    v_ALLFINITE = True", "    v_ALLINSTROKE = True", "    " + CHECK, "    v_POSITION[0] = _c64"]


def test_a_budget_check_that_fails_finds_the_state_it_finds_in_python():
    """Budgets that pass and fail at the check: the fault's place, every local the body set
    before it (the rotation, the flags), the variables its branch loads, the lists and the
    instance as Python's, on ordinary and special values (the None path too)."""
    assert _checked_mismatches() == []
    python = _faulting(CHECKED, {"_m_sqrt": math.sqrt})
    assert "fault" in python([0.5] * 6, [1.0, 2.0, 3.0], 794741) and "v_POSITION" in python([0.5] * 6, [1.0, 2.0, 3.0], 10**9)


def test_a_variable_the_check_does_not_load_ends_the_span_before_it():
    """A run line after the check setting a variable its branch does not load (here LegZ)
    would show the kernel's value where the check fails: the span ends before that line."""
    lines = [line.replace(" v_LEGZ = self.v_LEGZ;", "") for line in CHECKED]
    after, _ = _passed(lines)
    second = after.index("if _kr is None:", after.index("if _kr is None:") + 1)
    assert after.count("if _kr is None:") == 2 and after[second + 1] == "    v_LEGZ = (v_W + _c56)"


def test_a_wrong_check_rule_fails_a_row(monkeypatch):
    """Every target allowed after the check (the rule left out): the fault shows the legs'
    values the check's branch does not load."""
    global CHECKED
    right = CHECKED
    monkeypatch.setattr(kernels, "_SHARED", re.compile(r".*"))
    CHECKED = [line.replace(" v_LEGZ = self.v_LEGZ;", "") for line in right]
    try:
        assert _checked_mismatches()
    finally:
        CHECKED = right


#: CHECKED with a store of an expression before the check and one after it (session 24).
STORED_AROUND_CHECK = (IK[:11] + ["v_POSITION[4] = (v_R12 * 1.5)", "v_ALLFINITE = True", "v_ALLINSTROKE = True", CHECK,
                                  "v_POSITION[5] = (v_R11 * 2.5)"] + LEGS)


def _stored_around_check_mismatches() -> list:
    """As `_checked_mismatches`, the pass's values of stores `_kvN` left out (locals only its
    stores read)."""
    after, bound = _passed(STORED_AROUND_CHECK)
    python = _faulting(STORED_AROUND_CHECK, {"_m_sqrt": math.sqrt})
    kernel = _faulting(after, {"_m_sqrt": math.sqrt, **bound})

    def state(found):
        return {k: v for k, v in found.items() if not re.match(r"_kv\d+\Z", k)}
    return [row for row in _checked_rows() if not _same(state(python(*row)), state(kernel(*row)))]


def test_the_kernel_stores_only_before_the_budget_check():
    """The store before the check is the kernel's own (no line after it); the one after it
    stays a kept statement after the check, so a check that fails finds the element as
    Python leaves it (budgets that pass and fail, ordinary and special values)."""
    after, _ = _passed(STORED_AROUND_CHECK)
    path = after[after.index("else:") + 2:]
    assert not any(line.startswith("    v_POSITION[4] = ") for line in path)
    assert path[2:4] == ["    " + CHECK, "    v_POSITION[5] = _kv1"]
    assert _stored_around_check_mismatches() == []


def test_a_wrong_store_rule_fails_a_row(monkeypatch):
    """Every store of a run's value made by the kernel (the check left out of the rule): a
    failing check finds element 5 stored, where Python had not stored it yet."""
    def every_store(span):
        moved = [(own[1], int(own[2]), span.elements[own[1], int(own[2])]) for lines in span.kept
                 if (own := kernels._OWN_STORE.match(lines[0])) is not None]
        span.kept = [lines for lines in span.kept if kernels._OWN_STORE.match(lines[0]) is None]
        return moved
    monkeypatch.setattr(kernels._Span, "stores_in_kernel", every_store)
    assert _stored_around_check_mismatches()


#: TRJ_OceanWave's pose as the compiler writes it on the wave: stores of expressions into the
#: pose's elements, ATAN (the library's, math.atan) inside `try` with the fault's handler.
POSE = """\
v_POSE[0] = ((v_FADE * (self.v_HORIZONTAL * v_COSHEADING)) + v_CENTRE[0])
v_POSE[1] = ((v_FADE * (self.v_HORIZONTAL * v_SINHEADING)) + v_CENTRE[1])
v_POSE[2] = ((v_FADE * v_COSINESUM) + v_CENTRE[2])
v_POSE[3] = v_CENTRE[3]
try:
    v_POSE[4] = ((v_FADE * (-(_sf_ATAN((self.v_SLOPEALONG * v_COSHEADING)) * 57.29577951308232))) + v_CENTRE[4])
except _FAULTS as _e:
    _ctx.fault(_e, ('TRJ_OceanWave', 'TRJ_OceanWave.st', 317, 5))
try:
    v_POSE[5] = ((v_FADE * (_sf_ATAN((self.v_SLOPEALONG * v_SINHEADING)) * 57.29577951308232)) + v_CENTRE[5])
except _FAULTS as _e:
    _ctx.fault(_e, ('TRJ_OceanWave', 'TRJ_OceanWave.st', 318, 5))""".splitlines()
POSE_INPUTS = ("self", "_ctx", "v_FADE", "v_COSHEADING", "v_SINHEADING", "v_COSINESUM", "v_CENTRE", "v_POSE")


def _pose_function(lines: list[str], namespace: dict):
    """`lines` as a function of a row: its locals (the pose; not the kernel's values `_kvN`,
    which only its stores read), the faults it reported."""
    from st_runtime.compiler import _FAULTS
    from st_runtime.stdlib.functions import FUNCTIONS

    run = _function(lines, POSE_INPUTS, {**namespace, "_sf_ATAN": FUNCTIONS["ATAN"], "_FAULTS": _FAULTS})

    def call(horizontal, slope, *row):
        instance, context = type("Instance", (), {})(), type("Context", (), {})()
        instance.v_HORIZONTAL, instance.v_SLOPEALONG, context.faults = horizontal, slope, []
        context.fault = lambda e, where: context.faults.append((type(e).__name__, where))
        found = run(instance, context, *[list(x) if isinstance(x, list) else x for x in row])
        if isinstance(found, str):
            return found
        own = [name for name in found if re.match(r"_kv\d+\Z", name)]        # the pass's values of stores
        return {**{k: v for k, v in found.items() if k not in own}, "self": None, "_ctx": None, "faults": context.faults}
    return call


def _pose_rows(rng: random.Random):
    for k in range(300):
        row = [rng.uniform(-50.0, 50.0), rng.uniform(-0.5, 0.5), rng.uniform(0.0, 1.0), math.cos(k), math.sin(k),
               rng.uniform(-30.0, 30.0), [rng.uniform(-100.0, 100.0) for _ in range(6)], [0.0] * 6]
        if k >= 100:
            for _ in range(1 + k % 3):
                j = rng.randrange(7)
                if j == 6:
                    row[6][rng.randrange(6)] = rng.choice(SPECIAL)
                else:
                    row[j] = rng.choice(SPECIAL + [1e300, -1e300])
        yield row
    yield [1.0, 0.1, 1.0, 0.5, 0.5, 1.0, [1.0, 2.0, 3.0, 4.0, 5, 6.0], [0.0] * 6]        # an int element
    yield [1.0, 0.1, 1.0, 0.5, 0.5, 1.0, [1.0] * 6, [0.0] * 5]                          # a short pose
    yield [1.0, 0.1, 1.0, 0.5, 0.5, 1.0, (1.0,) * 6, [0.0] * 6]                         # a tuple


def _pose_mismatches(lines=POSE) -> list:
    after, bound = _passed(lines)
    python = _pose_function(lines, {"_m_sqrt": math.sqrt})
    kernel = _pose_function(after, {"_m_sqrt": math.sqrt, **bound})
    return [row for row in _pose_rows(random.Random(17)) if not _same(python(*row), kernel(*row))]


def test_the_pose_is_one_kernel_that_stores_it():
    """The four stores and the two `try` lines with ATAN: one kernel that stores the six
    values into the pose itself where it answers (session 24; no value returned, nothing
    after it); no handler on the kernel's path."""
    after, _ = _passed(POSE)
    assert after[0] == ("_kr = _k0(v_FADE, self.v_HORIZONTAL, v_COSHEADING, v_CENTRE, v_SINHEADING, v_COSINESUM,"
                        " self.v_SLOPEALONG, v_POSE)")
    assert after[1] == "if _kr is None:" and "else:" not in after and after[2:] == ["    " + line for line in POSE]
    written = []
    right = native.run_ir
    native.run_ir = lambda *a: written.append(right(*a)) or written[-1]
    try:
        _pose_mismatches()
    finally:
        native.run_ir = right
    assert written[0].count("store ptr %st") == 6 and written[0].count("call ptr @PyTuple_New(i64 0)") == 1


def test_the_pose_kernel_frees_the_floats_it_replaces():
    """Each item the kernel replaces loses the pose's reference (no leak), each new float is
    held by the pose alone; a pose holding an int where it stores: the kernel answers None."""
    from st_runtime.compiler import _FAULTS

    after, bound = _passed(POSE)
    run = _function(after, POSE_INPUTS, {"_sf_ATAN": math.atan, "_FAULTS": _FAULTS, **bound})
    instance = type("Instance", (), {"v_HORIZONTAL": 20.0, "v_SLOPEALONG": 0.1})()
    old = [float(k) + 0.5 for k in range(6)]
    pose, held = list(old), [sys.getrefcount(x) for x in old]
    arguments = [instance, None, 0.5, math.cos(1.0), math.sin(1.0), 3.0, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]]
    assert not isinstance(run(*arguments, pose), str)
    assert type(bound["_k0"]).__name__ == "builtin_function_or_method"
    assert [sys.getrefcount(x) for x in old] == [n - 1 for n in held] and pose != old
    assert [sys.getrefcount(pose[k]) for k in range(6)] == [2] * 6     # (the pose's and the call's own)
    kernel_arguments = [0.5, 20.0, math.cos(1.0), arguments[6], math.sin(1.0), 3.0, 0.1]
    assert bound["_k0"](*kernel_arguments, [0.0, 0.0, 0.0, 4, 0.0, 0.0]) is None
    assert bound["_k0"](*kernel_arguments, [0.0] * 6) == ()


def test_the_pose_gives_pythons_values_and_faults_bit_for_bit():
    """Ordinary rows and ones with inf, NaN, -0.0, subnormal and huge values (ATAN of an
    infinite slope is pi/2 in Python: the kernel answers None there), an int element, a short
    pose (IndexError), a tuple: every local, the pose and the faults reported as Python's."""
    assert _pose_mismatches() == []


def test_a_store_into_an_instances_array_is_no_run_line():
    """`self.v_P[k] = ...`: the list may be the one a local holds (`v_POSE = self.v_POSE`), which
    the kernel would read before the store: no run line, nothing changed."""
    lines = [line.replace("v_POSE[", "self.v_POSE[", 1) if line.startswith("v_POSE[") else line for line in POSE]
    assert lines[0].startswith("self.v_POSE[0] = ") and _passed(lines)[0] == lines


def test_a_try_with_else_or_finally_and_a_store_of_a_name_are_not_run_lines():
    """`try` with an `else:` or `finally:` (it runs more than the line) ends the span; a store
    of a name stays a deferred store of the run's value (no value more returned).  (The
    pose's 19 operations make one kernel; the lines before such a `try` and after it are too
    few for one.)"""
    for extra in (["else:", "    v_X = 1.0"], ["finally:", "    v_X = 1.0"]):
        lines = POSE[:7] + extra + POSE[7:]
        assert _passed(lines)[0] == lines
    after, _ = _passed(IK)
    assert not any("_kv" in line for line in after)


WRONG_POSE = {
    "atan as sin": lambda ir: ir.replace("@atan(double %", "@sin(double %").replace("declare double @atan(double)\n", ""),
    "a store dropped": lambda ir: ir.replace("  store ptr %st3, ptr %st3.at, align 8\n", "").replace(
        "@Py_DecRef(ptr %st3.old)", "@Py_DecRef(ptr %st3)"),       # (the new float freed, the old kept)
}


@pytest.mark.parametrize("wrong", WRONG_POSE, ids=WRONG_POSE.keys())
def test_a_wrong_pose_kernel_fails_a_row(wrong, monkeypatch):
    _wrong_ir(monkeypatch, WRONG_POSE[wrong])
    assert _pose_mismatches()


#: SP_Jacobian's angles as the compiler writes them (session 24): each angle a pose element kept
#: in a shared value, COS and SIN each behind its own finite test of the value kept in the
#: compiler's temporary `_t1` (no local holds the test), then the rotation.
TEMP_GUARDED = """\
_c0 = v_POSE[3]
v_COSALPHA = (_m_cos(_t1) if (_t1 := _c0) < 1e309 and _t1 > -1e309 else _sf_COS(_t1))
v_SINALPHA = (_m_sin(_t1) if (_t1 := _c0) < 1e309 and _t1 > -1e309 else _sf_SIN(_t1))
_c3 = v_POSE[4]
v_COSBETA = (_m_cos(_t1) if (_t1 := _c3) < 1e309 and _t1 > -1e309 else _sf_COS(_t1))
v_SINBETA = (_m_sin(_t1) if (_t1 := _c3) < 1e309 and _t1 > -1e309 else _sf_SIN(_t1))
_c6 = v_POSE[5]
v_COSGAMMA = (_m_cos(_t1) if (_t1 := _c6) < 1e309 and _t1 > -1e309 else _sf_COS(_t1))
v_SINGAMMA = (_m_sin(_t1) if (_t1 := _c6) < 1e309 and _t1 > -1e309 else _sf_SIN(_t1))""".splitlines() + IK[:11]


def _temp_guarded_mismatches(lines=TEMP_GUARDED) -> list:
    """The rows (poses whose angles are radians, special values among them) where the pass's
    lines and Python's give a local differently; `_t1` left out: the compiler's temporary,
    read only in the statement that sets it (exprs.py `temp`), which the kernel need not set."""
    after, bound = _passed(lines)

    def without_temp(call):
        return lambda row: (lambda found: found if isinstance(found, str)
                            else {k: v for k, v in found.items() if k != "_t1"})(call(row))
    python = without_temp(_with_instance(lines, _trig_namespace()))
    kernel = without_temp(_with_instance(after, {**_trig_namespace(), **bound}))
    rows = [[*row[:3], *(math.radians(a) if math.isfinite(a) and abs(a) < 1e300 else a for a in row[3:])]
            for row in _prologue_rows(random.Random(13))]
    return [row for row in rows if not _same(python(row), kernel(row))]


def test_sin_and_cos_tested_in_a_temporary_are_one_kernel_with_the_rotation():
    """SP_Jacobian's angles: the pose's elements, the six COS and SIN (each checked finite in
    the kernel, the C library's `cos` and `sin`) and the rotation are one call of the pose."""
    after, bound = _passed(TEMP_GUARDED)
    assert after[0] == "_kr = _k0(v_POSE)" and after.count("if _kr is None:") == 1
    ir = native.run_ir(*_kernel_arguments(TEMP_GUARDED))
    assert ir.count("call double @cos(double") == 3 and ir.count("call double @sin(double") == 3


def test_sin_and_cos_tested_in_a_temporary_give_pythons_values_bit_for_bit():
    """Ordinary angles and inf, -inf, NaN, -0.0, subnormal and huge ones: every local as
    Python's lines give it (a non-finite angle: the kernel answers None, the library's SIN
    and COS run in Python)."""
    assert _temp_guarded_mismatches() == []


def test_sin_tested_in_a_temporary_after_a_store_in_the_span():
    """A store of an expression before the angles (the span then looks up the elements a line
    reads among those it stored): the same one kernel, and Python's values."""
    lines = ["v_OUT[0] = (v_POSE[0] * 2.0)"] + TEMP_GUARDED
    after, _ = _passed(lines)
    assert after[0] == "_kr = _k0(v_POSE, v_OUT)" and after.count("if _kr is None:") == 1


def test_sin_behind_cos_s_fallback_in_a_temporary_ends_the_span():
    """`_m_sin` with the library's COS where the test fails is not SIN: the span stops there."""
    line = "v_X = (_m_sin(_t1) if (_t1 := _c0) < 1e309 and _t1 > -1e309 else _sf_COS(_t1))"
    after, _ = _passed(TEMP_GUARDED[:1] + [line] + IK[:11])
    assert after[1] == line


def test_a_wrong_kernel_of_sin_and_cos_tested_in_a_temporary_fails_a_row(monkeypatch):
    """`sin` and `cos` swapped fails a row.  (The angle's own finite test dropped would not:
    SIN or COS of an infinity or a NaN is a NaN, which the kernel's check of every value finds.)"""
    _wrong_ir(monkeypatch, WRONG_TRIG["sin and cos swapped"])
    assert _temp_guarded_mismatches()

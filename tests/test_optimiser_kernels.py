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
import struct

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


def _passed(lines):
    after, bound = list(lines), {"_m_sqrt": math.sqrt}
    kernels.replace(after, 0, _register(bound), bound.__setitem__)
    return after, bound


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


def test_the_pass_makes_kernels_of_the_float_runs_only():
    after, bound = _passed(IK)
    assert after.count("if _kr is None:") == 3              # the rotation, leg 1, leg 2 (a store between)
    assert "v_DONE = True" in after and "v_POSITION[0] = _c64" in after and "v_POSITION[1] = _c89" in after
    calls = [line for line in after if line.startswith("_kr = ")]
    assert calls[0] == "_kr = _k0(v_COSALPHA, v_COSBETA, v_SINBETA, v_SINGAMMA, v_SINALPHA, v_COSGAMMA)"
    assert calls[1] == "_kr = _k1(v_R11, v_R13, v_R12, v_R21, v_R23, v_R22, v_R31, v_R33, v_R32, v_POSE)"
    assert calls[2] == "_kr = _k2(v_R11, v_R12, _c36, v_R21, v_R22, _c41, v_R31, v_R32, _c46, _c48, _c51, _c56)"
    assert after[-3:] == ["else:", "    v_U, v_V, v_W, v_LEGX, v_LEGY, v_LEGZ, _c89, = _kr", "v_POSITION[1] = _c89"]
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
    assert len(written) == 3
    kernel(*(0.5,) * 6, [1.0, 2.0, 3.0])
    assert len(written) == 3
    assert type(bound["_k0"]).__name__ == "builtin_function_or_method"
    assert bound["_k0"](*(0.5,) * 5, 1) is None                    # an int: the lines run


def _swap_first_fsub(ir: str) -> str:
    lines = ir.splitlines()
    for k, line in enumerate(lines):
        if " = fsub double " in line and "%" in line.split(", ")[1]:
            head, operands = line.split(" = fsub double ")
            a, b = operands.split(", ")
            lines[k] = f"{head} = fsub double {b}, {a}"
            return "\n".join(lines) + "\n"
    return ir                   # (a run without one: unchanged)


WRONG = {
    "operands swapped": _swap_first_fsub,
    "sqrt dropped": lambda ir: ir.replace("call double @llvm.sqrt.f64(double", "call double @llvm.fabs.f64(double"),
    "finite test dropped": lambda ir: ir.replace("fcmp olt double %abs", "fcmp une double %abs"),
}


@pytest.mark.parametrize("wrong", WRONG, ids=WRONG.keys())
def test_a_wrong_kernel_fails_a_row(wrong, monkeypatch):
    """Each hand-made wrong kernel gives a value (or a missing ValueError) Python does not."""
    right = native.run_ir
    monkeypatch.setattr(native, "run_ir", lambda *a: WRONG[wrong](right(*a)))
    ik = _mismatches(IK, IK_INPUTS + ("v_POSE",), _ik_arguments(random.Random(5)))
    signed = _mismatches(SIGNED, ("v_A", "v_B"), [(1.0, 3.0), (-2.0, 0.5), (3.0, 1.0)])
    assert ik or signed

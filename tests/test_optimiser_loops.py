"""The `loops` pass (st_runtime/compiler/optimise/loops.py): TRJ_OceanWave's component loop
computed by one native call gives every value Python's own loop gives, bit for bit, and where
it cannot (a range not from 1 by 1, an empty range, an int, a short list, a tuple, a value
not finite) the loop runs in Python as written, with the same result or exception.

The references: Python's float arithmetic and math.sin/math.cos (the loop executed as the
compiler writes it), and the wave's sums written out by hand from the ST source
(generated/iec/TRJ_OceanWave.st: Psi := k*x~ - w*t + phi; SineSum += A*SIN(Psi); CosineSum
+= A*COS(Psi); SlopeSum += A*k*SIN(Psi))."""

from __future__ import annotations

import ctypes
import math
import random
import re
import shutil
import struct
import subprocess
import sys

import pytest

pytest.importorskip("llvmlite")

from st_runtime.compiler.optimise import loops  # noqa: E402

#: TRJ_OceanWave's component loop in its fast copy, as the compiler writes it on the wave.
WAVE = """\
for v_COMPONENT in _t15:
    _t19 = v_COMPONENT - 1
    v_PSI = ((((_t21 := v_WAVENUMBER[_t19]) * v_LATCHEDRESTPOSITION) - (v_ANGULARFREQUENCY[_t19] * v_WAVETIME)) + v_PHASERAD[_t19])
    _c211 = (True if (v_PSI < 1e309 and v_PSI > -1e309) else False)
    _c212 = (_m_sin(v_PSI) if _c211 else _sf_SIN(v_PSI))
    v_SINESUM = (v_SINESUM + ((_t22 := v_LATCHEDAMPLITUDE[_t19]) * _c212))
    v_COSINESUM = (v_COSINESUM + (_t22 * (_m_cos(v_PSI) if _c211 else _sf_COS(v_PSI))))
    v_SLOPESUM = (v_SLOPESUM + ((_t22 * _t21) * _c212))
else:
    v_COMPONENT = (_t16 + 1 if 1 <= _t16 else 1)""".splitlines()
#: What the rest of the body names (the outputs are stored back in its `finally`).
AFTER = ["v_HORIZONTAL = (-v_SINESUM)", "v_DONE = (v_PSI, v_COSINESUM, v_SLOPESUM, v_COMPONENT)"]
LISTS = ("v_WAVENUMBER", "v_ANGULARFREQUENCY", "v_PHASERAD", "v_LATCHEDAMPLITUDE")
PARAMS = ("_t15", "_t16", *LISTS, "v_LATCHEDRESTPOSITION", "v_WAVETIME", "v_PSI", "v_SINESUM", "v_COSINESUM", "v_SLOPESUM")
SPECIAL = [math.inf, -math.inf, math.nan, 0.0, -0.0, 5e-324, -2.5e-310, 1e-300, 1e200, -1e200]


def _sf(x):
    """The runtime's SIN of a value that is not finite: a fault (an exception here)."""
    raise ArithmeticError("not finite")


NAMESPACE = {"_m_sin": math.sin, "_m_cos": math.cos, "_sf_SIN": _sf, "_sf_COS": _sf}


def _passed(lines):
    """The lines after the pass, and the namespace with the kernels it registered (`_k0` ...)."""
    after, bound = list(lines), dict(NAMESPACE)

    def register(value):
        name = f"_k{sum(key.startswith('_k') for key in bound)}"
        bound[name] = value
        return name
    loops.replace(after, 0, register, bound.__setitem__)
    return after, bound


def _function(lines, namespace):
    """`lines` as a function of PARAMS returning its v_ locals (or the exception it raised)."""
    source = (f"def run({', '.join(PARAMS)}):\n    try:\n" + "\n".join("        " + line for line in lines)
              + "\n    except Exception as exc:\n        return type(exc).__name__\n"
              "    return {k: v for k, v in locals().items() if k.startswith('v_')}\n")
    exec(compile(source, "<loops test>", "exec"), namespace)
    return namespace["run"]


def _bits(x) -> bytes:
    return struct.pack("<d", x) if type(x) is float else repr(x).encode()


def _same(want, got) -> bool:
    if isinstance(want, str) or isinstance(got, str):
        return want == got
    flat = lambda d: {k: ([_bits(v) for v in d[k]] if isinstance(d[k], (list, tuple)) else _bits(d[k])) for k in d}
    return flat(want) == flat(got)


def _row(rng, n, special=False):
    lists = [[rng.uniform(1e-5, 5e-3) for _ in range(8)], [rng.uniform(0.2, 3.0) for _ in range(8)],
             [rng.uniform(-3.2, 3.2) for _ in range(8)], [rng.uniform(-800.0, 800.0) for _ in range(8)]]
    scalars = [rng.uniform(-1e4, 1e4), rng.uniform(0.0, 1e5), rng.random(), 0.0, 0.0, 0.0]
    if special:
        for _ in range(1 + rng.randrange(2)):
            if rng.random() < 0.5:
                rng.choice(lists)[rng.randrange(n)] = rng.choice(SPECIAL)
            else:
                scalars[rng.randrange(6)] = rng.choice(SPECIAL)
    return (range(1, n + 1), n, *lists, *scalars)


def _mismatches(rows):
    after, bound = _passed(WAVE + AFTER)
    python = _function(WAVE + AFTER, dict(NAMESPACE))
    kernel = _function(after, bound)
    return [row for row in rows if not _same(python(*row), kernel(*row))]


def test_the_pass_makes_one_kernel_of_the_wave_loop():
    after, bound = _passed(WAVE + AFTER)
    assert after[0] == ("_kr = _k0(_t15, v_WAVENUMBER, v_LATCHEDRESTPOSITION, v_ANGULARFREQUENCY, v_WAVETIME,"
                        " v_PHASERAD, v_SINESUM, v_LATCHEDAMPLITUDE, v_COSINESUM, v_SLOPESUM)")
    assert after[1] == "if _kr is None:"
    assert after[2:2 + len(WAVE)] == ["    " + line for line in WAVE]     # the loop as it was
    assert after[2 + len(WAVE):] == ["else:", "    v_COSINESUM, v_PSI, v_SINESUM, v_SLOPESUM, = _kr",
                                     "    v_COMPONENT = (_t16 + 1 if 1 <= _t16 else 1)", *AFTER]


def _kernel_answers(after, bound, row):
    """What the kernel of the first line of `after` returns for `row` (PARAMS' values)."""
    kernel, arguments = re.fullmatch(r"_kr = (\w+)\((.*)\)", after[0]).groups()
    values = dict(zip(PARAMS, row))
    return bound[kernel](*(values[name] for name in arguments.split(", ")))


def test_the_kernel_gives_pythons_values_bit_for_bit():
    rng = random.Random(17)
    rows = [_row(rng, rng.randint(1, 8)) for _ in range(300)]
    assert _mismatches(rows) == []
    after, bound = _passed(WAVE + AFTER)
    _function(after, bound)(*rows[0])                     # the first call builds the kernel
    assert all(type(_kernel_answers(after, bound, row)) is tuple for row in rows)   # computed, not None


def test_special_values_take_the_loop_in_python():
    rng = random.Random(22)
    rows = [_row(rng, rng.randint(1, 8), special=True) for _ in range(300)]
    assert _mismatches(rows) == []


def test_what_the_kernel_cannot_read_runs_in_python():
    rng = random.Random(5)
    base = list(_row(rng, 5))
    rows = []
    for change in ({0: range(0)}, {0: range(0, 5)}, {0: range(1, 9, 2)}, {0: [1, 2, 3]},   # not 1 .. stop by 1
                   {0: range(1, 10)},                             # longer than the lists: IndexError
                   {2: base[2][:3]}, {2: tuple(base[2])},          # a short list, a tuple
                   {5: [1] * 8}, {6: 3}):                         # int elements, an int operand
        row = list(base)
        for k, v in change.items():
            row[k] = v
        rows.append(tuple(row))
    assert _mismatches(rows) == []
    after, bound = _passed(WAVE + AFTER)
    assert _function(after, bound)(*rows[4]) == "IndexError"


def test_the_wave_sums_by_hand():
    """Two components, t = 0.25 s: the ST's formulas written out (libm's sin and cos)."""
    k, w, phi, a = [0.002, 0.004], [1.1, 2.3], [0.5, -1.0], [300.0, -150.0]
    x, t = 120.0, 0.25
    psi = [k[i] * x - w[i] * t + phi[i] for i in range(2)]
    want = {"v_PSI": psi[1],
            "v_SINESUM": (0.0 + a[0] * math.sin(psi[0])) + a[1] * math.sin(psi[1]),
            "v_COSINESUM": (0.0 + a[0] * math.cos(psi[0])) + a[1] * math.cos(psi[1]),
            "v_SLOPESUM": (0.0 + a[0] * k[0] * math.sin(psi[0])) + a[1] * k[1] * math.sin(psi[1])}
    after, bound = _passed(WAVE + AFTER)
    got = _function(after, bound)(range(1, 3), 2, k, w, phi, a, x, t, 9.0, 0.0, 0.0, 0.0)
    assert {name: _bits(got[name]) for name in want} == {name: _bits(v) for name, v in want.items()}
    assert got["v_COMPONENT"] == 3


@pytest.mark.parametrize("lines", [
    WAVE[:-2] + AFTER,                                                   # no else: the variable's value
    WAVE + AFTER + ["v_X = _t22"],                                       # a temporary read after the loop
    WAVE[:2] + ["    v_PSI = (v_WAVENUMBER[_t19] // 2.0)"] + WAVE[3:] + AFTER,   # not + - *
    WAVE[:2] + ["    v_PSI = (v_WAVENUMBER[v_COMPONENT] * 2.0)"] + WAVE[3:] + AFTER,  # another index
    WAVE[:4] + ["    _c212 = (_m_sin(v_PSI) if _c211 else _sf_COS(v_PSI))"] + WAVE[5:] + AFTER,  # another guard
    [WAVE[0], "    _t19 = v_COMPONENT - 2"] + WAVE[2:] + AFTER,         # not the index from 0
])
def test_loops_of_other_forms_are_left_as_they_are(lines):
    assert _passed(lines)[0] == lines


@pytest.mark.skipif(not sys.platform.startswith("linux") or shutil.which("readelf") is None, reason="ELF, readelf")
def test_the_kernels_sin_and_cos_are_the_functions_math_calls():
    """The math module calls `sin`, `cos` and `atan` through its PLT: the addresses in its GOT
    (bound by the first call) are the ones the kernels bind (kernels.py's `atan` too)."""
    import math as m

    relocations = subprocess.run(["readelf", "-rW", m.__file__], capture_output=True, text=True).stdout
    slots = {name: int(offset, 16) for offset, name in
             re.findall(r"^([0-9a-f]+)\s+\S+\s+R_X86_64_JUMP_SLOT\s+\S+\s+(sin|cos|atan)@", relocations, re.M)}
    m.sin(0.5), m.cos(0.5), m.atan(0.5)
    base = next(int(line.split("-")[0], 16) for line in open("/proc/self/maps") if line.rstrip().endswith(m.__file__))
    symbols = loops.libm_symbols()
    assert {name: ctypes.c_void_p.from_address(base + slot).value for name, slot in slots.items()} == \
        {"sin": symbols["sin"], "cos": symbols["cos"], "atan": symbols["atan"]}


def test_an_interpreter_whose_ranges_lie_elsewhere_runs_the_loop_in_python(monkeypatch):
    """Where ints or ranges are not CPython 3.11's, the kernel answers None on every call."""
    assert loops.ranges_are_cpythons()
    monkeypatch.setattr(loops, "ranges_are_cpythons", lambda: False)
    after, bound = _passed(WAVE + AFTER)
    row = _row(random.Random(3), 4)
    got = _function(after, bound)(*row)
    assert _same(_function(WAVE + AFTER, dict(NAMESPACE))(*row), got)
    assert _kernel_answers(after, bound, row) is None        # the kernel the first call bound


def test_a_loop_of_sums_without_sin_or_cos_is_left():
    """The pass takes loops that call SIN or COS; a body that calls them elsewhere does not
    make its other loops kernels."""
    sums = ["for v_I in _t5:", "    _t6 = v_I - 1", "    v_S = (v_S + (v_A[_t6] * v_A[_t6]))", "else:",
            "    v_I = (_t7 + 1 if 1 <= _t7 else 1)"]
    lines = sums + ["v_X = _m_sin(v_S)", "v_DONE = (v_S, v_I)"]
    assert _passed(lines)[0] == lines

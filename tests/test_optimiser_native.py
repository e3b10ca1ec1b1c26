"""The `native` pass (st_runtime/compiler/optimise/native.py): a `vector` run computed by
machine code LLVM compiles from the run's graph gives Python's floats bit for bit, falls
back to Python operation by operation when an output is not finite, contracts no multiply
and add into an FMA, compiles on the run's first call, and is off by its switch.

The references are Python's own float arithmetic: the lines the compiler wrote, executed as
they are (test_compiler_tables_passes_vector.py's families and special inputs), and for the
determinant the Leibniz formula written out in Python (test_optimiser_vector.py's)."""

from __future__ import annotations

import math
import random
import re
import struct
import types
from dataclasses import replace

import pytest

pytest.importorskip("llvmlite")

from st_runtime import api  # noqa: E402
from st_runtime.compiler import Optimisations, compile_program  # noqa: E402
from st_runtime.compiler.optimise import native, vector  # noqa: E402
from test_compiler_tables_passes_vector import ELEMENTS, FAMILIES, FLOATS, _check, _register  # noqa: E402
from test_optimiser_vector import LEIBNIZ5, N, _leibniz, _run, helpers_in  # noqa: E402


def _bits(x: float) -> bytes:
    return struct.pack("<d", x)


def _native_vectorised(lines: list[str], elements=None):
    """The lines after the pass with native kernels, and the namespace its calls need."""
    bound: dict = {}
    out = list(lines)
    vector.vectorise(out, 0, len(out), set(FLOATS + list(ELEMENTS)).__contains__, _register(bound),
                     None if elements is None else elements.get, bound.__setitem__)
    return out, bound


def _is_native(run) -> bool:
    """A native kernel (a builtin function), or what builds it on the first call."""
    if isinstance(run, types.BuiltinFunctionType):
        return isinstance(run.__self__, vector.Vectorised)
    return run.__func__.__name__ == "first"


def runs_in(compiled) -> list:
    """The runs a build's generated code calls (each `__self__` a Vectorised)."""
    return [v for v in compiled.namespace.values() if isinstance(getattr(v, "__self__", None), vector.Vectorised)]


@pytest.mark.parametrize("family", FAMILIES.values(), ids=FAMILIES.keys())
def test_a_native_run_gives_pythons_floats(family):
    """Each family of runs (products by depth, chains, literals, a list passed whole), for
    ordinary inputs and for infinities, NaN, -0.0, huge, tiny and subnormal ones: every
    value a later line can read is the one Python's lines give, bit for bit."""
    rng = random.Random(3)
    lines, reads_after = family(rng)
    later = [f"v_R{k} = abs({name})" for k, name in enumerate(reads_after)]
    elements = ELEMENTS if "_e0" in "\n".join(lines) else None
    after, bound = _native_vectorised(lines + later, elements)
    assert len(bound) == 1 and _is_native(bound["_k0"])
    _check(lines + later, after, bound, reads_after, seed=3)
    assert isinstance(bound["_k0"], types.BuiltinFunctionType)       # built by the first call


@pytest.fixture(scope="module")
def program():
    return api.load_text(LEIBNIZ5).program


@pytest.fixture(scope="module")
def builds(program):
    return {name: compile_program(program, optimise=o)
            for name, o in (("native", Optimisations()), ("numpy", replace(Optimisations(), native=False)))}


def _matrices(rng: random.Random):
    """Random 5x5 matrices, and ones with zeros, signed zeros, huge, tiny and subnormal
    entries (products that overflow to inf, underflow to zero or lose bits)."""
    specials = [0.0, -0.0, 1e300, -1e300, 1e-300, 5e-324, -2.5e-310, 1e60, -3e-80, 1.0, -1.0]
    for k in range(300):
        m = [rng.uniform(-4.0, 4.0) for _ in range(N * N)]
        for _ in range(k % 6):
            m[rng.randrange(N * N)] = rng.choice(specials)
        if k % 50 == 49:
            m = [rng.choice(specials) for _ in range(N * N)]
        yield m


def test_the_determinant_is_the_leibniz_formulas_bit_for_bit(builds):
    run, = runs_in(builds["native"])
    assert _is_native(run)
    for m in _matrices(random.Random(11)):
        fb, _ = _run(builds["native"], m)
        want = _leibniz(m)
        assert _bits(fb.v_D) == _bits(want) or (math.isnan(want) and math.isnan(fb.v_D)), m


def test_a_non_finite_output_takes_the_run_in_python(program):
    """The kernel says whether every output is finite; when one is not, the run is the
    Python operation by operation (`exact`), called exactly then."""
    helper, = helpers_in(compile_program(program, optimise=Optimisations()))
    calls = []
    exact = helper.exact
    helper.exact = lambda whole, inputs: calls.append(1) or exact(whole, inputs)
    run = native.builtin(helper, native.compiled(native.helper_ir(helper)))     # calls the counting `exact`
    m = [float(k % 7) - 3.0 for k in range(N * N)]
    assert run(m, (0.0,))[0] == _leibniz(m) and calls == []
    for value in (math.inf, -math.inf, math.nan, 1e300):
        big = list(m)
        big[7] = big[13] = value                  # 1e300: products overflow to inf
        got = run(big, (0.0,))[0]
        want = _leibniz(big)
        assert _bits(got) == _bits(want) or (math.isnan(want) and math.isnan(got))
        assert not math.isfinite(want) and len(calls) == 1
        calls.clear()


def test_no_multiply_and_add_is_fused(program):
    """The emitted code has separate multiplies and adds: no `vfmadd` (one rounding fewer
    than Python's `*` then `+`).  The check can fail: the same run with LLVM's `contract`
    flags, compiled for a CPU with FMA, has them."""
    helper, = helpers_in(compile_program(program, optimise=Optimisations()))
    ir = native.helper_ir(helper)
    code = native.assembly(ir)
    assert "mulsd" in code or "mulpd" in code
    assert "fma" not in code.lower()
    if native._llvm.get_process_triple().startswith("x86_64"):
        contracted = re.sub(r"= (fmul|fadd|fsub) double", r"= \1 contract double", ir)
        machine = native._llvm.Target.from_triple(native._llvm.get_process_triple()).create_target_machine(
            cpu="haswell", opt=2)
        assert "vfmadd" in machine.emit_assembly(native._llvm.parse_assembly(contracted))


def test_the_kernel_is_compiled_by_the_first_call_and_kept():
    rng = random.Random(1234)
    lines = FAMILIES["two chains, nested"](rng)[0]
    lines.append(f"v_F = (_t1 * {rng.uniform(1.0, 2.0)!r})")      # an IR no other test has
    _, bound = _native_vectorised(lines)
    helper = bound["_k0"].__self__
    ir = native.helper_ir(helper)
    assert ir not in native._KERNELS                # loading compiled nothing
    values = tuple(rng.uniform(-1.0, 1.0) for _ in helper.variable_inputs)
    first = bound["_k0"](None, values)
    assert ir in native._KERNELS and isinstance(bound["_k0"], types.BuiltinFunctionType)
    kernels = len(native._KERNELS)
    _, again = _native_vectorised(lines)             # the same graph, loaded again
    assert again["_k0"](None, values) == first == tuple(helper.exact(None, values))      # (a tuple: native.py)
    assert len(native._KERNELS) == kernels          # not compiled again


def test_the_switch_and_the_environment_give_numpys_kernel(program, builds, monkeypatch):
    numpy_run, = runs_in(builds["numpy"])
    assert numpy_run.__func__.__name__ == "run" and not _is_native(numpy_run)
    monkeypatch.setenv("ST_RUNTIME_NATIVE", "0")
    run, = runs_in(compile_program(program, optimise=Optimisations()))
    assert not _is_native(run)
    m = [float((5 * k) % 13) - 6.0 for k in range(N * N)]
    assert _bits(_run(builds["numpy"], m)[0].v_D) == _bits(_run(builds["native"], m)[0].v_D) == _bits(_leibniz(m))


# Session 21 (h-mut-s21): rows for the survivors of native.py's every mutant.

@pytest.mark.parametrize("value, on", [("0", False), ("off", False), (" OFF ", False), ("No", False),
                                       ("false", False), ("FALSE\n", False),
                                       ("1", True), ("on", True), ("yes", True), ("", True)])
def test_the_environment_switch_reads_its_off_words_in_any_case(value, on, monkeypatch):
    """`ST_RUNTIME_NATIVE` turns the pass off with 0, off, no or false, spaces and case aside
    (native.enabled's docstring and code); any other value leaves it on (llvmlite is here)."""
    monkeypatch.setenv("ST_RUNTIME_NATIVE", value)
    assert native.enabled() is on


def test_unset_the_environment_leaves_native_kernels_on(monkeypatch):
    monkeypatch.delenv("ST_RUNTIME_NATIVE", raising=False)
    assert native.enabled() is True


def test_the_kernel_is_a_builtin_named_native_run_bound_to_its_helper(program):
    """The builtin function's name is its method definition's `ml_name`; its `__self__` the
    Vectorised helper whose `exact` it calls."""
    helper, = helpers_in(compile_program(program, optimise=Optimisations()))
    run = native.builtin(helper, native.compiled(native.helper_ir(helper)))
    assert run.__name__ == "native_run" and run.__self__ is helper and run.__doc__ is None


def test_this_interpreters_layout_is_cpythons():
    assert native.layout_is_cpythons() is True


@pytest.mark.parametrize("name, pointer, gil_disabled", [("pypy", 8, 0), ("cpython", 4, 0), ("cpython", 8, 1)])
def test_another_interpreters_layout_is_not_read(name, pointer, gil_disabled, monkeypatch):
    """The kernels read CPython's 64-bit GIL build's object layout: another implementation,
    4-byte pointers or a free-threaded build (`Py_GIL_DISABLED`) is refused before any
    address is read, so `first_call` keeps NumPy's kernel (native.py's docstring)."""
    import sysconfig

    config = sysconfig.get_config_var
    monkeypatch.setattr(native.sys, "implementation", types.SimpleNamespace(name=name))
    monkeypatch.setattr(native.struct, "calcsize", lambda fmt: pointer)
    monkeypatch.setattr(sysconfig, "get_config_var",
                        lambda key: gil_disabled if key == "Py_GIL_DISABLED" else config(key))
    assert native.layout_is_cpythons() is False


@pytest.mark.parametrize("offset, wrong", [("OB_FVAL", 8), ("OB_TYPE", 0), ("OB_SIZE", 8)])
def test_a_layout_that_is_not_where_the_kernels_read_is_refused(offset, wrong, monkeypatch):
    """Each probe of the layout must hold: a float's double read at another offset (its
    type pointer), a type read at the reference count, a list's size read at its type
    (each still inside the object: nothing is dereferenced) make the check say no."""
    monkeypatch.setattr(native, offset, wrong)
    assert native.layout_is_cpythons() is False


def test_the_first_call_keeps_numpys_kernel_where_the_layout_is_not_cpythons(monkeypatch):
    """first_call's docstring: where the layout check says no, nothing is compiled and the
    helper's own (NumPy) run is bound in place of the first call, with the same result."""
    monkeypatch.setattr(native, "layout_is_cpythons", lambda: False)
    rng = random.Random(4321)
    lines = FAMILIES["two chains, nested"](rng)[0]
    lines.append(f"v_F = (_t1 * {rng.uniform(2.0, 3.0)!r})")      # an IR no other test has
    _, bound = _native_vectorised(lines)
    helper = bound["_k0"].__self__
    values = tuple(rng.uniform(-1.0, 1.0) for _ in helper.variable_inputs)
    got = bound["_k0"](None, values)
    assert bound["_k0"] == helper.run and not isinstance(bound["_k0"], types.BuiltinFunctionType)
    assert native.helper_ir(helper) not in native._KERNELS
    assert got == helper.exact(None, values)


# Session 22 (h-comp15-s22): the switch is read once a load, not once a body.

def test_a_load_reads_the_switch_once_and_each_load_reads_it_again(monkeypatch):
    """`native.enabled` reads the environment (a test may switch it between loads): a compile
    asks it once, however many bodies it compiles (three here: two FUNCTIONs and a PROGRAM),
    and the next compile asks again."""
    program = api.load_text("""
FUNCTION F1 : LREAL VAR_INPUT x : LREAL; END_VAR F1 := x * 2.0; END_FUNCTION
FUNCTION F2 : LREAL VAR_INPUT x : LREAL; END_VAR F2 := x + 1.0; END_FUNCTION
PROGRAM P VAR y : LREAL; END_VAR y := F1(F2(y)); END_PROGRAM
""").program
    asked = []
    enabled = native.enabled
    monkeypatch.setattr(native, "enabled", lambda: asked.append(1) or enabled())
    compile_program(program)
    assert len(asked) == 1
    compile_program(program)
    assert len(asked) == 2


# Session 25 (lead): a helper a native kernel replaces makes no NumPy arrays, so a load
# imports no NumPy (a first load of generated/iec: about 320 million machine instructions).

_NUMPY_AFTER = """
import sys
from st_runtime import api
program = api.load_text(sys.stdin.read())
loaded = "numpy" in sys.modules
fb = program.compiled.new("Det5")
fb.v_M = [float((k * 7) % 5) - 2.0 for k in range(25)]
class Context:            # what a body needs of the controller (no test module: they import NumPy)
    budget, faults = 10**12, []
type(fb).execute(fb, Context())
print(loaded, "numpy" in sys.modules, repr(fb.v_D))
"""


@pytest.mark.parametrize("switch, numpy_at_load", [("1", False), ("0", True)])
def test_numpy_is_imported_only_where_its_kernel_runs(switch, numpy_at_load):
    """With native kernels (ST_RUNTIME_NATIVE=1), neither the load nor the run of the Leibniz
    5x5 imports NumPy (the kernel takes the helper's place at its first call); with them
    off, the helper is NumPy's and the load imports it.  The determinant is the Leibniz
    formula's either way."""
    import os
    import subprocess
    import sys

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = dict(os.environ, ST_RUNTIME_NATIVE=switch,
               PYTHONPATH=os.pathsep.join([root, os.environ.get("PYTHONPATH", "")]))
    out = subprocess.run([sys.executable, "-c", _NUMPY_AFTER], input=LEIBNIZ5, env=env,
                         capture_output=True, text=True, check=True).stdout.split()
    assert out[:2] == [str(numpy_at_load), str(numpy_at_load)]
    m = [float((k * 7) % 5) - 2.0 for k in range(N * N)]
    assert _bits(float(out[2])) == _bits(_leibniz(m))

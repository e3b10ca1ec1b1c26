"""`native`: a run of vector.py computed by machine code LLVM makes (llvmlite), one call a run.

vector.py's graph (inputs, then `+ - *` operations in order, then the outputs) is written
out as LLVM IR, one `fmul`/`fadd`/`fsub` of doubles per operation on the same two operands
in the same order, and compiled by MCJIT the first time the run is called (a program that
never calls it compiles nothing; a graph compiled once is kept for the process, by its IR
text, so the exact and fast copies of a body and every load of one program share it).

Exactness: LLVM's floating-point instructions without fast-math flags are IEEE-754
binary64 operations rounded to nearest, Python's float `* + -`, and its optimisations keep
them so (no reassociation; a fold such as `x * 1.0 -> x` is the same value except for a
NaN's payload).  No multiply and add are contracted into one FMA (one rounding fewer): the
instructions carry no `contract` flag, the target machine is a generic x86-64 (no FMA
instruction at all) and the emitted code is checked for `vfmadd` by the tests.  The
function returns whether every output is finite; a non-finite value never becomes finite
through `+ - *`, so then every value was finite and the outputs are Python's bit for bit.
Otherwise (an inf or a NaN somewhere, whose sign or payload could differ) the caller runs
vector.py's `exact`, the run in Python operation by operation.

The crossing: the inputs reach one C double buffer by one `struct.pack_into` (as the NumPy
kernel's), the function takes the buffer's address and writes the outputs after the
inputs, read back by one `struct.unpack_from`.

Without llvmlite (not installed, or `ST_RUNTIME_NATIVE=0`) `kernel` returns None and
vector.py's NumPy kernel runs, as before this module.
"""

from __future__ import annotations

import ctypes
import importlib.util
import os
import struct
import types

#: Compiled kernels by their IR text: (execution engine, C function).
_KERNELS: dict[str, tuple] = {}
_llvm = None            # llvmlite.binding, imported by the first kernel built
_target_machine = None


def enabled() -> bool:
    """Whether native kernels may be built: llvmlite importable and not switched off by
    `ST_RUNTIME_NATIVE=0` (to compare with NumPy's kernel in one tree)."""
    if os.environ.get("ST_RUNTIME_NATIVE", "1").strip().lower() in ("0", "off", "no", "false"):
        return False
    return importlib.util.find_spec("llvmlite") is not None     # found, not imported: loads stay fast


def _double(value: float) -> str:
    """An LLVM IR double constant with `value`'s bits exactly (LLVM's 64-bit hex form)."""
    return "0x%016X" % struct.unpack("<Q", struct.pack("<d", value))[0]


_INSTRUCTION = {"*": "fmul", "+": "fadd", "-": "fsub"}


def ir_text(n_inputs: int, slots: dict[int, int], constants: dict[int, float],
            ops: list[tuple[str, int, int]], live: list[int], outputs: list[int], out_slot: int) -> str:
    """The IR of `i1 run(double* io)`: input i is `io[slots[i]]` or the literal
    `constants[i]`; operation k (value n_inputs + k) is `ops[k]` of two earlier values, for
    each k in `live` (those that feed an output), in order; output j is stored at
    `io[out_slot + j]`; the result is whether every output is finite."""
    name = {i: _double(c) for i, c in constants.items()}
    body = []
    for i, slot in slots.items():
        body += [f"  %p{i} = getelementptr inbounds double, ptr %io, i64 {slot}",
                 f"  %v{i} = load double, ptr %p{i}, align 8"]
        name[i] = f"%v{i}"
    for k in live:
        op, a, b = ops[k]
        v = n_inputs + k
        body.append(f"  %v{v} = {_INSTRUCTION[op]} double {name[a]}, {name[b]}")
        name[v] = f"%v{v}"
    finite = "true"
    for j, o in enumerate(outputs):
        body += [f"  %o{j} = getelementptr inbounds double, ptr %io, i64 {out_slot + j}",
                 f"  store double {name[o]}, ptr %o{j}, align 8",
                 f"  %a{j} = call double @llvm.fabs.f64(double {name[o]})",
                 f"  %f{j} = fcmp olt double %a{j}, 0x7FF0000000000000",      # below inf: false for NaN
                 f"  %all{j} = and i1 {finite}, %f{j}"]
        finite = f"%all{j}"
    body.append(f"  ret i1 {finite}")
    return ("declare double @llvm.fabs.f64(double)\n\n"
            "define i1 @run(ptr noalias nocapture %io) nounwind {\nentry:\n" + "\n".join(body) + "\n}\n")


def _machine():
    """The target machine: the host's triple; on x86-64 the generic `x86-64` CPU (SSE2, no
    FMA instruction to contract into)."""
    global _llvm, _target_machine
    if _target_machine is None:
        import llvmlite.binding as llvm

        llvm.initialize_native_target()
        llvm.initialize_native_asmprinter()
        triple = llvm.get_process_triple()
        cpu = "x86-64" if triple.startswith("x86_64") else ""
        _target_machine = llvm.Target.from_triple(triple).create_target_machine(cpu=cpu, features="", opt=2)
        _llvm = llvm
    return _target_machine


def compiled(ir: str):
    """The C function `ir` defines (`run`), compiled once per process."""
    found = _KERNELS.get(ir)
    if found is None:
        machine = _machine()
        module = _llvm.parse_assembly(ir)
        module.verify()
        engine = _llvm.create_mcjit_compiler(module, machine)
        engine.finalize_object()
        function = ctypes.CFUNCTYPE(ctypes.c_bool, ctypes.c_void_p)(engine.get_function_address("run"))
        found = _KERNELS[ir] = (engine, function)
    return found[1]


def assembly(ir: str) -> str:
    """The machine code `ir` compiles to, as assembly text (for the tests' FMA check)."""
    machine = _machine()
    return machine.emit_assembly(_llvm.parse_assembly(ir))


def native_run(helper):
    """`helper.run` (a vector.py `Vectorised`) computed by a native kernel: the same
    arguments and results, its kernel compiled by the first call.  The inputs are packed
    in the order the NumPy kernel's buffer has them (the list passed whole, the tuple's
    inputs), the literals are constants of the IR, the outputs follow the inputs."""
    n_passed, n_out = helper.n_passed, len(helper.output_refs)
    buffer = (ctypes.c_double * (n_passed + n_out))()
    names = {"exact": helper.exact, "pack": struct.Struct(f"={n_passed}d").pack_into,
             "unpack": struct.Struct(f"={n_out}d").unpack_from, "memory": memoryview(buffer).cast("B"),
             "io": ctypes.c_void_p(ctypes.addressof(buffer)), "error": struct.error,
             "build": lambda: compiled(_helper_ir(helper))}
    lines = []
    if helper.n_list:
        lines.append(f"if type(whole) is not list or len(whole) != {helper.n_list}: return exact(whole, inputs)")
    whole = "*(whole or ()), " if helper.n_list else ""
    lines += [f"try: pack(memory, 0, {whole}*inputs)",
              "except (error, TypeError, OverflowError): return exact(whole, inputs)",
              f"if kernel(io): return unpack(memory, {8 * n_passed})",
              "return exact(whole, inputs)"]
    source = ("def factory(" + ", ".join(names) + "):\n"
              "    def first(io):\n"              # the first call compiles the kernel
              "        nonlocal kernel\n"
              "        kernel = build()\n"
              "        return kernel(io)\n"
              "    kernel = first\n"
              "    def run(self, whole, inputs):\n" + "".join(f"        {line}\n" for line in lines) +
              "    return run\n")
    scope: dict = {}
    exec(compile(source, "<native run>", "exec"), scope)
    run = scope["factory"](**names)
    run.buffer = buffer          # kept alive with the function
    return types.MethodType(run, helper)


def _helper_ir(helper) -> str:
    """The IR of a `Vectorised` helper's run: its passed inputs at their buffer slots."""
    slots = {i: helper.n_list + p for p, i in enumerate(helper.variable_inputs)}
    slots.update(helper.elements)
    return ir_text(helper.n_inputs, slots, dict(helper.constants), helper.ops, helper.live,
                   helper.output_refs, helper.n_passed)

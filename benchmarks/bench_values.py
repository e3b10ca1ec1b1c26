"""Store-path micro-benchmarks of the value model (not a test).

Prints ns per call of the float32 rounding candidates and of integer wrap
with and without the in-range fast path, measured side by side in one run.
Run: PYTHONPATH=. python benchmarks/bench_values.py (or with the package installed).
Measured here: array 50 ns, struct 69, ctypes 96, numpy 217; INT wrap with the
fast path 29 ns in range (58 out of range) against 45 for arithmetic only.
"""

from __future__ import annotations

import array
import ctypes
import struct
import timeit

import numpy as np

from st_runtime.types import INT
from st_runtime.values import int_wrapper, to_real32

N = 300_000


def ns_per_call(fn, arg) -> float:
    best = min(timeit.repeat(lambda: fn(arg), number=N, repeat=5))
    base = min(timeit.repeat(lambda: None, number=N, repeat=5))   # lambda overhead
    return (best - base) / N * 1e9


def main() -> None:
    pack = struct.Struct("f")
    p, u = pack.pack, pack.unpack
    buf = array.array("f", [0.0])

    def via_array(x):
        buf[0] = x
        return buf[0]

    candidates = {
        "array('f') store/load": via_array,
        "struct pack/unpack": lambda x: u(p(x))[0],
        "ctypes.c_float": lambda x: ctypes.c_float(x).value,
        "numpy.float32": lambda x: float(np.float32(x)),
        "values.to_real32": to_real32,
    }
    print("float32 rounding, ns per call:")
    for name, fn in candidates.items():
        print(f"  {name:24s} {ns_per_call(fn, 1.2345678901):7.1f}")

    half, mask = 1 << 15, (1 << 16) - 1
    arithmetic = lambda v: ((v + half) & mask) - half   # noqa: E731
    fast = int_wrapper(INT)
    print("INT wrap, ns per call (in range / out of range):")
    print(f"  arithmetic only          {ns_per_call(arithmetic, 1234):7.1f} / {ns_per_call(arithmetic, 40000):7.1f}")
    print(f"  values.int_wrapper(INT)  {ns_per_call(fast, 1234):7.1f} / {ns_per_call(fast, 40000):7.1f}")


if __name__ == "__main__":
    main()

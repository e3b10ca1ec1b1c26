"""Runtime speed: the same algorithms in ST (compiled by st_runtime) and in
hand-written Python, timed side by side in one run; and the empty-scan rate.

    /work/venv/bin/python benchmarks/bench_runtime.py [--repeat N]

Algorithms (6x6, as in the platform's forward kinematics):
  * determinant by the Leibniz formula with a constant permutation/sign table,
  * Doolittle LU decomposition with partial pivoting and the two substitutions,
  * inverse kinematics of the six legs (rotation Rz*Ry*Rx, leg vectors, lengths).
Target: ST within 2x of the hand-written Python; empty scan >= 200,000 scans/s.
"""

from __future__ import annotations

import argparse
import itertools
import math
import random
import sys
import time

from st_runtime.api import load_text
from st_runtime.compiler import compile_program

# ----------------------------------------------------------------- tables

PERMS = list(itertools.permutations(range(6)))


def _sign(p) -> int:
    s = 1
    for i in range(6):
        for j in range(i + 1, 6):
            if p[i] > p[j]:
                s = -s
    return s


SIGNS = [_sign(p) for p in PERMS]

# ------------------------------------------------------------------- ST

ST_SOURCE = """
VAR_GLOBAL CONSTANT
  PERM : ARRAY[1..720, 1..6] OF SINT := [%(perm)s];
  PERM_SIGN : ARRAY[1..720] OF LREAL := [%(sign)s];
END_VAR

FUNCTION Det6 : LREAL
VAR_IN_OUT M : ARRAY[1..6, 1..6] OF LREAL; END_VAR
VAR k, j : INT; p, s : LREAL; END_VAR
s := 0.0;
FOR k := 1 TO 720 DO
  p := PERM_SIGN[k];
  FOR j := 1 TO 6 DO
    p := p * M[j, PERM[k, j]];
  END_FOR;
  s := s + p;
END_FOR;
Det6 := s;
END_FUNCTION

(* Doolittle LU with partial pivoting, then L y = P b and U x = y. *)
FUNCTION LuSolve : BOOL
VAR_IN_OUT A : ARRAY[1..6, 1..6] OF LREAL; b : ARRAY[1..6] OF LREAL; x : ARRAY[1..6] OF LREAL; END_VAR
VAR i, j, k, pivot : INT; big, t, s : LREAL; END_VAR
FOR k := 1 TO 6 DO
  pivot := k; big := ABS(A[k, k]);
  FOR i := k + 1 TO 6 DO
    IF ABS(A[i, k]) > big THEN big := ABS(A[i, k]); pivot := i; END_IF;
  END_FOR;
  IF big = 0.0 THEN LuSolve := FALSE; RETURN; END_IF;
  IF pivot <> k THEN
    FOR j := 1 TO 6 DO
      t := A[k, j]; A[k, j] := A[pivot, j]; A[pivot, j] := t;
    END_FOR;
    t := b[k]; b[k] := b[pivot]; b[pivot] := t;
  END_IF;
  FOR i := k + 1 TO 6 DO
    A[i, k] := A[i, k] / A[k, k];
    FOR j := k + 1 TO 6 DO
      A[i, j] := A[i, j] - A[i, k] * A[k, j];
    END_FOR;
  END_FOR;
END_FOR;
FOR i := 1 TO 6 DO
  s := b[i];
  FOR j := 1 TO i - 1 DO s := s - A[i, j] * x[j]; END_FOR;
  x[i] := s;
END_FOR;
FOR i := 6 TO 1 BY -1 DO
  s := x[i];
  FOR j := i + 1 TO 6 DO s := s - A[i, j] * x[j]; END_FOR;
  x[i] := s / A[i, i];
END_FOR;
LuSolve := TRUE;
END_FUNCTION

FUNCTION_BLOCK Ik6
VAR_INPUT Pose : ARRAY[1..6] OF LREAL; END_VAR
VAR_OUTPUT Q : ARRAY[1..6] OF LREAL; END_VAR
VAR_IN_OUT B : ARRAY[1..6, 1..3] OF LREAL; P : ARRAY[1..6, 1..3] OF LREAL; END_VAR
VAR
  H0 : LREAL := 1374.0; L0 : LREAL := 1192.63;
  i : INT; ca, sa, cb, sb, cg, sg : LREAL;
  r11, r12, r13, r21, r22, r23, r31, r32, r33 : LREAL;
  lx, ly, lz : LREAL;
END_VAR
ca := COS(Pose[4] * 0.017453292519943295); sa := SIN(Pose[4] * 0.017453292519943295);
cb := COS(Pose[5] * 0.017453292519943295); sb := SIN(Pose[5] * 0.017453292519943295);
cg := COS(Pose[6] * 0.017453292519943295); sg := SIN(Pose[6] * 0.017453292519943295);
r11 := ca * cb; r12 := ca * sb * sg - sa * cg; r13 := ca * sb * cg + sa * sg;
r21 := sa * cb; r22 := sa * sb * sg + ca * cg; r23 := sa * sb * cg - ca * sg;
r31 := -sb;     r32 := cb * sg;                r33 := cb * cg;
FOR i := 1 TO 6 DO
  lx := r11 * P[i, 1] + r12 * P[i, 2] + r13 * P[i, 3] + Pose[1] - B[i, 1];
  ly := r21 * P[i, 1] + r22 * P[i, 2] + r23 * P[i, 3] + Pose[2] - B[i, 2];
  lz := r31 * P[i, 1] + r32 * P[i, 2] + r33 * P[i, 3] + Pose[3] + H0 - B[i, 3];
  Q[i] := SQRT(lx * lx + ly * ly + lz * lz) - L0;
END_FOR;
END_FUNCTION_BLOCK

PROGRAM Empty
VAR n : DINT; END_VAR
n := n + 1;
END_PROGRAM
"""


def st_source() -> str:
    perm = ", ".join(str(v + 1) for p in PERMS for v in p)
    sign = ", ".join(f"{s}.0" for s in SIGNS)
    return ST_SOURCE % {"perm": perm, "sign": sign}


# ------------------------------------------------------- hand-written Python

def py_det6(m):
    s = 0.0
    for perm, sign in zip(PERMS, SIGNS):
        p = sign
        for j in range(6):
            p *= m[j][perm[j]]
        s += p
    return s


def py_lu_solve(a, b, x):
    for k in range(6):
        pivot, big = k, abs(a[k][k])
        for i in range(k + 1, 6):
            if abs(a[i][k]) > big:
                big, pivot = abs(a[i][k]), i
        if big == 0.0:
            return False
        if pivot != k:
            a[k], a[pivot] = a[pivot], a[k]
            b[k], b[pivot] = b[pivot], b[k]
        for i in range(k + 1, 6):
            a[i][k] = a[i][k] / a[k][k]
            for j in range(k + 1, 6):
                a[i][j] = a[i][j] - a[i][k] * a[k][j]
    for i in range(6):
        s = b[i]
        for j in range(i):
            s -= a[i][j] * x[j]
        x[i] = s
    for i in range(5, -1, -1):
        s = x[i]
        for j in range(i + 1, 6):
            s -= a[i][j] * x[j]
        x[i] = s / a[i][i]
    return True


def py_ik6(pose, base, plat, q, h0=1374.0, l0=1192.63):
    d = math.pi / 180.0
    ca, sa = math.cos(pose[3] * d), math.sin(pose[3] * d)
    cb, sb = math.cos(pose[4] * d), math.sin(pose[4] * d)
    cg, sg = math.cos(pose[5] * d), math.sin(pose[5] * d)
    r11, r12, r13 = ca * cb, ca * sb * sg - sa * cg, ca * sb * cg + sa * sg
    r21, r22, r23 = sa * cb, sa * sb * sg + ca * cg, sa * sb * cg - ca * sg
    r31, r32, r33 = -sb, cb * sg, cb * cg
    for i in range(6):
        px, py, pz = plat[i]
        bx, by, bz = base[i]
        lx = r11 * px + r12 * py + r13 * pz + pose[0] - bx
        ly = r21 * px + r22 * py + r23 * pz + pose[1] - by
        lz = r31 * px + r32 * py + r33 * pz + pose[2] + h0 - bz
        q[i] = math.sqrt(lx * lx + ly * ly + lz * lz) - l0


# ------------------------------------------------------------------ timing

def best_of(fns, repeat: int, number: int) -> list[float]:
    """Seconds per call of each function, best of `repeat` batches of `number`.

    The batches of the functions alternate, so a change in the machine's load
    during the run affects them alike.
    """
    best = [math.inf] * len(fns)
    for _ in range(repeat):
        for i, fn in enumerate(fns):
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            best[i] = min(best[i], (time.perf_counter() - t0) / number)
    return best


def geometry():
    rb, rp, hb, hp = 470.45, 388.95, 95.0, -115.0
    fb, fp = math.radians(24.07), math.radians(103.66)
    base, plat = [], []
    for i in range(1, 7):
        if i % 2:
            th, ph = (2 * i * math.pi - 3 * fb) / 6, (2 * i * math.pi - 3 * fp) / 6
        else:
            th, ph = th + fb, ph + fp
        base.append([rb * math.cos(th), rb * math.sin(th), hb])
        plat.append([rp * math.cos(ph), rp * math.sin(ph), hp])
    return base, plat


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=9)
    args = parser.parse_args(argv)
    rng = random.Random(1)

    t0 = time.perf_counter()
    project = load_text(st_source(), "bench.st")
    load_s = time.perf_counter() - t0
    plc = project.controller()
    ctx = plc.controller.ctx
    ctx.budget = 1 << 62
    fns = project.compiled.functions

    m = [[rng.uniform(-1, 1) for _ in range(6)] for _ in range(6)]
    flat = [v for row in m for v in row]
    det_st = fns["DET6"](ctx, flat)
    det_py = py_det6(m)
    assert abs(det_st - det_py) <= 1e-12 * max(1.0, abs(det_py)), (det_st, det_py)

    a0 = [[rng.uniform(-1, 1) + (3.0 if i == j else 0.0) for j in range(6)] for i in range(6)]
    b0 = [rng.uniform(-1, 1) for _ in range(6)]
    a_flat, b_st, x_st = [v for row in a0 for v in row], list(b0), [0.0] * 6
    fns["LUSOLVE"](ctx, a_flat, b_st, x_st)
    x_py = [0.0] * 6
    py_lu_solve([row[:] for row in a0], list(b0), x_py)
    assert max(abs(p - q) for p, q in zip(x_st, x_py)) < 1e-12

    base, plat = geometry()
    ik = project.compiled.new("Ik6")
    ik.v_B = [v for row in base for v in row]
    ik.v_P = [v for row in plat for v in row]
    pose = [10.0, -5.0, 150.0, 2.0, -3.0, 4.0]
    ik.v_POSE[:] = pose
    ik.execute(ctx)
    q_py = [0.0] * 6
    py_ik6(pose, base, plat, q_py)
    assert max(abs(p - q) for p, q in zip(ik.v_Q, q_py)) < 1e-9

    # The same program compiled without the per-statement fault handlers.
    bare = compile_program(project.program, guard_statements=False)
    bare_ik = bare.new("Ik6")
    bare_ik.v_B, bare_ik.v_P = ik.v_B, ik.v_P
    bare_ik.v_POSE[:] = pose

    def st_lu(lu):
        def go():
            a_flat[:] = [v for row in a0 for v in row]
            b_st[:] = b0
            lu(ctx, a_flat, b_st, x_st)
        return go

    def hand_lu():
        py_lu_solve([row[:] for row in a0], list(b0), x_py)

    det6, bare_det6 = fns["DET6"], bare.functions["DET6"]
    cases = [
        ("Leibniz det 6x6 (720-row table)", lambda: det6(ctx, flat), lambda: bare_det6(ctx, flat),
         lambda: py_det6(m), 200),
        ("Doolittle LU solve 6x6", st_lu(fns["LUSOLVE"]), st_lu(bare.functions["LUSOLVE"]), hand_lu, 5000),
        ("IK, six legs", lambda: ik.execute(ctx), lambda: bare_ik.execute(ctx),
         lambda: py_ik6(pose, base, plat, q_py), 20000),
    ]
    print(f"load (parse + check + compile) of {st_source().count(chr(10))} lines: {load_s * 1e3:.0f} ms")
    print(f"{'algorithm':34s} {'ST us':>9s} {'Python us':>10s} {'ratio':>7s} {'ST unguarded us':>16s}")
    worst = 0.0
    for name, st_fn, bare_fn, py_fn, number in cases:
        st_t, py_t, bare_t = best_of([st_fn, py_fn, bare_fn], args.repeat, number)
        ratio = st_t / py_t
        worst = max(worst, ratio)
        print(f"{name:34s} {st_t * 1e6:9.2f} {py_t * 1e6:10.2f} {ratio:7.2f}x {bare_t * 1e6:16.2f}")
    print(f"worst ratio ST / hand-written Python: {worst:.2f}x (target <= 2x)")
    print("(ST unguarded: compiled without the per-statement try/except; CPython 3.11+ "
          "exception tables make the guards free until a fault)")

    empty = project.controller()
    empty.add_program("Empty")
    n = 200_000
    best = math.inf
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        empty.run(n)
        best = min(best, time.perf_counter() - t0)
    print(f"empty scan (one assignment): {n / best:,.0f} scans/s (target >= 200,000)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Machine instructions per Newton-Raphson iteration of the generated SP_ForwardKinematics, by callgrind.

    # this tree, every variant
    .venv/bin/python tools/callgrind_fk.py [--poses 200] [--variant table] [--keep out.callgrind]
    # any other tree (the code measured is the one PYTHONPATH puts first)
    PYTHONPATH=/path/to/tree .venv/bin/python tools/callgrind_fk.py

Prints, per variant of the rendered FK (``table``, ``unrolled``, ``lu``: the variants of
``benchmarks/bench_fk.py``), the machine instructions (callgrind's Ir) of one FK iteration:
the instructions of solving ``--poses`` of ``bench_fk.py``'s poses (seed 7, from p_NR,
Tolerance 1e-9) divided by the Newton iterations they take, so the figure holds what
``bench_fk.py`` times (the harness's call per simulated scan and the per-solve work spread over
the iterations). A figure the machine's load does not change, unlike a time.

How: as ``tools/callgrind_wave.py`` (its ``run_under_callgrind``): the child loads the
kinematics and solves every pose once uninstrumented (warm), switches callgrind's
instrumentation on and solves them again as one call inside ``itertools.starmap``, the only
call counted (``--toggle-collect=starmap_next``). ``--keep`` keeps the output file (one
variant) for ``callgrind_annotate``.
"""

from __future__ import annotations

import argparse
import itertools
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from callgrind_wave import _CHILD, instrument, run_under_callgrind  # noqa: E402

VARIANTS = ("table", "unrolled", "lu")
#: The benchmark's poses: ``bench_fk.py``'s seed.
POSE_SEED = 7
#: Where the child writes the iterations its measured solves took.
_ITERATIONS_SUFFIX = ".iterations"


def measured_solves(poses: int, variant: str, iterations_file: str) -> None:
    """The child: solve the poses once warm, then again with the instrumentation on."""
    import numpy as np

    from stgen.config import PlatformConfig
    from stgen.reference import inverse_kinematics
    from stgen.render import RenderOptions
    from stgen.verify import fk_solver, load_kinematics, random_poses

    config = PlatformConfig.default()
    solver = fk_solver(config)
    positions = inverse_kinematics(config.geometry, random_poses(config, poses, seed=POSE_SEED),
                                   config.stroke).positions
    start = np.asarray(config.solver.start_pose)
    runtime = load_kinematics(config, RenderOptions(variant), capacity=len(positions))
    runtime.forward_kinematics(positions, start, solver)
    instrument("on")
    for fk in itertools.starmap(runtime.forward_kinematics, [(positions, start, solver)]):
        if not fk.done.all():
            raise SystemExit(f"{variant}: not every solve converged")
        Path(iterations_file).write_text(str(int(fk.iterations.sum())))


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == [_CHILD]:
        measured_solves(int(argv[1]), argv[2], argv[3])
        return 0
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=200, help="FK solves measured (default 200)")
    parser.add_argument("--variant", choices=VARIANTS, action="append",
                        help="a variant to measure (repeatable; default all three)")
    parser.add_argument("--keep", type=Path, help="keep callgrind's output file here (one variant)")
    args = parser.parse_args(argv)
    variants = args.variant or list(VARIANTS)
    if args.keep and len(variants) > 1:
        parser.error("--keep takes one --variant")
    import stgen

    print(f"{Path(stgen.__file__).resolve().parent.parent}: {args.poses} FK solves")
    with tempfile.TemporaryDirectory() as scratch:
        for variant in variants:
            out_file = args.keep or Path(scratch) / f"{variant}.callgrind"
            iterations_file = Path(scratch) / f"{variant}{_ITERATIONS_SUFFIX}"
            started = time.perf_counter()
            total = run_under_callgrind(args.poses, out_file, __file__, variant, str(iterations_file))
            iterations = int(iterations_file.read_text())
            print(f"  {variant:<9}{total / iterations:>12,.0f} machine instructions an iteration "
                  f"({total:,} in {iterations:,} iterations; {time.perf_counter() - started:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Benchmark: our ST parser against blark, side by side in one run.

    python benchmarks/bench_parse.py [--blark-files N]

1. Builds a corpus of ST files in a temporary directory: the accept corpus
   (`tests/corpus/accept`) plus generated kinematics-style POUs (loops, matrix
   arithmetic, IF/CASE, FB calls), at least 2,000 lines in all.
2. Parses every file with our parser (best of several rounds) and, when
   `st_runtime.checker` is importable, checks them: lines per second.
3. Parses the same files with blark (Lark Earley, TwinCAT grammar; its raw
   parse tree only, its fastest path) and prints lines per second and the
   ratio.  Files blark's grammar rejects are left out of the comparison on
   both sides.  blark is a benchmark-only dependency: without it the script
   says so and reports our figures alone (exit status 0).
4. Peak resident memory to load (parse, and check if available) 5,000 lines,
   measured in a fresh subprocess with `resource.getrusage`.

Times are CPU seconds of this process (`time.process_time`): both parsers
are single-threaded, and CPU time does not depend on what else the shared
machine is doing, so the ratio is stable from run to run.

Targets (issue 2): >= 100x blark's lines/s; 5,000 lines in < 150 MB.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from st_runtime.parser import parse  # noqa: E402

ACCEPT = ROOT / "tests" / "corpus" / "accept"
clock = time.process_time


def generated_pou(n: int) -> str:
    """One kinematics-style FUNCTION_BLOCK (about 75 lines)."""
    return textwrap.dedent(f"""\
        (* Generated benchmark block {n}: leg lengths and a Jacobian-like update. *)
        FUNCTION_BLOCK FB_Bench{n}
        VAR_INPUT
            Execute : BOOL;
            Pose : ARRAY[1..6] OF LREAL;
            Gain : LREAL := 0.5;
        END_VAR
        VAR_OUTPUT
            Done : BOOL;
            Busy : BOOL;
            Error : BOOL;
            ErrorID : WORD;
            Lengths : ARRAY[1..6] OF LREAL;
        END_VAR
        VAR
            i, j, k : INT;
            state : INT := 0;
            acc : LREAL;
            m : ARRAY[1..6, 1..6] OF LREAL;
            v : ARRAY[1..6] OF LREAL := [6(0.0)];
            edge : R_TRIG;
            timer : TON;
        END_VAR
            edge(CLK := Execute);
            timer(IN := Busy, PT := T#250ms);
            CASE state OF
                0:
                    IF edge.Q THEN
                        Busy := TRUE;
                        Done := FALSE;
                        state := 10;
                    END_IF;
                10:
                    FOR i := 1 TO 6 DO
                        FOR j := 1 TO 6 DO
                            m[i, j] := SIN(Pose[i] * 0.017453292519943295) * COS(Pose[j])
                                       + INT_TO_LREAL(i - j) * Gain;
                        END_FOR;
                    END_FOR;
                    state := 20;
                20:
                    FOR i := 1 TO 6 DO
                        acc := 0.0;
                        FOR k := 1 TO 6 DO
                            acc := acc + m[i, k] * Pose[k];
                        END_FOR;
                        v[i] := acc;
                        Lengths[i] := SQRT(v[i] * v[i] + 1.0E-9) - 1192.63;
                        IF Lengths[i] < 0.0 OR Lengths[i] > 600.0 THEN
                            Error := TRUE;
                            ErrorID := 16#1004;
                        END_IF;
                    END_FOR;
                    state := 30;
                30:
                    IF timer.Q AND NOT Error THEN
                        Done := TRUE;
                        Busy := FALSE;
                        state := 0;
                    ELSIF Error THEN
                        Busy := FALSE;
                        state := 99;
                    END_IF;
                99:
                    IF NOT Execute THEN
                        Error := FALSE;
                        ErrorID := 0;
                        state := 0;
                    END_IF;
            ELSE
                state := 0;
            END_CASE;
        END_FUNCTION_BLOCK
        """)


def build_corpus(directory: Path, min_lines: int) -> list[Path]:
    paths = []
    for source in sorted(ACCEPT.glob("*.st")):
        target = directory / source.name
        target.write_text(source.read_text(encoding="utf-8"), encoding="utf-8")
        paths.append(target)
    lines = sum(count_lines(p.read_text(encoding="utf-8")) for p in paths)
    n = 0
    while lines < min_lines:
        target = directory / f"generated_{n:03d}.st"
        target.write_text(generated_pou(n), encoding="utf-8")
        paths.append(target)
        lines += count_lines(target.read_text(encoding="utf-8"))
        n += 1
    return paths


def count_lines(text: str) -> int:
    return text.count("\n") + (0 if text.endswith("\n") else 1)


def time_ours(texts: dict[str, str], rounds: int) -> tuple[float, list]:
    """Median CPU time of `rounds` passes over the files (blark gets one pass,
    after a warm-up pass; the median keeps the comparison honest)."""
    times = []
    trees = []
    for _ in range(rounds):
        start = clock()
        trees = [parse(text, name)[0] for name, text in texts.items()]
        times.append(clock() - start)
    assert all(t is not None for t in trees), "the benchmark corpus must parse cleanly"
    return sorted(times)[len(times) // 2], trees


def time_check(trees) -> tuple[float, int] | None:
    """Check each file on its own with the native prelude (TON, R_TRIG, ...)."""
    try:
        from st_runtime import native
        from st_runtime import stdlib  # noqa: F401  (registers the standard FBs)

        del stdlib
        from st_runtime.checker import check
    except ImportError:
        return None
    prelude, _ = parse(native.prelude_source(), "<builtin>")
    errors = 0
    start = clock()
    for tree in trees:
        _, diagnostics = check([prelude, tree], "iec")
        errors += sum(d.is_error for d in diagnostics)
    return clock() - start, errors


def blark_parser():
    try:
        from blark.parse import get_parser
    except ImportError:
        return None
    return get_parser()


def blark_accepts(parser, text: str) -> bool:
    try:
        parser.parse(text, start="iec_source")
        return True
    except Exception:  # blark's grammar is TwinCAT's: some IEC corners differ
        return False


def time_blark(parser, texts: dict[str, str]) -> float:
    start = clock()
    for text in texts.values():
        parser.parse(text, start="iec_source")
    return clock() - start


MEMORY_PROBE = """
import resource, sys, time
sys.path.insert(0, {root!r})
sys.path.insert(0, {bench!r})
from bench_parse import generated_pou
from st_runtime.parser import parse
texts, lines, n = {{}}, 0, 0
while lines < 5000:
    text = generated_pou(n)
    texts[f"g{{n}}.st"] = text
    lines += text.count("\\n")
    n += 1
start = time.process_time()
trees = [parse(t, name)[0] for name, t in texts.items()]
parsed = time.process_time() - start
checked = "no checker"
try:
    from st_runtime import native, stdlib
    from st_runtime.checker import check
    prelude, _ = parse(native.prelude_source(), "<builtin>")
    start = time.process_time()
    _, diagnostics = check([prelude] + trees, "iec")
    checked = f"{{time.process_time() - start:.3f}} s, {{len([d for d in diagnostics if d.is_error])}} errors"
except ImportError:
    pass
rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(f"{{lines}} {{parsed:.3f}} {{rss_mb:.1f}} {{checked}}")
"""


def measure_memory() -> str:
    code = MEMORY_PROBE.format(root=str(ROOT), bench=str(Path(__file__).parent))
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=600)
    if result.returncode != 0:
        return f"memory probe failed: {result.stderr.strip()[-300:]}"
    lines, parsed, rss, checked = result.stdout.split(maxsplit=3)
    verdict = "OK" if float(rss) < 150 else "ABOVE TARGET"
    return (f"load {lines} lines in a fresh process: parse {parsed} s, check {checked.strip()}; "
            f"peak RSS {rss} MB (target < 150 MB: {verdict})")


def main() -> int:
    options = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    options.add_argument("--min-lines", type=int, default=2500)
    options.add_argument("--rounds", type=int, default=5)
    args = options.parse_args()

    with tempfile.TemporaryDirectory(prefix="bench_parse_") as tmp:
        paths = build_corpus(Path(tmp), args.min_lines)
        texts = {p.name: p.read_text(encoding="utf-8") for p in paths}
    total_lines = sum(count_lines(t) for t in texts.values())
    print(f"corpus: {len(texts)} files, {total_lines} lines")

    # Warm the grammar (built once per process, its tables in the user cache, st_runtime/grammar_cache.py).
    start = clock()
    parse("PROGRAM P END_PROGRAM", "warm.st")
    print(f"our parser: grammar load {clock() - start:.3f} s (once per process)")

    ours, trees = time_ours(texts, args.rounds)
    print(f"our parser: {ours:.3f} s for {total_lines} lines -> {total_lines / ours:,.0f} lines/s")
    checked = time_check(trees)
    if checked is None:
        print("checker: not importable; parse figures only")
    else:
        seconds, errors = checked
        both = ours + seconds
        print(f"parse + check: {both:.3f} s -> {total_lines / both:,.0f} lines/s "
              f"(check alone {seconds:.3f} s; {errors} checker errors in the corpus)")

    parser = blark_parser()
    if parser is None:
        print("blark: not installed (pip install blark) -- comparison skipped")
    else:
        common = {name: text for name, text in texts.items() if blark_accepts(parser, text)}
        common_lines = sum(count_lines(t) for t in common.values())
        print(f"blark accepts {len(common)} of {len(texts)} files ({common_lines} lines); "
              "both parsers timed on those")
        theirs = time_blark(parser, common)
        ours_common, _ = time_ours(common, args.rounds)
        ratio = theirs / ours_common
        print(f"blark:      {theirs:.3f} s -> {common_lines / theirs:,.0f} lines/s")
        print(f"our parser: {ours_common:.3f} s -> {common_lines / ours_common:,.0f} lines/s")
        print(f"ratio: {ratio:,.0f}x blark's speed (target >= 100x: "
              f"{'OK' if ratio >= 100 else 'BELOW TARGET'})")

    print(measure_memory())
    return 0


if __name__ == "__main__":
    sys.exit(main())

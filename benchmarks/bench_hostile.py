"""Benchmark: the hostile inputs of issue 15, each in a fresh process, with its
time and peak memory.

    python benchmarks/bench_hostile.py

Every case is an ST file written to a temporary folder and given to `stgen
check` (and, where it passes, `stgen run`), as a user would. For each: the
exit status, the first diagnostic's code, CPU seconds and the peak resident
memory of the child (`resource.getrusage(RUSAGE_CHILDREN).ru_maxrss` read in
a wrapper process, so each case is measured alone). A `python -c pass` run
is the reference line. Target (issue 15): under 1 GB and 10 s each, and a
diagnostic or a clean run, never an internal error.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def program(body: str, decls: str = "x : DINT; r : LREAL;") -> str:
    return f"PROGRAM P\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n"


CASES = {
    "10,000 unary minus": program("x := " + "- " * 10_000 + "1;"),
    "10,000-long ** chain": program("r := " + " ** ".join(["1.0"] * 10_000) + ";"),
    "3,000 nested IF": program("IF x = 0 THEN\n" * 3_000 + "x := 1;\n" + "END_IF;\n" * 3_000),
    "100,000 ELSIF": program("IF x = 0 THEN x := 1;\n" + "".join(
        f"ELSIF x = {k} THEN x := {k};\n" for k in range(1, 100_001)) + "END_IF;"),
    "20,000 ELSIF (a file under the line limit)": program("IF x = 0 THEN x := 1;\n" + "".join(
        f"ELSIF x = {k} THEN x := {k};\n" for k in range(1, 20_001)) + "END_IF;"),
    "CASE of 100,000 labels": program("CASE x OF\n" + ", ".join(str(k) for k in range(100_000)) + ": x := 1;\nEND_CASE;"),
    "CASE of 1,500 clauses": program("CASE x OF\n" + "".join(f"{k}: x := {k};\n" for k in range(1_500)) + "END_CASE;"),
    "1,000,000 statements": program("x := 1;\n" * 1_000_000),
    "ARRAY[0..9999999] OF ARRAY[0..999] OF LREAL": program("x := 1;", "a : ARRAY[0..9999999] OF ARRAY[0..999] OF LREAL; x : DINT;"),
    "STRING[2000000000] with CONCAT": program("s := CONCAT(s, s);", "s : STRING[2000000000];"),
    "ARRAY[0..2**63-1] OF BOOL": program("x := 1;", "b : ARRAY[0..9223372036854775807] OF BOOL; x : DINT;"),
    "FB in STRUCT in FB": ("TYPE S : STRUCT f : F; END_STRUCT; END_TYPE\nFUNCTION_BLOCK F\nVAR_INPUT s : S; END_VAR\n"
                           "END_FUNCTION_BLOCK\n" + program("a();", "a : F;")),
    "WSTRING with a lone surrogate": program("w := w;", 'w : WSTRING := "a$D800b";'),
}

#: Runs `argv` as a child and prints its exit status, CPU seconds and peak RSS (KiB) as JSON.
WRAPPER = """
import json, resource, subprocess, sys
result = subprocess.run(sys.argv[1:], capture_output=True, text=True)
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
first = next((line for line in result.stderr.splitlines() if "error[" in line or "internal error" in line), "")
print(json.dumps({"code": result.returncode, "cpu": usage.ru_utime + usage.ru_stime,
                  "rss_kib": usage.ru_maxrss, "first": first}))
"""


def measure(argv: list[str]) -> dict:
    out = subprocess.run([sys.executable, "-c", WRAPPER, *argv], cwd=ROOT, capture_output=True, text=True)
    return json.loads(out.stdout)


def main() -> int:
    floor = measure([sys.executable, "-c", "pass"])
    print(f"{'case':<46}{'exit':>5}{'CPU s':>8}{'peak MB':>9}  diagnostic")
    print(f"{'python -c pass':<46}{floor['code']:>5}{floor['cpu']:>8.2f}{floor['rss_kib'] / 1024:>9.0f}")
    worst_cpu = worst_rss = 0.0
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in CASES.items():
            path = Path(tmp) / "case.st"
            path.write_text(text, encoding="utf-8")
            result = measure([sys.executable, "-m", "stgen", "check", str(path)])
            if result["code"] == 0:    # accepted: it must also run
                result = measure([sys.executable, "-m", "stgen", "run", str(path), "--program", "P"])
            code = result["first"].split("error[", 1)[1].split("]", 1)[0] if "error[" in result["first"] else (
                "internal error" if "internal error" in result["first"] else "-")
            print(f"{name:<46}{result['code']:>5}{result['cpu']:>8.2f}{result['rss_kib'] / 1024:>9.0f}  {code}")
            worst_cpu, worst_rss = max(worst_cpu, result["cpu"]), max(worst_rss, result["rss_kib"] / 1024)
            if code == "internal error" or result["cpu"] > 10 or result["rss_kib"] > 1024 * 1024:
                failures.append(name)
    print(f"worst: {worst_cpu:.2f} CPU s, {worst_rss:.0f} MB peak (targets 10 s, 1,024 MB);"
          f" {'all within' if not failures else 'NOT within: ' + ', '.join(failures)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

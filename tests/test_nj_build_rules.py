"""What Sysmac Studio builds (docs/nj501.md, first table): NJ rules 006-008 and
OMRON's pin names of the standard counters.

The rejected examples live in the reject corpus (`nj_fb_*`, `nj_case_label_*`,
`nj_initial_value_*`: an error under `--dialect nj`, checked by
test_checker_corpus.py); here the same files must give the matching warning
under `iec` (which allows them) and nothing else, and the accepted examples
must be clean under `nj`.  Counter values by hand from the counters' bodies
(IEC 61131-3 3rd ed. table 45; OMRON W502 CTD/CTUD pages).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from st_runtime.api import load
from st_runtime.dialects import DIALECTS, NJ_RULES
from st_runtime.loader import load_texts

TESTS = Path(__file__).parent
REJECT = TESTS / "corpus" / "reject"
ACCEPT = TESTS / "corpus" / "accept"
DIALECT_ST = TESTS / "st_dialects"

# rule -> (code under nj, code under iec)
CODES = {"006": ("E-NJ-006", "W-NJ-006"), "007": ("E-NJ-007", "W-NJ-007"),
         "008": ("E-NJ-008", "W-NJ-008")}
RULE_FILES = {
    "006": (["nj_fb_array_element_read", "nj_fb_array_element_write", "nj_fb_struct_member"],
            "nj_fb_variables_whole_and_scalar"),
    "007": (["nj_case_label_constant"], "nj_case_label_literals"),
    "008": (["nj_initial_value_constant"], "nj_initial_value_literals"),
}


def _load(path: Path, dialect: str):
    return load_texts({path.name: path.read_text(encoding="utf-8")}, dialect)


@pytest.mark.parametrize("rule", sorted(RULE_FILES))
def test_rejected_example_is_an_error_under_nj_and_a_warning_under_iec(rule):
    for stem in RULE_FILES[rule][0]:
        path = REJECT / f"{stem}.st"
        nj = _load(path, "nj")
        assert nj.program is None
        assert [d.code for d in nj.diagnostics] == [CODES[rule][0]], stem
        iec = _load(path, "iec")
        assert iec.program is not None, stem
        assert [(d.code, d.pos.line) for d in iec.diagnostics] == \
            [(CODES[rule][1], nj.diagnostics[0].pos.line)], stem


@pytest.mark.parametrize("rule", sorted(RULE_FILES))
def test_accepted_example_is_clean_under_nj(rule):
    result = _load(ACCEPT / f"{RULE_FILES[rule][1]}.st", "nj")
    assert result.program is not None
    assert result.diagnostics == []


def test_the_message_names_the_build_error_and_the_cure():
    result = _load(REJECT / "nj_fb_array_element_read.st", "nj")
    message = result.diagnostics[0].message
    assert "Cannot use an element of array or a member of structure" in message
    assert "copy 'Ik.CylinderPos' whole" in message
    (case,) = _load(REJECT / "nj_case_label_constant.st", "nj").diagnostics
    assert "write 1 (* STATE_RUN *)" in case.message      # STATE_RUN : INT := 1
    (init,) = _load(REJECT / "nj_initial_value_constant.st", "nj").diagnostics
    assert "write 0 (* STATE_IDLE *)" in init.message     # STATE_IDLE : INT := 0


def test_every_nj_rule_has_a_source_and_a_confidence():
    for rule in NJ_RULES.values():
        assert rule.source and rule.confidence in ("documented", "observed", "assumed")
    assert DIALECTS["nj"].errors == frozenset(NJ_RULES)
    assert DIALECTS["iec"].errors == frozenset()


# ------------------------------------------------------------- pin names

COUNTERS = {"nj": DIALECT_ST / "counters_omron.st", "iec": DIALECT_ST / "counters_iec.st"}
RESET_PIN = {"nj": "Reset", "iec": "R"}


@pytest.mark.parametrize("dialect", sorted(COUNTERS))
def test_counters_run_with_the_dialects_pin_names(dialect):
    plc = load([COUNTERS[dialect]], dialect=dialect).controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(2)
    # Scan 1: CU rises (CV 1), CTD loads PV = 5; scan 2: Reset/R of CTU and CTUD.
    assert (main["Up.CV"], main["Down.CV"], main["Both.CV"], main["Both.QD"]) == (0, 5, 0, True)
    assert main[f"Up.{RESET_PIN[dialect]}"] is True
    plc.run(1)
    # Scan 3: CU and CD rise again.
    assert (main["Up.CV"], main["Down.CV"], main["Both.CV"]) == (1, 4, 1)
    assert (main["Up.Q"], main["Down.Q"], main["Both.QU"]) == (False, False, False)
    assert plc.faults == []


@pytest.mark.parametrize("dialect, other", [("nj", "iec"), ("iec", "nj")])
def test_the_other_dialects_pin_names_are_refused_with_the_right_name(dialect, other):
    result = _load(COUNTERS[other], dialect)
    assert result.program is None
    codes = [(d.code, d.pos.line) for d in result.diagnostics]
    assert codes == [("E-PIN-001", 13), ("E-PIN-001", 14), ("E-PIN-001", 15), ("E-PIN-001", 15)] \
        if other == "iec" else [("E-PIN-001", 16), ("E-PIN-001", 17), ("E-PIN-001", 18),
                                ("E-PIN-001", 18)]
    first = result.diagnostics[0].message
    assert f"here the pin is '{RESET_PIN[dialect]}'" in first


def test_stgen_run_takes_omrons_pins_under_dialect_nj(capsys):
    from stgen.cli import main

    path = str(COUNTERS["nj"])
    assert main(["run", path, "--program", "Main", "--cycles", "3", "--dialect", "nj", "--json"]) == 0
    state = json.loads(capsys.readouterr().out)
    assert (state["Up"]["CV"], state["Up"]["Reset"], state["Down"]["CV"], state["Down"]["Load"]) \
        == (1, False, 4, False)
    assert main(["run", path, "--program", "Main", "--cycles", "3", "--json"]) == 1
    printed = capsys.readouterr()
    assert "E-PIN-001" in printed.out + printed.err

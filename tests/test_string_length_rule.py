"""STRING[n] counts the same way in the checker, the running program and ``--set``, per dialect (issue 9).

Before: the runtime counted characters and ``--set`` UTF-8 bytes, so ``--set``
refused a value the program itself could store. Now ``iec`` counts characters
(IEC 61131-3: a STRING of single-byte characters) and ``nj`` bytes of UTF-8
(OMRON sizes NJ strings in bytes; st_runtime.types.STRING_UNITS has the source).
'été' is 3 characters and 5 bytes ('é' is 2 bytes in UTF-8).
"""

from __future__ import annotations

import json

import pytest

from stgen.cli import main

PROGRAM = "PROGRAM Main\nVAR s : STRING[3]; t : STRING[3]; END_VAR\nt := 'été';\nEND_PROGRAM\n"


def _run(tmp_path, capsys, dialect, *sets):
    source = tmp_path / "main.st"
    source.write_text(PROGRAM, encoding="utf-8")
    args = ["run", str(source), "--program", "Main", "--dialect", dialect, "--json"]
    for item in sets:
        args += ["--set", item]
    code = main(args)
    out = capsys.readouterr()
    return code, (json.loads(out.out) if code == 0 else None), out.err


@pytest.mark.parametrize("dialect, stored", [("iec", "été"), ("nj", "ét")])
def test_set_accepts_exactly_what_the_program_itself_stores(tmp_path, capsys, dialect, stored):
    code, values, _ = _run(tmp_path, capsys, dialect)
    assert code == 0 and values["t"] == stored  # nj: 3 bytes hold 'é' and 't', not half of the second 'é'
    code, values, err = _run(tmp_path, capsys, dialect, f"s={json.dumps(stored)}")
    assert code == 0, err
    assert values["s"] == stored


def test_nj_refuses_a_value_of_more_bytes_and_says_bytes(tmp_path, capsys):
    code, _, err = _run(tmp_path, capsys, "nj", 's="été"')
    assert code == 2 and "--set s: string of 5 bytes exceeds STRING[3]" in err


@pytest.mark.parametrize("dialect, warning", [("iec", None), ("nj", "string of 5 bytes is truncated to STRING[3]")])
def test_the_checker_counts_the_same_way(tmp_path, capsys, dialect, warning):
    source = tmp_path / "main.st"
    source.write_text(PROGRAM, encoding="utf-8")
    assert main(["check", "--dialect", dialect, str(source)]) == 0
    out = capsys.readouterr()
    if warning is None:
        assert "W-TYPE-001" not in out.err
    else:
        assert f"warning[W-TYPE-001]: assignment: {warning}" in out.err

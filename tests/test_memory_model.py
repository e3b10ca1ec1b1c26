"""The checker's memory model (st_runtime/checker/memory.py): bytes per
variable from its type by OMRON's allocation table (W501 appendix, W506
A-47), and a diagnostic where a variable, a POU instance or the project needs
more than the limit. Expected sizes are worked out by hand from that table."""

from __future__ import annotations

import pytest

from st_runtime import types as T
from st_runtime.api import LoadError, load_text
from st_runtime.checker.memory import DEFAULT_LIMIT, MemoryModel
from stgen.cli import main


@pytest.mark.parametrize("t, expected", [
    (T.BOOL, (2, 2)), (T.SINT, (1, 1)), (T.BYTE, (1, 1)), (T.INT, (2, 2)), (T.WORD, (2, 2)),
    (T.DINT, (4, 4)), (T.REAL, (4, 4)), (T.LINT, (8, 8)), (T.LREAL, (8, 8)), (T.TIME, (8, 8)),
    (T.DT, (8, 8)),
    (T.StringType(10), (11, 1)),                                   # STRING[N+1] for N characters
    (T.StringType(10, wide=True), (22, 2)),                        # assumed: 2 bytes a character
    (T.ArrayType(((1, 5),), T.BOOL), (2, 2)),                      # BOOL arrays: 2 bytes per 16
    (T.ArrayType(((0, 18),), T.BOOL), (4, 2)),                     # 19 elements: 4 bytes
    (T.ArrayType(((1, 5),), T.INT), (10, 2)),
    (T.ArrayType(((0, 9), (1, 3)), T.LREAL), (240, 8)),
])
def test_layout_by_omrons_table(t, expected):
    assert MemoryModel().layout(t) == expected


def test_structure_members_at_multiples_of_their_alignment():
    # BOOL at 0 (2 bytes), LREAL at 8, INT at 16 (2 bytes): 18, rounded up to 8 -> 24.
    s = T.StructType("S", {"A": ("a", T.BOOL), "B": ("b", T.LREAL), "C": ("c", T.INT)})
    assert MemoryModel().layout(s) == (24, 8)
    # DWORD, WORD, DWORD (W501's example): 4 + 2 (+2 unused) + 4 = 12.
    s2 = T.StructType("S2", {"A": ("a", T.DWORD), "B": ("b", T.WORD), "C": ("c", T.DWORD)})
    assert MemoryModel().layout(s2) == (12, 4)


def refused(text: str, **kwargs) -> list[tuple[str, int]]:
    with pytest.raises(LoadError) as info:
        load_text(text, "m.st", **kwargs)
    return [(d.code, d.pos.line, d.message) for d in info.value.diagnostics]


def test_the_issues_huge_declarations_are_refused_by_the_checker():
    text = ("FUNCTION_BLOCK Big\nVAR m : ARRAY[1..100000] OF LREAL; END_VAR\nEND_FUNCTION_BLOCK\n"
            "PROGRAM P\nVAR\n"
            "  a : ARRAY[0..9999999] OF ARRAY[0..999] OF LREAL;\n"     # line 6: 8e10 bytes
            "  s : STRING[2000000000];\n"                              # line 7
            "  b : ARRAY[0..9223372036854775807] OF BOOL;\n"           # line 8
            "  f : ARRAY[1..1000] OF Big;\n"                           # line 9: 1000 x 800,000
            "END_VAR\ns := CONCAT(s, s);\nEND_PROGRAM\n")
    found = refused(text)
    assert [(code, line) for code, line, _ in found] == [
        ("E-LIMIT-008", 6), ("E-LIMIT-008", 7), ("E-LIMIT-008", 8), ("E-LIMIT-008", 9)]
    assert "P.a needs 80,000,000,000 bytes" in found[0][2]
    assert "P.s needs 2,000,000,001 bytes" in found[1][2]
    assert "P.f needs 800,000,000 bytes" in found[3][2]
    assert f"memory limit of {DEFAULT_LIMIT:,} bytes" in found[0][2]


def test_a_pou_instance_and_the_project_have_limits_too():
    # Each variable fits in 64 KiB, the instance (3 x 40,000) does not.
    text = ("PROGRAM P\nVAR a, b, c : ARRAY[1..5000] OF LREAL; END_VAR\nEND_PROGRAM\n")
    assert [(c, line) for c, line, _ in refused(text, memory_limit=65536)] == [("E-LIMIT-009", 1)]
    # Two programs of 40,000 bytes each: 80,000 in all.
    text = ("PROGRAM P\nVAR a : ARRAY[1..5000] OF LREAL; END_VAR\nEND_PROGRAM\n"
            "PROGRAM Q\nVAR a : ARRAY[1..5000] OF LREAL; END_VAR\nEND_PROGRAM\n")
    [(code, _, message)] = refused(text, memory_limit=65536)
    assert code == "E-LIMIT-010" and "80,000 bytes" in message
    load_text(text, "m.st", memory_limit=80_000)


def test_nj_string_limit():
    ok = "PROGRAM P\nVAR s : STRING[1986]; END_VAR\nEND_PROGRAM\n"
    load_text(ok, "m.st", dialect="nj")
    found = refused(ok.replace("1986", "1987"), dialect="nj")
    assert [c for c, _, _ in found] == ["E-LIMIT-011"] and "STRING[1986]" in found[0][2]
    load_text(ok.replace("1986", "1987"), "m.st")              # IEC: no such limit


def test_check_memory_limit_option(tmp_path, capsys):
    path = tmp_path / "m.st"
    path.write_text("PROGRAM P\nVAR a : ARRAY[1..1000] OF LREAL; END_VAR\nEND_PROGRAM\n")
    assert main(["check", str(path)]) == 0
    assert main(["check", "--memory-limit", "4k", str(path)]) == 1
    assert "P.a needs 8,000 bytes (ARRAY[1..1000] OF LREAL), above the memory limit of 4,096 bytes" \
        in capsys.readouterr().err
    with pytest.raises(SystemExit) as info:             # argparse's usage error, one line
        main(["check", "--memory-limit", "lots", str(path)])
    assert info.value.code == 2 and "not a number of bytes" in capsys.readouterr().err

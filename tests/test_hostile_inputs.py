"""Hostile input, one test per class (issue 15): each is a diagnostic with
file, line and column, or a one-line usage error naming the option (exit 2),
never an internal error or a traceback.

Classes: self-containment through a mix of FB and STRUCT; a WSTRING literal
with a lone UTF-16 surrogate; `--set` paths that are no member, no index or
100,000 characters; `--set` JSON nested 60,000 deep, with 100,000 digits or a
lone surrogate; the same paths in `--watch`.
"""

from __future__ import annotations

import pytest

from st_runtime.api import LoadError, load_text
from stgen.cli import main

MAIN = """
PROGRAM P
VAR a : ARRAY[0..3] OF INT; s : STRING; w : WSTRING; x : DINT; t : TON; END_VAR
x := x;
END_PROGRAM
"""


@pytest.fixture()
def main_st(tmp_path):
    path = tmp_path / "main.st"
    path.write_text(MAIN)
    return path


def codes(text: str) -> list[tuple[str, int]]:
    with pytest.raises(LoadError) as info:
        load_text(text, "h.st")
    return [(d.code, d.pos.line) for d in info.value.diagnostics]


# ------------------------------------------------------------ types that contain themselves

def test_fb_holding_itself_through_a_struct_is_refused():
    text = ("TYPE S : STRUCT f : F; END_STRUCT; END_TYPE\n"
            "FUNCTION_BLOCK F\nVAR_INPUT s : S; END_VAR\nEND_FUNCTION_BLOCK\n"
            "PROGRAM P\nVAR a : F; END_VAR\na();\nEND_PROGRAM\n")
    assert codes(text) == [("E-REC-001", 3)]


def test_fb_holding_itself_through_arrays_of_structs_and_another_fb_is_refused():
    text = ("TYPE S : STRUCT a : ARRAY[1..2] OF T2; END_STRUCT; T2 : STRUCT g : G; END_STRUCT; END_TYPE\n"
            "FUNCTION_BLOCK G\nVAR x : F2; END_VAR\nEND_FUNCTION_BLOCK\n"
            "FUNCTION_BLOCK F2\nVAR_OUTPUT o : S; END_VAR\nEND_FUNCTION_BLOCK\n"
            "PROGRAM P\nVAR a : F2; END_VAR\na();\nEND_PROGRAM\n")
    with pytest.raises(LoadError) as info:
        load_text(text, "h.st")
    [diagnostic] = info.value.diagnostics
    assert diagnostic.code == "E-REC-001"
    assert "G declares an instance of F2, F2 declares a S holding an instance of G" in diagnostic.message


def test_a_struct_of_fbs_without_a_cycle_still_loads():
    text = ("TYPE S : STRUCT t : TON; END_STRUCT; END_TYPE\n"
            "FUNCTION_BLOCK F\nVAR_INPUT s : S; END_VAR\nEND_FUNCTION_BLOCK\n"
            "PROGRAM P\nVAR a : F; END_VAR\na();\nEND_PROGRAM\n")
    load_text(text, "h.st")


# ------------------------------------------------------------ WSTRING surrogates

def test_lone_surrogate_in_a_wstring_literal_is_a_diagnostic():
    text = 'PROGRAM P\nVAR w : WSTRING := "a$D800b"; END_VAR\nw := w;\nEND_PROGRAM\n'
    with pytest.raises(LoadError) as info:
        load_text(text, "h.st")
    [diagnostic] = info.value.diagnostics
    assert (diagnostic.code, diagnostic.pos.line, diagnostic.pos.col) == ("E-PARSE-009", 2, 20)
    assert "'$D800' is half of a UTF-16 surrogate pair" in diagnostic.message


def test_a_surrogate_pair_is_one_character():
    # U+1F600 is D83D DE00 in UTF-16.
    plc = load_text('PROGRAM P\nVAR w : WSTRING := "a$D83D$DE00b"; n : INT; END_VAR\nn := LEN(w);\nEND_PROGRAM\n'
                    ).controller()
    main_ = plc.add_program("P")
    plc.run(1)
    assert main_["w"] == "a\U0001F600b" and main_["n"] == 3


# ------------------------------------------------------------ --set and --watch

@pytest.mark.parametrize("item, words", [
    ("a.__class__=1", "--set a.__class__: '__class__' is no member"),
    ("x.y=1", "--set x.y: 'y' is no member"),
    ("a[0x1]=1", "array indices must be integer literals"),
    ("a[]=1", "array indices must be integer literals"),
    ("a=" + "[" * 60_000, "--set a: nested more than 64 levels deep"),
    ("a=" + "[" * 70 + "]" * 70, "--set a: nested more than 64 levels deep"),
    ("x=" + "1" * 100_000, "--set x: a number of 100,000 digits is beyond any ST number"),
    ('s="\\ud800x"', "--set s: the string holds a lone UTF-16 surrogate (\\ud800)"),
    ('w="\\udc00"', "--set w: the string holds a lone UTF-16 surrogate (\\udc00)"),
    ("a[" + "1" * 100_000 + "]=1", "--set 'a[1111"),
])
def test_hostile_set_is_one_line_usage_error(main_st, capsys, item, words):
    code = main(["run", str(main_st), "--program", "P", "--set", item])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("stgen run: error: --set") and words in err
    assert len(err.splitlines()) == 1 and len(err) < 300
    assert "internal error" not in err and "sys.set_int_max_str_digits" not in err


@pytest.mark.parametrize("path, words", [
    ("a.__class__", "a has no member '__class__'"),
    ("a[0x1]", "array indices must be integer literals"),
    ("a" + "[" * 60_000, "--watch: 'a[[["),
    ("a[" + "1" * 100_000 + "]", "--watch: 'a[111"),
])
def test_hostile_watch_is_one_line_usage_error(main_st, tmp_path, capsys, path, words):
    code = main(["run", str(main_st), "--program", "P", "--trace", str(tmp_path / "t.csv"), "--watch", path])
    err = capsys.readouterr().err
    assert code == 2 and words in err
    assert len(err.splitlines()) == 1 and len(err) < 300

"""ST text is data: no identifier, literal or file name can run Python.

Identifiers that are Python keywords, builtins or runtime names, and strings
that look like Python, must compile to code that treats them as data.
"""

from __future__ import annotations

import builtins
import io
import tokenize

import pytest

from st_runtime.api import load_sources, load_text

HOSTILE_IDENTIFIERS = ["def", "class", "lambda", "None", "self", "import", "print", "len",
                       "range", "float", "exec", "eval", "open", "globals", "G", "ctx", "e",
                       "t1", "f32", "FAULTS", "v_x", "return_", "yield", "await", "async"]


@pytest.mark.parametrize("name", HOSTILE_IDENTIFIERS)
def test_hostile_identifier_as_variable_and_fb_member(name):
    src = f"""
    FUNCTION_BLOCK Box
    VAR_INPUT {name} : INT; END_VAR
    VAR_OUTPUT o : INT; END_VAR
    o := {name} * 2;
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR {name} : INT := 20; b : Box; r : INT; END_VAR
    {name} := {name} + 1;
    b({name} := {name});
    r := b.o + b.{name};
    END_PROGRAM
    """
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main[name] == 21
    assert main["r"] == 63


def test_pou_and_type_names_that_are_python_names():
    src = """
    TYPE lambda : STRUCT None : INT; self : LREAL; END_STRUCT; END_TYPE
    TYPE class : (def, pass := 5); END_TYPE
    FUNCTION print : INT
    VAR_INPUT exec : INT; END_VAR
    print := exec + 1;
    END_FUNCTION
    PROGRAM Main
    VAR x : lambda; k : class := pass; y : INT; END_VAR
    x.None := print(41); x.self := 0.5;
    IF k = pass THEN y := 1; END_IF;
    END_PROGRAM
    """
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["x"] == {"None": 42, "self": 0.5}
    assert main["y"] == 1


HOSTILE_STRINGS = [
    "'); import os; ('",
    '"); __import__("os").system("false"); ("',
    "\\' + str(1/0) + \\'",
    "back\\slash\\n",
    "{__import__}",
    "%s %r %d",
    "line\nbreak",
]


def st_string(text: str) -> str:
    """Encode text as an ST string literal with $ escapes."""
    out = []
    for ch in text:
        if ch == "'":
            out.append("$'")
        elif ch == "$":
            out.append("$$")
        elif ch == "\n":
            out.append("$N")
        else:
            out.append(ch)
    return "'" + "".join(out) + "'"


@pytest.mark.parametrize("text", HOSTILE_STRINGS)
def test_strings_that_look_like_python_are_just_strings(text):
    literal = st_string(text)
    src = f"""
    PROGRAM Main
    VAR s : STRING[200] := {literal}; t : STRING[200]; n : INT; END_VAR
    t := {literal};
    n := LEN(t);
    END_PROGRAM
    """
    project = load_text(src)
    plc = project.controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["s"] == text and main["t"] == text
    assert main["n"] == len(text)
    # The text reaches the generated Python only as a repr literal.
    source = project.compiled.python_sources["MAIN"]
    assert repr(text) in source


def test_dollar_escapes_decode_to_their_characters():
    src = "PROGRAM Main\nVAR s : STRING; END_VAR\ns := 'a$Nb$$c$'d$Te$R$L';\nEND_PROGRAM\n"
    plc = load_text(src).controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main["s"] == "a\nb$c'd\te\r\n"


def test_hostile_file_name_is_only_a_literal():
    path = "x'); import os; os.system('false'); ('.st"
    src = "PROGRAM Main\nVAR a : ARRAY[1..2] OF INT; i : INT := 3; END_VAR\na[i] := 1;\nEND_PROGRAM\n"
    project = load_sources({path: src})
    plc = project.controller()
    plc.add_program("Main")
    plc.run(1)
    assert plc.faults[0].file == path and plc.faults[0].line == 3


def test_generated_source_uses_only_mangled_names():
    src = """
    PROGRAM Main
    VAR lambda : INT; self : BOOL; None : LREAL; END_VAR
    lambda := lambda + 1; self := NOT self; None := None + 1.0;
    END_PROGRAM
    """
    source = load_text(src).compiled.python_sources["MAIN"]
    compile(source, "<check>", "exec")
    tokens = list(tokenize.generate_tokens(io.StringIO(source).readline))
    # Names, not attributes after a dot (`_ctx.fault`, `fb.execute`).
    words = {tok.string for prev, tok in zip([None] + tokens, tokens)
             if tok.type == tokenize.NAME and not (prev and prev.string == ".")}
    python_words = {"def", "try", "except", "as", "finally", "self", "if", "else", "for", "in",
                    "return", "not", "and", "or", "True", "False", "None", "pass", "while", "break",
                    "continue", "elif"}
    for word in words - python_words:
        assert word.startswith(("v_", "_")), word
    attributes = {tok.string for prev, tok in zip([None] + tokens, tokens)
                  if tok.type == tokenize.NAME and prev and prev.string == "."}
    assert {"v_LAMBDA", "v_SELF", "v_NONE"} <= words | attributes


def test_generated_code_has_no_access_to_python_builtins():
    project = load_text("PROGRAM Main\nVAR x : INT; END_VAR\nx := 1;\nEND_PROGRAM\n")
    allowed = project.compiled.namespace["__builtins__"]
    assert "__import__" not in allowed and "open" not in allowed and "eval" not in allowed
    assert set(allowed) <= set(dir(builtins))


# -------------------------------------------------------------- property test

from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

from st_runtime.api import LoadError  # noqa: E402

IDENT = st.from_regex(r"[A-Za-z][A-Za-z0-9]{0,12}", fullmatch=True)
TEXT = st.text(alphabet=st.characters(min_codepoint=32, max_codepoint=126), max_size=40)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=IDENT, text=TEXT)
def test_any_identifier_and_printable_string_is_data(name, text):
    src = (f"PROGRAM Main\nVAR {name} : STRING[60] := {st_string(text)}; n : INT; END_VAR\n"
           f"n := LEN({name});\nEND_PROGRAM\n")
    try:
        project = load_text(src)
    except LoadError as exc:
        # A keyword or a reserved name is refused with a diagnostic, never run.
        assert all(d.code.startswith(("E-", "W-")) for d in exc.diagnostics)
        return
    plc = project.controller()
    main = plc.add_program("Main")
    plc.run(1)
    assert main[name] == text and main["n"] == len(text)

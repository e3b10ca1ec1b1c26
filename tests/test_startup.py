"""Start-up of `stgen check`: what it imports and the caches it keeps (issue 15).

Not timed (benchmarks/bench_startup.py measures the time); these tests hold
what the speed rests on: `stgen check` imports nothing it has no use for,
and the caches in the user cache directory (`st_runtime/user_cache.py`) are
never stale, never read from a place someone else can write, and never run
code from a forged entry.
"""

from __future__ import annotations

import os
import pickle
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from st_runtime import grammar_cache, parser, prelude, user_cache

ROOT = Path(__file__).resolve().parent.parent
SMALL = "PROGRAM Main\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n"

#: Modules `stgen check` of an ST file has no use for.
NOT_FOR_CHECK = ("numpy", "jinja2", "matplotlib", "lxml", "stgen.render", "stgen.reference",
                 "st_runtime.compiler", "st_runtime.controller", "st_runtime.testing.runner")


def _run(code: str, cache: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "ST_RUNTIME_CACHE_DIR": str(cache)}
    return subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                          env=env, timeout=300)


def _check_and_list_modules(path: Path, cache: Path) -> tuple[int, list[str]]:
    probe = ("import sys, runpy\nsys.argv = ['stgen', 'check', %r]\ncode = 0\n"
             "try:\n    runpy.run_module('stgen', run_name='__main__')\n"
             "except SystemExit as exit:\n    code = exit.code\n"
             "print('EXIT', code)\n"
             "print('LOADED', ' '.join(m for m in %r if m in sys.modules))") % (str(path), NOT_FOR_CHECK)
    result = _run(probe, cache)
    lines = result.stdout.splitlines()
    code = int(next(line for line in lines if line.startswith("EXIT")).split()[1])
    loaded = next(line for line in lines if line.startswith("LOADED")).split()[1:]
    return code, loaded


def test_check_imports_neither_numpy_nor_jinja2_nor_the_runtime(tmp_path):
    source = tmp_path / "small.st"
    source.write_text(SMALL)
    for _ in range(2):   # cold cache, then warm: the same modules either way
        code, loaded = _check_and_list_modules(source, tmp_path / "cache")
        assert code == 0
        assert loaded == []


def test_cache_entries_are_private_and_a_warm_start_gives_the_same_diagnostics(tmp_path):
    source = tmp_path / "bad.st"
    source.write_text("PROGRAM Main\nVAR x : INT; END_VAR\nx := y;\nEND_PROGRAM\n")
    cache = tmp_path / "cache"
    runs = [subprocess.run([sys.executable, "-m", "stgen", "check", str(source)], cwd=ROOT,
                           capture_output=True, text=True, timeout=300,
                           env={**os.environ, "ST_RUNTIME_CACHE_DIR": str(cache)}) for _ in range(2)]
    assert [r.returncode for r in runs] == [1, 1]
    assert runs[0].stderr == runs[1].stderr
    assert f"{source}:3:6" in runs[0].stderr
    assert stat.S_IMODE(cache.stat().st_mode) == 0o700
    names = sorted(p.name for p in cache.iterdir())
    assert [n.split("-")[0] for n in names] == ["lark", "prelude"]
    for entry in cache.iterdir():
        assert stat.S_IMODE(entry.stat().st_mode) == 0o600


# ------------------------------------------------------------------ user_cache


def test_restricted_reader_refuses_any_global_and_runs_nothing(tmp_path):
    marker = tmp_path / "ran"

    class Payload:
        def __reduce__(self):
            return (os.mkdir, (str(marker),))

    with pytest.raises(pickle.UnpicklingError, match="refused global"):
        user_cache.loads(pickle.dumps(Payload()))
    assert not marker.exists()
    assert user_cache.loads(pickle.dumps({"a": [1, "b", (2.5, None)]})) == {"a": [1, "b", (2.5, None)]}


def test_no_cache_dir_in_a_place_others_can_write(tmp_path, monkeypatch):
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o777)
    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", str(shared))
    assert user_cache.directory() is None
    assert user_cache.write("x", b"data") is False
    assert list(shared.iterdir()) == []


def test_an_unusable_cache_location_means_no_cache_not_an_error(tmp_path, monkeypatch):
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", str(blocker / "cache"))
    assert user_cache.directory() is None
    assert user_cache.read("x") is None
    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", "")   # empty: the cache turned off
    assert user_cache.directory() is None
    monkeypatch.setattr(prelude, "_cache", {})
    text, parsed, diagnostics = prelude.prelude_file("iec")
    assert parsed is not None and diagnostics == []


def test_an_entry_that_is_a_symbolic_link_is_not_followed(tmp_path, monkeypatch):
    cache = tmp_path / "cache"
    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", str(cache))
    assert user_cache.directory() == str(cache)
    target = tmp_path / "elsewhere"
    target.write_bytes(b"secret")
    (cache / "entry").symlink_to(target)
    assert user_cache.read("entry") is None


# ------------------------------------------------------------------ the prelude


def _fresh_prelude(monkeypatch):
    monkeypatch.setattr(prelude, "_cache", {})
    return prelude.prelude_file("iec")


def test_the_cached_prelude_is_the_parsed_prelude(tmp_path, monkeypatch):
    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", str(tmp_path))
    text, first, _ = _fresh_prelude(monkeypatch)
    assert any(p.name.startswith("prelude-") for p in tmp_path.iterdir())
    _, second, _ = _fresh_prelude(monkeypatch)          # read from the entry
    reparsed, diagnostics = parser.parse(text, "<builtin>")
    assert diagnostics == []
    assert second == reparsed
    assert len(second.items) > 10
    # positions too (equality skips them)
    assert [item.pos for item in second.items] == [item.pos for item in reparsed.items]


def test_a_forged_prelude_entry_is_refused_and_parsed_again(tmp_path, monkeypatch):
    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", str(tmp_path))
    text, expected, _ = _fresh_prelude(monkeypatch)
    entry = tmp_path / prelude._entry_name(text)
    marker = tmp_path / "ran"

    class Payload:
        def __reduce__(self):
            return (os.mkdir, (str(marker),))

    for forged in (pickle.dumps(Payload()), b"not a pickle", pickle.dumps([1, 2])):
        entry.write_bytes(forged)
        _, parsed, diagnostics = _fresh_prelude(monkeypatch)
        assert parsed == expected and diagnostics == []
        assert not marker.exists()


def test_the_prelude_entry_changes_with_what_decides_the_ast(monkeypatch):
    text = prelude.prelude_text("iec")
    name = prelude._entry_name(text)
    assert prelude._entry_name(text + "\n") != name
    assert prelude._entry_name(prelude.prelude_text("nj")) != name
    import lark
    monkeypatch.setattr(lark, "__version__", "0.0.0")
    assert prelude._entry_name(text) != name


def test_every_module_the_ast_builder_imports_is_in_the_prelude_key():
    """A change to a file the parser's output depends on must change the key."""
    import ast as python_ast

    folder = ROOT / "st_runtime"
    keyed = {name.removesuffix(".py") for name in prelude.PARSER_FILES}
    for module in ("parser", "ast_builder", "ast", "literals", "diagnostics", "grammar_cache"):
        tree = python_ast.parse((folder / f"{module}.py").read_text())
        for node in python_ast.walk(tree):
            if isinstance(node, python_ast.ImportFrom) and node.level == 1:
                names = [node.module] if node.module else [a.name for a in node.names]
                for name in names:
                    if name == "recovery":
                        continue   # only after a failed parse, and such a prelude is not stored
                    assert name in keyed, f"{module}.py imports .{name}, not in PARSER_FILES"
    assert "grammar.lark" in prelude.PARSER_FILES


# ------------------------------------------------------------------ the grammar


def test_the_grammar_entry_changes_with_grammar_options_and_lark_version(monkeypatch):
    options = {"parser": "lalr", "start": ["start"]}
    key = grammar_cache._key("a: 'x'", options)
    assert grammar_cache._key("a: 'y'", options) != key
    assert grammar_cache._key("a: 'x'", {**options, "start": ["a"]}) != key
    import lark
    monkeypatch.setattr(lark, "__version__", "0.0.0")
    assert grammar_cache._key("a: 'x'", options) != key


def test_a_damaged_grammar_entry_is_rebuilt(tmp_path, monkeypatch):
    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", str(tmp_path))
    grammar, options = "start: WORD\nWORD: /[a-z]+/\n", {"parser": "lalr", "lexer": "contextual"}
    name = f"lark-{grammar_cache._key(grammar, options)}.pickle"
    (tmp_path / name).write_bytes(b"\x80\x05damaged")
    built = grammar_cache.cached_lark(grammar, options, {})
    assert built.parse("abc").children[0] == "abc"
    loaded = grammar_cache.cached_lark(grammar, options, {})   # from the rewritten entry
    assert loaded.parse("xyz").children[0] == "xyz"


def test_lexers_made_on_demand_parse_as_lark_own_contextual_lexer(monkeypatch):
    """The same ASTs and diagnostics with Lark's ContextualLexer (every keyword
    alternative in every state) as with LazyContextualLexer (made per state on
    demand, without the keyword alternatives IDENT always shadows)."""
    from lark.lexer import ContextualLexer

    corpus = sorted((ROOT / "tests" / "corpus").glob("*/*.st")) + sorted((ROOT / "generated" / "iec").glob("*.st"))
    texts = {str(path): path.read_text() for path in corpus}
    texts["bad.st"] = "PROGRAM P\nVAR x : INT; END_VAR\nx := 1 +;\nIF x THEN\nEND_PROGRAM\n"
    texts["keywords.st"] = ("PROGRAM P\nVAR ifx : INT; end_ifx : BOOL; t : TIME := t#5s; END_VAR\n"
                            "if ifx > 0 THEN end_ifx := TRUE; ElsIf ifx < 0 then ifx := INT#3; END_if;\n"
                            "END_PROGRAM\n")
    texts["keyword_as_name.st"] = "PROGRAM P\nVAR if : INT; END_VAR\nEND_PROGRAM\n"
    lazy = {path: parser.parse(text, path) for path, text in texts.items()}

    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", "")
    monkeypatch.setattr(grammar_cache, "LazyContextualLexer", ContextualLexer)
    monkeypatch.setattr(parser, "_grammar", None)
    eager = {path: parser.parse(text, path) for path, text in texts.items()}
    assert parser.grammar().lark.parser.lexer.lexer.__class__ is ContextualLexer
    assert eager == lazy


# ------------------------------------------------------------------ load path


def test_loads_that_share_generated_code_keep_their_own_behaviour():
    """The compiler reuses the code compiled for an identical generated source
    (the prelude's initializers): a different body is never given another's."""
    from st_runtime.api import load_text
    from st_runtime.compiler import _CODE

    def f_of(body: str):
        return load_text(f"FUNCTION F : INT\nVAR_INPUT a : INT; END_VAR\n{body}\nEND_FUNCTION\n")

    plus, times = f_of("F := a + 1;"), f_of("F := a * 3;")
    assert plus.call("F", {"a": 5})["outputs"]["return"] == 6
    assert times.call("F", {"a": 5})["outputs"]["return"] == 15
    again = f_of("F := a + 1;")
    assert again.call("F", {"a": 7})["outputs"]["return"] == 8
    assert len(_CODE) > 0


def test_a_read_only_home_falls_back_to_a_private_folder_in_the_temp_dir(tmp_path, monkeypatch):
    if not hasattr(os, "getuid"):
        pytest.skip("POSIX only")
    blocker = tmp_path / "home_is_a_file"
    blocker.write_text("")
    monkeypatch.delenv("ST_RUNTIME_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))
    fallback = tmp_path / f"st_runtime-{os.getuid()}"
    assert user_cache.directory() == str(fallback)
    assert stat.S_IMODE(fallback.stat().st_mode) == 0o700
    fallback.rmdir()
    fallback.symlink_to(tmp_path)                 # planted by someone: not followed
    assert user_cache.directory() is None


def test_the_parse_table_read_from_the_cache_is_lark_s_own_reading(tmp_path, monkeypatch):
    """grammar_cache._parse_table makes from a cache entry the table Lark's
    IntParseTable.deserialize makes of it: the same states, in order, each with
    the same terminals and rules in order and the same actions on the same
    rule objects."""
    import io

    from lark.grammar import Rule
    from lark.lexer import TerminalDef
    from lark.parsers.lalr_analysis import IntParseTable, Reduce
    from lark.utils import SerializeMemoizer

    monkeypatch.setenv("ST_RUNTIME_CACHE_DIR", str(tmp_path))
    built = parser._Grammar().lark            # a fresh build stores the entry
    buffer = io.BytesIO()
    built.save(buffer, exclude_options=("transformer", "postlex", "lexer_callbacks", "_plugins"))
    stored = pickle.loads(buffer.getvalue())
    data, memo_data = stored["data"]["parser"]["parser"], stored["memo"]
    memo = SerializeMemoizer.deserialize(memo_data, {"Rule": Rule, "TerminalDef": TerminalDef}, {})
    ours, larks = grammar_cache._parse_table(data, memo), IntParseTable.deserialize(data, memo)
    assert len(ours.states) > 500 and list(ours.states) == list(larks.states)
    for state, actions in larks.states.items():
        assert list(ours.states[state].items()) == list(actions.items())
        assert all(ours.states[state][kind][1] is rule for kind, (action, rule) in actions.items()
                   if action is Reduce)
    assert (ours.start_states, ours.end_states) == (larks.start_states, larks.end_states)
    loaded = parser._Grammar().lark            # read back from the entry
    assert type(loaded.parser.parser) is grammar_cache.CachedLalrParser
    assert list(loaded.parser.parser._parse_table.states) == list(larks.states)

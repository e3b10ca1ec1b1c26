"""The registry of equivalent mutants (tools/mutation_registry.py): matching, stale entries, scores.

Pure functions on hand-made run results: no mutmut run.
"""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tools"))
import mutation_registry as registry  # noqa: E402

NAME = "st_runtime.motion.axis.xǁAxisǁ_set_period__mutmut_3"

# as `mutmut show` prints it: file header, hunk line, context, then the change
SHOWN = """--- st_runtime/motion/axis.py
+++ st_runtime/motion/axis.py
@@ -1,5 +1,5 @@
 def _set_period(self, dt):
-    self._dt = dt
+    self._dt = None
     self._max_step = self.vmax * dt"""

CHANGED = "-    self._dt = dt\n+    self._dt = None"


def entry(mutant=NAME, diff=CHANGED, module="motion", reason="read only as a cache key"):
    return registry.Entry(module, mutant, diff, reason)


def entries(*items):
    return {(e.module, e.mutant): e for e in items}


def test_changed_lines_keep_only_the_change_not_the_header_hunk_or_context():
    assert registry.changed_lines(SHOWN) == CHANGED
    # a removed line whose text starts with "--" is a change, not a header
    assert registry.changed_lines("--- a\n+++ a\n@@ -1 +1 @@\n---x\n+--y") == "---x\n+--y"


def test_changed_lines_ignore_where_the_function_moved():
    moved = SHOWN.replace("@@ -1,5 +1,5 @@", "@@ -40,5 +40,5 @@")
    assert registry.changed_lines(moved) == registry.changed_lines(SHOWN)


def test_an_entry_written_is_read_back_the_same(tmp_path):
    odd = entry(mutant="st_runtime.values.x_f__mutmut_1", module="values",
                diff="-    s = '''a'''\n+    s = \"b\"", reason='a "quoted" reason')
    path = tmp_path / "eq.toml"
    path.write_text(registry.entry_toml(entry(diff=SHOWN)) + registry.entry_toml(odd))
    assert registry.load(path) == entries(entry(), odd)


def test_a_missing_registry_lists_nothing(tmp_path):
    assert registry.load(tmp_path / "none.toml") == {}


def test_an_entry_listed_twice_or_without_a_reason_is_refused(tmp_path):
    path = tmp_path / "eq.toml"
    path.write_text(registry.entry_toml(entry()) * 2)
    with pytest.raises(ValueError, match="listed twice"):
        registry.load(path)
    path.write_text(registry.entry_toml(entry()).replace('reason = "read only as a cache key"', ""))
    with pytest.raises(ValueError, match="has no reason"):
        registry.load(path)


def test_every_entry_of_the_repositorys_registry_names_a_module_a_change_and_a_reason():
    import mutation

    for (module, name), e in registry.load().items():
        assert module in mutation.MODULES, name
        assert e.diff.startswith("-") and "\n+" in e.diff and e.reason, name
        assert name.startswith(("st_runtime.", "stgen.")) and "__mutmut_" in name, name


def test_a_survivor_whose_diff_matches_its_entry_is_equivalent():
    v = registry.judge("motion", {NAME: "survived"}, {NAME: SHOWN}, entries(entry()))
    assert list(v.equivalent) == [NAME] and not v.stale and not v.listed_killed


def test_an_entry_whose_mutant_now_has_another_diff_is_stale_and_counts_as_a_survivor():
    other = SHOWN.replace("self._dt = None", "self._dt = dt + 1")
    v = registry.judge("motion", {NAME: "survived"}, {NAME: other}, entries(entry()))
    assert list(v.stale) == [NAME] and not v.equivalent
    t = registry.tally({NAME: "survived", "k": "killed"}, v)
    assert (t.killed, t.survived, t.equivalent) == (1, 1, 0)
    assert registry.notes(v) == [f"    stale entry (its diff changed; counted as a survivor): {NAME}"]


def test_an_entry_whose_mutant_is_gone_is_stale_when_the_name_was_run():
    v = registry.judge("motion", {NAME: "no tests"}, {}, entries(entry()))
    assert list(v.stale) == [NAME]


def test_entries_of_other_modules_and_of_mutants_not_run_are_left_out():
    listed = entries(entry(module="values"), entry(mutant="x__mutmut_9"))
    v = registry.judge("motion", {NAME: "survived", "x__mutmut_9": "not checked"}, {NAME: SHOWN}, listed)
    assert not (v.equivalent or v.stale or v.listed_killed)


def test_a_listed_mutant_that_a_test_kills_is_reported():
    v = registry.judge("motion", {NAME: "killed"}, {NAME: SHOWN}, entries(entry()))
    assert list(v.listed_killed) == [NAME]
    assert registry.tally({NAME: "killed"}, v).killed == 1
    assert "killed (entry wrong?)" in registry.notes(v)[0]


def test_scores_by_hand():
    # 183 killed (one a timeout), 2 survivors, 17 listed survivors of which one had no tests, 1 not listed
    # without tests, 3 not drawn: raw 183 / 203 = 90.1 %, not equivalent 183 / 186 = 98.4 %
    status = {f"k{i}": "killed" for i in range(182)} | {"t": "timeout"}
    status |= {"s1": "survived", "s2": "survived", "n": "no tests"}
    status |= {f"e{i}": "survived" for i in range(16)} | {"en": "no tests"}
    status |= {f"c{i}": "not checked" for i in range(3)}
    listed = {n: entry(mutant=n) for n in [f"e{i}" for i in range(16)] + ["en"]}
    t = registry.tally(status, registry.Verdicts(equivalent=listed))
    assert (t.killed, t.survived, t.equivalent, t.no_tests, t.others) == (183, 2, 17, 1, {"not checked": 3})
    assert round(t.raw, 1) == 90.1 and round(t.of_not_equivalent, 1) == 98.4
    assert registry.score_line("motion", t, "  [seed 23]") == (
        "motion     killed 183, survived 2, equivalent 17 (listed), no tests 1, not checked 3: "
        "score 90.1 % raw, 98.4 % of the not equivalent  [seed 23]")


def test_every_survivor_listed_equivalent_or_not():
    status = {NAME: "survived", "b": "survived", "c": "killed", "d": "not checked", "e": "no tests"}
    v = registry.Verdicts(equivalent={NAME: entry()}, stale={"e": entry(mutant="e")})
    assert registry.survivor_lines(status, v) == [
        "    b: survived", "    e: no tests, stale entry",
        f"    {NAME}: survived, equivalent: read only as a cache key"]


def test_a_run_of_listed_mutants_only_has_no_score_of_the_not_equivalent():
    t = registry.tally({NAME: "survived"}, registry.Verdicts(equivalent={NAME: entry()}))
    assert registry.score_line("motion", t).endswith("score 0.0 % raw, n/a of the not equivalent")


def test_an_audit_sorts_entries_into_holding_stale_and_gone():
    other = "st_runtime.motion.axis.xǁAxisǁ_set_period__mutmut_4"
    gone = "st_runtime.motion.axis.xǁAxisǁ_set_period__mutmut_9"
    listed = entries(entry(), entry(mutant=other), entry(mutant=gone),
                     entry(mutant="elsewhere", module="checker"))
    now = {NAME: SHOWN, other: "-    self._dt = dt\n+    self._dt = 0"}
    found = registry.audit("motion", now, listed)
    assert (found.holding, found.stale, found.gone) == ([NAME], [other], [gone])


def test_removing_entries_leaves_the_others_as_written(tmp_path):
    path = tmp_path / "registry.toml"
    keep = entry(mutant="kept_1", reason="a reason with 'quotes'")
    path.write_text("# a header line\n" + "".join(registry.entry_toml(e) for e in (
        entry(mutant="gone_1"), keep, entry(mutant="gone_2"), entry(mutant="gone_1", module="checker"))))
    assert registry.without(path, "motion", {"gone_1", "gone_2", "never_listed"}) == 2
    text = path.read_text()
    assert text.startswith("# a header line\n")
    assert text == "# a header line\n" + registry.entry_toml(keep) + registry.entry_toml(
        entry(mutant="gone_1", module="checker"))
    assert set(registry.load(path)) == {("motion", "kept_1"), ("checker", "gone_1")}


def test_an_audit_finds_where_a_stale_entrys_change_went():
    renumbered = "st_runtime.motion.axis.xǁAxisǁ_set_period__mutmut_4"
    elsewhere = "st_runtime.motion.axis.xǁAxisǁstep__mutmut_3"
    now = {NAME: "-    self._dt = dt\n+    self._dt = 0", renumbered: SHOWN, elsewhere: SHOWN}
    found = registry.audit("motion", now, entries(entry()))
    assert found.stale == [NAME]
    assert found.moved == {NAME: renumbered}    # the same change in another function is not it
    holding_already = registry.audit("motion", now, entries(entry(), entry(mutant=renumbered)))
    assert holding_already.moved == {}
    shifted = registry.audit("motion", now, entries(entry(), entry(mutant=renumbered, diff="-a\n+b")))
    assert shifted.moved == {NAME: renumbered}     # a renumbering moves every listed change one on


# tools/mutation.py's `--files`: one file of a module mutated in full (session 16).
def test_prepare_mutates_only_the_named_files_of_the_module(tmp_path, monkeypatch):
    import mutation
    monkeypatch.setattr(mutation, "SCRATCH", tmp_path)
    monkeypatch.setattr(mutation, "COPY", [])
    charges = "st_runtime/compiler/optimise/charges.py"
    pyproject = (mutation.prepare("compiler", [charges]) / "pyproject.toml").read_text()
    assert f'only_mutate = ["{charges}"]' in pyproject
    assert '"tests/test_optimiser_charges.py"' in pyproject          # the module's tests stay
    whole = (mutation.prepare("compiler") / "pyproject.toml").read_text()
    assert 'only_mutate = ["st_runtime/compiler/*"]' in whole
    with pytest.raises(SystemExit, match="not files of module compiler"):
        mutation.prepare("compiler", ["st_runtime/values.py"])


def test_a_mutants_name_gives_its_file():
    import mutation
    assert mutation.source_file("st_runtime.compiler.calls.xǁCallsǁ_result_init__mutmut_3") == \
        "st_runtime/compiler/calls.py"
    assert mutation.source_file("st_runtime.compiler.optimise.charges.x__sink_once__mutmut_52") == \
        "st_runtime/compiler/optimise/charges.py"
    assert mutation.source_file("st_runtime.xml_reader.x_parse__mutmut_1") == "st_runtime/xml_reader.py"
    assert mutation.source_file("st_runtime.compiler.x__compile__mutmut_7") == "st_runtime/compiler/__init__.py"
    assert mutation.source_file("st_runtime.compiler.xǁSharedPreludeǁlead__mutmut_1") == \
        "st_runtime/compiler/__init__.py"

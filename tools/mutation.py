"""Mutation testing of the named modules with mutmut, one module at a time.

    .venv/bin/pip install -e '.[test,mutation]'
    .venv/bin/python tools/mutation.py values            # one module
    .venv/bin/python tools/mutation.py --all             # every module (hours)
    .venv/bin/python tools/mutation.py values --max-children 2
    .venv/bin/python tools/mutation.py reference --sample 400 --seed 16   # a seeded sample

Each module runs in its own scratch copy of the project (build/mutation/<module>/),
with a `[tool.mutmut]` table written there that mutates only that module and runs
only the test files relevant to it (MODULES below): mutmut then picks, per mutant,
the tests among those that executed the mutated function.  The result is a line
per module: killed (a timeout counts as killed), survived, equivalent (listed),
no tests, the raw score killed / (killed + survived + equivalent + no tests) and
the score of the not equivalent, killed / (killed + survived + no tests).
"Equivalent (listed)" are the survivors that tools/mutation_equivalent.toml
lists, each with its reason, while their diff is still the recorded one
(tools/mutation_registry.py; a stale entry is reported and its mutant counts
as a survivor).  `--register NAME --reason TEXT` adds a mutant of the module's
last run to it.  The line is printed and collected with the other modules'
last lines in build/mutation/report.txt; `--survivors` lists the mutants not
killed, the listed equivalent ones with their reason (the others are also kept
in build/mutation/<module>/survivors.txt; build/mutation/history.txt keeps the
line of every run) (see one with
`cd build/mutation/<module> && ../../../.venv/bin/mutmut show NAME`).

Not part of the default test run: it takes minutes per module on two cores.
mutmut runs under `nice -n 15` (`--nice`) with one worker by default
(`--max-children`): the machine is shared.

One file in full: `--files st_runtime/compiler/optimise/charges.py` mutates only the
named files of the module (with its test selection): mutmut generates their mutants
alone (seconds, where the compiler's 11,700 take 15-20 minutes under load), under the
names they have in the whole module's run, and the score line covers those files
("every mutant of ..."); with `--names` or `--sample`, of those files' mutants.

Sampling, for a module too large to finish in the time at hand: `--sample N
--seed S` first generates every mutant of the module (no tests run), lists
their names in sorted order, draws N of them with `random.Random(S).sample`
and runs only those (their names are kept in build/mutation/<module>/sample.txt).
The score is then the score of that sample, and the report says so
("sample N of TOTAL"); the mutants not drawn count as not checked.
`--names FILE` runs the names listed in FILE (an earlier run's sample.txt,
copied out of the scratch copy first) instead: the same sample again after
a change of the source, which would make a new draw another sample.
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import random
import re
import shutil
import subprocess
import sys
from pathlib import Path

import mutation_registry as registry

ROOT = Path(__file__).resolve().parent.parent
SCRATCH = ROOT / "build" / "mutation"

# module name -> (files or folders to mutate, test files that exercise them).
# Only each module's own fast test files: the differential tests (ST against the
# reference, 7-14 s a file) are left out of `reference`, whose mutants its own
# tests must kill.
MODULES: dict[str, tuple[list[str], list[str]]] = {
    "values": (["st_runtime/values.py"],
               ["tests/test_values.py", "tests/test_values_edges.py", "tests/test_controller_api.py",
                "tests/test_semantics.py", "tests/test_operators_runtime.py",
                "tests/test_semantics_random.py", "tests/test_stdlib_functions.py",
                # session 8's whole run (issue 16)
                "tests/test_values_mutation_s8.py"]),
    "compiler": (["st_runtime/compiler/*"],
                 ["tests/test_compiler.py", "tests/test_semantics.py", "tests/test_operators_runtime.py",
                  "tests/test_semantics_random.py", "tests/test_compiler_corpus.py",
                  "tests/test_iec_constructs.py", "tests/test_optimiser_equivalence.py",
                  "tests/test_cost_model.py", "tests/test_compiler_mutants.py",
                  # the optimiser passes' own tests and the shared prelude (fast, seed-19 run)
                  "tests/test_optimiser_ranges.py", "tests/test_optimiser_vector.py",
                  "tests/test_inline_selection.py", "tests/test_prelude_sharing.py",
                  "tests/test_compiler_mutants_s19.py", "tests/test_compiler_mutation_s7.py",
                  # session 8: the later passes' own tests and the nj expression rules', which it had missed
                  "tests/test_optimiser_branches.py", "tests/test_optimiser_unguard.py",
                  "tests/test_optimiser_absolute.py", "tests/test_optimiser_fastpath.py",
                  "tests/test_nj_expression_overflow.py", "tests/test_nj_assignment_casts.py",
                  "tests/test_compiler_mutation_s8.py",
                  # session 9: the chains pass's own tests, which the selection had missed, and seed 24's
                  "tests/test_optimiser_chains.py", "tests/test_compiler_mutation_s9.py",
                  # session 10: the old open mutants and seed 25's, and the later passes' own tests,
                  # which the selection had missed
                  "tests/test_compiler_mutation_s10.py", "tests/test_optimiser_reuse.py",
                  "tests/test_optimiser_charges.py", "tests/test_optimiser_loads.py",
                  "tests/test_optimiser_sets.py", "tests/test_optimiser_stores.py",
                  # session 11: seed 26's survivors
                  "tests/test_compiler_mutation_s11.py",
                  # session 12: seed 25's last and seed 27's survivors, and the passes' own tests
                  # that came with session 11's merges (halves, shortcut, finite, spread: 2 s)
                  "tests/test_compiler_mutation_s12.py", "tests/test_optimiser_halves.py",
                  "tests/test_optimiser_shortcut.py", "tests/test_optimiser_finite.py",
                  "tests/test_optimiser_spread.py",
                  # session 13: the passes' table (every pass alone, off and with all), and the passes'
                  # own tests the selection had missed (wraps, deferred, stores_read, temps: 2 s)
                  "tests/test_compiler_tables_passes.py", "tests/test_compiler_tables_passes_vector.py",
                  "tests/test_compiler_tables_passes_lines.py", "tests/test_optimiser_wraps.py",
                  "tests/test_optimiser_deferred.py", "tests/test_optimiser_stores_read.py",
                  "tests/test_optimiser_temps.py",
                  # session 13: tables of the core files' behaviours (exprs, statements, calls, cost, ...)
                  "tests/test_compiler_tables_core.py",
                  # session 14: rows for the optimiser lines the selection never ran (coverage.py)
                  "tests/test_compiler_tables_passes_s14.py",
                  # session 15: optimise/'s leftovers and the fresh seed 350's survivors
                  "tests/test_compiler_tables_passes_s15.py",
                  # session 14: the core files' leftovers and the lines the selection never ran
                  "tests/test_compiler_tables_core_s14.py",
                  # and the REST test of motion FBs calls.py emits, which the selection never ran (2 s)
                  "tests/test_motion_rest.py",
                  # session 15: the core files' leftovers and the fresh seed 360's survivors
                  "tests/test_compiler_tables_core_s15.py",
                  # a project's own FB named like a native one in the bound and the estimate (session 15)
                  "tests/test_optimiser_fastpath_own_fb.py",
                  # session 16: optimise/charges.py's every mutant, line by line
                  "tests/test_compiler_tables_gaps_s16.py",
                  # session 16: optimise/'s fresh seed 450's survivors
                  "tests/test_compiler_tables_passes_s16.py",
                  # session 16: the fresh seed 460's survivors in the core files
                  "tests/test_compiler_tables_core_s16.py",
                  # session 17: the survivors of seeds 450 and 460 run to their end
                  "tests/test_compiler_tables_s17.py",
                  # session 18: the scalars pass's own tests (2 s), and MIN/MAX of two inlined
                  "tests/test_optimiser_scalars.py", "tests/test_optimiser_selection.py",
                  # session 19: the sums and pivots passes' own tests
                  "tests/test_optimiser_sums.py", "tests/test_optimiser_pivots.py",
                  # session 19: the native pass's own tests (skipped without llvmlite)
                  "tests/test_optimiser_native.py",
                  # session 20: the reads and seal passes' own tests, which the selection had missed
                  "tests/test_optimiser_reads.py", "tests/test_optimiser_seal.py",
                  # session 20: array copies through one slice, FOR ranges from the tables
                  "tests/test_compiler_array_copies.py", "tests/test_compiler_for_ranges.py",
                  # session 21: the kernels pass's own tests (skipped without llvmlite)
                  "tests/test_optimiser_kernels.py",
                  # session 22: the loops pass's own tests (skipped without llvmlite)
                  "tests/test_optimiser_loops.py",
                  # session 23: the elements pass's own tests
                  "tests/test_optimiser_elements.py",
                  # session 23: the dormant pass's own tests
                  "tests/test_compiler_dormant.py",
                  "tests/test_compiler_dormant_groups.py",
                  # session 24: the threads pass's own tests
                  "tests/test_optimiser_threads.py",
                  # session 24: the early store's own tests (aliases.store_early)
                  "tests/test_optimiser_early.py",
                  # session 25: the shared finder of a local in generated code (mentions.py)
                  "tests/test_optimiser_mentions.py", "tests/test_optimiser_margins.py",
                  # session 26: the first prologue load read by drop_unread and store_early
                  "tests/test_optimiser_first_load.py"]),
    "stdlib": (["st_runtime/stdlib/*"],
               ["tests/test_stdlib_functions.py", "tests/test_stdlib_fbs.py", "tests/test_stdlib_st.py",
                "tests/test_operators_runtime.py", "tests/test_st_unit_files.py",
                "tests/test_stdlib_mutants.py"]),
    "motion": (["st_runtime/motion/*"],
               ["tests/test_motion_axis.py", "tests/test_motion_fbs.py", "tests/test_motion_omron.py",
                "tests/test_motion_config.py", "tests/test_motion_invariants.py", "tests/test_motion_st.py",
                "tests/test_motion_limits_negative.py", "tests/test_motion_mutants.py",
                # seed-21 run: two motion files the selection had missed, and round s7's tests
                "tests/test_motion_idle_calls.py", "tests/test_motion_publish.py",
                "tests/test_motion_mutation_s7.py",
                # seed-23 run (issue 16, session 8)
                "tests/test_motion_mutation_s8.py",
                # seed-24 run (issue 16, session 9)
                "tests/test_motion_mutation_s9.py",
                # the binding of axis FBs (session 9's speed work), tested in its own file
                "tests/test_motion_binding.py",
                # seeds 25 and 26 (issue 16, session 11)
                "tests/test_motion_mutation_s11.py",
                # seed 28 (issue 16, session 12), and the two motion files session 11's merge added
                "tests/test_motion_mutation_s12.py", "tests/test_motion_stream_epoch.py",
                "tests/test_motion_rest.py"]),
    "checker": (["st_runtime/checker/*"],
                ["tests/test_checker_rules.py", "tests/test_checker_typing.py", "tests/test_checker_program.py",
                 "tests/test_checker_loader.py", "tests/test_checker_corpus.py",
                 "tests/test_checker_mutants.py", "tests/test_checker_mutants_diagnostics.py",
                 "tests/test_checker_mutants_rules.py",
                 # checker tests named after their subject (issue 16, seed-16 run)
                 "tests/test_sfc.py", "tests/test_memory_model.py", "tests/test_nj_build_rules.py",
                 "tests/test_dialect_table.py", "tests/test_diagnostic_codes.py",
                 "tests/test_string_length_rule.py", "tests/test_call_cycles_and_hints.py",
                 "tests/test_iec_constructs.py",
                 # seed-19 run: prelude_base.py's own tests (the shared prelude), and round three
                 "tests/test_prelude_sharing.py", "tests/test_checker_mutants_third.py",
                 # seed-21 run (issue 16, session 7)
                 "tests/test_checker_mutation_s7.py",
                 # seed-24 run (issue 16, session 9)
                 "tests/test_checker_mutation_s9.py",
                 # seed 24's last survivors and the seed-25 run (issue 16, session 10)
                 "tests/test_checker_mutation_s10.py",
                 # the seed-26 run (issue 16, session 11)
                 "tests/test_checker_mutation_s11.py",
                 # session 12: every diagnostic of declarations, statements, oo, configuration, ... in full
                 "tests/test_checker_diagnostics_decls.py",
                 # every diagnostic of expressions, calls and standard functions (session 12)
                 "tests/test_checker_diagnostics_exprs.py", "tests/test_checker_diagnostics_exprs_builtins.py",
                 # the whole-module seed-28 run (issue 16, session 13)
                 "tests/test_checker_mutation_s13.py",
                 # the fresh seed-29 run and the PROPERTY accessors (issue 16, session 14)
                 "tests/test_checker_mutation_s14.py",
                 # qualified calls NS.F(...) (issue 16, session 15)
                 "tests/test_checker_namespaced_calls.py",
                 # the FOR and STRUCT gaps (session 17), a global FOR variable written by a call (session 18)
                 "tests/test_checker_gaps_s17.py", "tests/test_checker_loop_writes.py"]),
    "reference": (["stgen/reference/*"],
                  ["tests/test_reference_brake.py", "tests/test_reference_cycloidal.py",
                   "tests/test_reference_error_codes.py", "tests/test_reference_forward.py",
                   "tests/test_reference_geometry.py", "tests/test_reference_kinematics.py",
                   "tests/test_reference_linalg.py", "tests/test_reference_wave.py",
                   "tests/test_reference_paths.py", "tests/test_reference_platforms.py",
                   "tests/test_reference_playback.py", "tests/test_study_motions.py",
                   "tests/test_reference_mutants.py",
                   # seed-21 run (issue 16, session 7)
                   "tests/test_reference_mutation_s7.py",
                   # seeds 24 and 25 (issue 16, session 10)
                   "tests/test_reference_mutation_s10.py", "tests/test_reference_mutation_s10_seed25.py",
                   # seed 27's last and the seed-28 run (issue 16, session 11)
                   "tests/test_reference_mutation_s11.py",
                   # seed 30 (issue 16, session 12)
                   "tests/test_reference_mutation_s12.py",
                   # make_table_105 and seed 32 (issue 16, session 13)
                   "tests/test_reference_mutation_s13.py",
                   # seed 33 (issue 16, session 14)
                   "tests/test_reference_mutation_s14.py",
                   # the registry's "integer inputs" entries re-read (issue 16, session 15)
                   "tests/test_reference_mutation_s15.py"]),
}

# Extra [tool.mutmut] settings of one module. The compiler's mutants include
# endless loops (a WHILE without its budget check), and mutmut's default
# timeout (15 x the tests' time, x2) would spend half an hour on each.
# "forkserver": each mutant's worker is forked from a process that has not run
# the tests; forked from mutmut's own process (the default), it inherits the
# shared prelude the stats run compiled, and a mutant of the code that compiles
# it never runs (docs/mutation.md, compiler, seed 19).
SETTINGS: dict[str, dict[str, float | str]] = {
    "compiler": {"timeout_multiplier": 3.0, "process_isolation": "forkserver"}}

# Tests left out of a module's mutmut run: the compiler's twelve slowest (3-29 s
# each, 190 of the selection's 245 s in mutmut's stats) made every survivor cost
# 4-10 minutes under load, and a sample of 150 never finished (seed 25: 64 run).
# Each runs whole programs (FK solves, the study's scan times, loads in a row)
# through every pass: a mutant only they would kill is a survivor here, judged
# by hand like the others, so the score is a lower bound of the whole
# selection's (docs/mutation.md, compiler, session 11).  Ten ids: the FK
# solves' test has three parameters.
DESELECTED: dict[str, list[str]] = {
    "compiler": [
        "tests/test_prelude_sharing.py::test_loads_in_a_row_do_not_leak_into_each_other",
        "tests/test_prelude_sharing.py::test_loads_leave_the_shared_prelude_as_it_was",
        "tests/test_optimiser_fastpath.py::test_fk_cut_by_f_period_at_many_budgets_lands_the_same",
        "tests/test_optimiser_fastpath.py::test_f_period_lands_on_the_same_statement_at_every_budget",
        "tests/test_optimiser_equivalence.py::test_fk_solves_are_bit_identical_with_and_without_the_passes",
        "tests/test_cost_model.py::test_the_estimate_belongs_to_the_st_not_to_the_python",
        "tests/test_cost_model.py::test_a_scenario_result_carries_the_controller_time_per_scan",
        "tests/test_cost_model.py::test_the_study_end_points",
        "tests/test_cost_model.py::test_a_converging_solve_costs_as_many_iterations",
        "tests/test_cost_model.py::test_one_newton_raphson_iteration_costs_the_studys_49_5_us"]}

COPY = ["st_runtime", "stgen", "st_templates", "tests", "examples", "generated", "README.md"]


def toml_list(items: list[str]) -> str:
    return "[" + ", ".join(json.dumps(i) for i in items) + "]"


def prepare(name: str, files: list[str] | None = None) -> Path:
    """A scratch copy of the project whose pyproject configures mutmut for `name` (for only
    `files` of it, when given: their mutants keep the names they have in the whole module's)."""
    targets, tests = MODULES[name]
    if files:
        outside = [f for f in files if not any(fnmatch.fnmatch(f, t) for t in targets)]
        if outside:
            raise SystemExit(f"not files of module {name} ({', '.join(targets)}): {', '.join(outside)}")
        targets = files
    work = SCRATCH / name
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    for item in COPY:
        src = ROOT / item
        if src.is_dir():
            shutil.copytree(src, work / item, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        elif src.exists():
            shutil.copy2(src, work / item)
    tests = [t for t in tests if (ROOT / t).exists()]
    pytest_args = ["-p", "no:cacheprovider", "-q", "-x"]
    for test in DESELECTED.get(name, []):
        pytest_args += ["--deselect", test]
    pyproject = (ROOT / "pyproject.toml").read_text()
    pyproject = pyproject.split("\n[tool.mutmut]")[0]
    pyproject += ("\n[tool.mutmut]\n"
                  'source_paths = ["st_runtime", "stgen"]\n'
                  f"only_mutate = {toml_list(targets)}\n"
                  f"pytest_add_cli_args_test_selection = {toml_list(tests)}\n"
                  f"pytest_add_cli_args = {toml_list(pytest_args)}\n"
                  'also_copy = ["st_templates", "examples", "generated", "README.md"]\n'
                  + "".join(f"{k} = {json.dumps(v)}\n" for k, v in SETTINGS.get(name, {}).items()))
    (work / "pyproject.toml").write_text(pyproject)
    return work


GENERATE = """
import os
import mutmut.__main__ as m
from mutmut.utils.file_utils import copy_also_copy_files, copy_src_dir, setup_source_paths
os.makedirs("mutants", exist_ok=True)
copy_src_dir()
copy_also_copy_files()
setup_source_paths()
m.create_mutants(1)
"""


def all_mutant_names(work: Path) -> list[str]:
    """Every mutant of the module, generated without running a test."""
    subprocess.run([sys.executable, "-c", GENERATE], cwd=work, check=True, capture_output=True)
    names = []
    for meta in sorted((work / "mutants").rglob("*.meta")):
        names += json.loads(meta.read_text())["exit_code_by_key"]
    return sorted(names)


def draw_sample(work: Path, size: int, seed: int) -> tuple[list[str], int]:
    """A seeded sample of `size` mutant names (sorted), and the number of mutants."""
    names = all_mutant_names(work)
    sample = sorted(random.Random(seed).sample(names, min(size, len(names))))
    (work / "sample.txt").write_text(f"# seed {seed}, {len(sample)} of {len(names)} mutants\n"
                                     + "".join(n + "\n" for n in sample))
    return sample, len(names)


def listed_sample(work: Path, listed: Path) -> tuple[list[str], int]:
    """The mutant names of an earlier sample file (e.g. its sample.txt) that still exist."""
    names = all_mutant_names(work)
    wanted = [n.strip() for n in listed.read_text().splitlines() if n.strip() and not n.startswith("#")]
    present = set(names)
    sample = sorted(n for n in wanted if n in present)
    gone = len(wanted) - len(sample)
    (work / "sample.txt").write_text(f"# {len(sample)} names of {listed.name} ({gone} no longer exist), "
                                     f"of {len(names)} mutants\n" + "".join(n + "\n" for n in sample))
    return sample, len(names)


def results(work: Path) -> dict[str, str]:
    """mutant name -> status, from `mutmut results --all true`."""
    out = subprocess.run([sys.executable, "-m", "mutmut", "results", "--all", "true"], cwd=work,
                         capture_output=True, text=True).stdout
    status = {}
    for line in out.splitlines():
        if ":" in line:
            mutant, _, state = line.strip().rpartition(":")
            if mutant:
                status[mutant.strip()] = state.strip()
    return status


DIFFS = """
import json, sys
from pathlib import Path
from mutmut.mutation.diff_apply import get_diff_for_mutant
wanted = set(json.load(sys.stdin))
diffs = {}
for meta in Path("mutants").rglob("*.meta"):
    for name in json.loads(meta.read_text())["exit_code_by_key"]:
        if name in wanted:
            diffs[name] = get_diff_for_mutant(name, path=meta.with_suffix("").relative_to("mutants"))
json.dump(diffs, sys.stdout)
"""


def mutant_diffs(work: Path, names: list[str]) -> dict[str, str]:
    """name -> the diff `mutmut show` prints, for the named mutants of the scratch copy."""
    if not names:
        return {}
    out = subprocess.run([sys.executable, "-c", DIFFS], cwd=work, input=json.dumps(names), check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)


def report(name: str, work: Path, entries: dict, survivors: bool) -> tuple[str, list[str]]:
    """The module's score line (the registry's equivalent mutants left out of the second score),
    and the lines under it: stale entries, and with `survivors` every mutant not killed."""
    status = results(work)
    judged = (*registry.UNKILLED, *registry.KILLED)
    listed = [m for (mod, m) in entries if mod == name and status.get(m) in judged]
    verdicts = registry.judge(name, status, mutant_diffs(work, listed), entries)
    sample_file = work / "sample.txt"
    sampled = f"  [{sample_file.read_text().splitlines()[0][2:]}]" if sample_file.exists() else ""
    line = registry.score_line(name, registry.tally(status, verdicts), sampled)
    (work / "survivors.txt").write_text("".join(
        f"{m}: {st}\n" for m, st in sorted(status.items())
        if st in registry.UNKILLED and m not in verdicts.equivalent))
    below = registry.notes(verdicts) + (registry.survivor_lines(status, verdicts) if survivors else [])
    return line, below


def register(name: str, mutant: str, reason: str) -> str:
    """Add a judged equivalent mutant of the last run of `name` to the registry."""
    diff = mutant_diffs(SCRATCH / name, [mutant]).get(mutant)
    if diff is None:
        raise SystemExit(f"{mutant} is not a mutant of {SCRATCH / name}")
    entry = registry.Entry(name, mutant, diff, reason)
    if (name, mutant) in registry.load():
        raise SystemExit(f"{mutant} is listed already")
    with open(registry.REGISTRY, "a") as out:
        out.write(registry.entry_toml(entry))
    return registry.changed_lines(diff)


def source_file(mutant: str) -> str:
    """The file a mutant's name comes from: st_runtime.compiler.calls.xǁCallsǁf__mutmut_3 ->
    st_runtime/compiler/calls.py (a function's name is prefixed `x_`, a method's `xǁClassǁ`);
    a package's own functions live in its __init__.py (st_runtime.compiler.x__compile__mutmut_7)."""
    module = re.split(r"\.x(?:_|ǁ)", mutant, maxsplit=1)[0].replace(".", "/")
    return f"{module}/__init__.py" if (ROOT / module).is_dir() else f"{module}.py"


def audit(name: str, prune: bool, files: list[str] | None = None) -> list[str]:
    """The module's registry entries against its mutants now (generated, no test run): lines on the
    stale and gone ones; with `prune`, the gone ones are removed (a stale one waits for a new judgement).
    With `files`, only those files' mutants are generated and only their entries audited."""
    work = prepare(name, files)
    entries = {k: e for k, e in registry.load().items() if not files or source_file(k[1]) in files}
    found = registry.audit(name, mutant_diffs(work, all_mutant_names(work)), entries)
    lines = [f"{name:10s} registry: {len(found.holding)} entries hold, {len(found.stale)} stale, "
             f"{len(found.gone)} name no mutant any more"]
    moved = {n: f" (its change is {found.moved[n]} now)" for n in found.moved}
    lines += [f"    stale (the name makes another change now): {n}{moved.get(n, '')}" for n in found.stale]
    lines += [f"    gone: {n}{moved.get(n, '')}" for n in found.gone]
    if prune and found.gone:
        removed = registry.without(registry.REGISTRY, name, set(found.gone))
        lines.append(f"    removed the {removed} gone entries from {registry.REGISTRY.name}")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    # `[]` among the choices: argparse checks the empty default of nargs="*" against them.
    parser.add_argument("modules", nargs="*", choices=[*MODULES, []], metavar="MODULE",
                        help=f"modules to mutate: {', '.join(MODULES)}")
    parser.add_argument("--all", action="store_true", help="every module")
    parser.add_argument("--max-children", type=int, default=1)
    parser.add_argument("--nice", type=int, default=15, help="niceness of the mutmut run")
    parser.add_argument("--sample", type=int, help="run only a seeded sample of this many mutants")
    parser.add_argument("--seed", type=int, default=16, help="seed of the sample")
    parser.add_argument("--names", type=Path, help="run only the mutants named in this file (an earlier "
                        "sample.txt: the same sample again after the source changed)")
    parser.add_argument("--files", nargs="+", metavar="FILE", help="mutate only these files of the "
                        "module (paths as in MODULES, e.g. st_runtime/compiler/optimise/charges.py): "
                        "every mutant of a file without generating the module's others; with --audit, those files' "
                        "entries only")
    parser.add_argument("--survivors", action="store_true",
                        help="list the mutants not killed, the listed equivalent ones with their reason")
    parser.add_argument("--report-only", action="store_true", help="report an earlier run")
    parser.add_argument("--register", metavar="MUTANT", help="add MUTANT of the module's last run to the "
                        f"registry of equivalent mutants ({registry.REGISTRY.name}), with --reason")
    parser.add_argument("--reason", help="why no test can kill the --register'ed mutant (one line)")
    parser.add_argument("--audit", action="store_true", help="check the registry's entries of the "
                        "modules against their mutants now, without running a test")
    parser.add_argument("--prune", action="store_true", help="with --audit: remove the entries whose "
                        "mutant no longer exists")
    args = parser.parse_args(argv)
    names = list(MODULES) if args.all else args.modules
    if not names:
        parser.error("name a module or pass --all")
    if args.register:
        if len(names) != 1 or not args.reason:
            parser.error("--register needs one module and a --reason")
        print(register(names[0], args.register, args.reason))
        return 0
    if args.prune and not args.audit:
        parser.error("--prune goes with --audit")
    if args.audit:
        print("\n".join(line for name in names for line in audit(name, args.prune, args.files)))
        return 0
    entries = registry.load()
    lines = []
    for name in names:
        work = SCRATCH / name
        if not args.report_only:
            work = prepare(name, args.files)
            chosen: list[str] = []
            if args.names:
                chosen, total = listed_sample(work, args.names.resolve())
                print(f"{name}: {len(chosen)} mutants named in {args.names}, of {total}", flush=True)
            elif args.sample:
                chosen, total = draw_sample(work, args.sample, args.seed)
                print(f"{name}: sample of {len(chosen)} of {total} mutants, seed {args.seed}", flush=True)
            if args.files and not chosen:
                (work / "sample.txt").write_text(f"# every mutant of {', '.join(args.files)}\n")
            print(f"{name}: mutmut run in {work} (progress in {work / 'mutmut.log'})", flush=True)
            with open(work / "mutmut.log", "w") as log:
                subprocess.run(["nice", "-n", str(args.nice), sys.executable, "-m", "mutmut", "run",
                                "--max-children", str(args.max_children), *chosen],
                               cwd=work, check=False, stdout=log, stderr=subprocess.STDOUT)
        line, below = report(name, work, entries, args.survivors)
        (work / "score.txt").write_text(line + "\n")
        if not args.report_only:   # every run's score, kept when the next run replaces the scratch copy
            with open(SCRATCH / "history.txt", "a") as history:
                history.write(line + "\n")
        lines += [line, *below]
    print("\n".join(lines))
    # The table of every module run so far (each run keeps its own score.txt).
    scores = [(SCRATCH / n / "score.txt") for n in MODULES]
    (SCRATCH / "report.txt").write_text("".join(p.read_text() for p in scores if p.exists()))
    return 0


if __name__ == "__main__":
    sys.exit(main())

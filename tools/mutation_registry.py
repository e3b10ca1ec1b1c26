"""The registry of judged equivalent mutants, and the scores that leave them out.

An equivalent mutant is one no test can tell from the original (docs/mutation.md
gives each one's reason at length).  tools/mutation_equivalent.toml lists them,
one `[[equivalent]]` table each:

    [[equivalent]]
    module = "motion"
    mutant = "st_runtime.motion.axis.xǁAxisǁ_set_period__mutmut_3"
    diff = '''
    -        self._dt = dt
    +        self._dt = None'''
    reason = "a _dt of None only makes step call _set_period again"

`diff` holds the changed lines of `mutmut show NAME` (its "-" and "+" lines,
without the file header and the hunk lines).  mutmut numbers the mutants of a
function in order, so an edit of the function gives an old name to another
mutation: an entry counts only while its mutant's changed lines are still the
recorded ones.  Otherwise it is stale, and its mutant counts as a survivor
until it is judged again.
"""

from __future__ import annotations

import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

REGISTRY = Path(__file__).with_name("mutation_equivalent.toml")
# what starts each entry in the file (entry_toml writes it so)
TABLE = "[[equivalent]]\n"

# mutmut's states that count as killed: a timeout is a mutant that hung the tests.
KILLED = ("killed", "timeout")
# the states of a mutant no test failed on, which an entry can explain
UNKILLED = ("survived", "no tests")


@dataclass(frozen=True)
class Entry:
    module: str
    mutant: str
    diff: str
    reason: str


def changed_lines(diff: str) -> str:
    """The "-" and "+" lines of a unified diff, after its file header: what identifies a mutation."""
    lines = diff.strip("\n").splitlines()
    body = lines[2:] if len(lines) >= 2 and lines[0].startswith("---") and lines[1].startswith("+++") else lines
    return "\n".join(line.rstrip() for line in body if line[:1] in ("-", "+"))


def load(path: Path = REGISTRY) -> dict[tuple[str, str], Entry]:
    """(module, mutant name) -> entry; a malformed or repeated entry is an error."""
    if not path.exists():
        return {}
    entries: dict[tuple[str, str], Entry] = {}
    for i, table in enumerate(tomllib.loads(path.read_text()).get("equivalent", [])):
        missing = {"module", "mutant", "diff", "reason"} - set(table)
        if missing:
            raise ValueError(f"{path.name}: entry {i + 1} has no {', '.join(sorted(missing))}")
        entry = Entry(table["module"], table["mutant"], changed_lines(table["diff"]), table["reason"].strip())
        if not entry.diff or not entry.reason:
            raise ValueError(f"{path.name}: entry {i + 1} ({entry.mutant}) has an empty diff or reason")
        key = (entry.module, entry.mutant)
        if key in entries:
            raise ValueError(f"{path.name}: {entry.mutant} is listed twice for {entry.module}")
        entries[key] = entry
    return entries


def entry_toml(entry: Entry) -> str:
    """One `[[equivalent]]` table, as `load` reads it back."""
    diff = changed_lines(entry.diff)
    shown = f"'''\n{diff}'''" if "'''" not in diff and "\r" not in diff else json.dumps(diff, ensure_ascii=False)
    return ("\n[[equivalent]]\n"
            f"module = {json.dumps(entry.module)}\n"
            f"mutant = {json.dumps(entry.mutant, ensure_ascii=False)}\n"
            f"diff = {shown}\n"
            f"reason = {json.dumps(entry.reason, ensure_ascii=False)}\n")


@dataclass
class Verdicts:
    """What the registry says of one module's run."""
    equivalent: dict[str, Entry] = field(default_factory=dict)   # unkilled, listed, diff as recorded
    stale: dict[str, Entry] = field(default_factory=dict)        # listed, but the diff is another now
    listed_killed: dict[str, Entry] = field(default_factory=dict)  # listed, diff as recorded, yet killed


def judge(module: str, status: dict[str, str], diffs: dict[str, str],
          entries: dict[tuple[str, str], Entry]) -> Verdicts:
    """Sort the run's listed mutants: `status` is name -> mutmut state, `diffs` name -> `mutmut show` diff
    (needed for every listed name of the run).  Entries of mutants the run did not judge are left out."""
    verdicts = Verdicts()
    for (mod, name), entry in entries.items():
        state = status.get(name)
        if mod != module or state not in (*UNKILLED, *KILLED):
            continue
        if changed_lines(diffs.get(name, "")) != entry.diff:
            verdicts.stale[name] = entry
        elif state in UNKILLED:
            verdicts.equivalent[name] = entry
        else:
            verdicts.listed_killed[name] = entry
    return verdicts


@dataclass
class Audit:
    """Every entry of one module against the module's mutants as the source is now, without a run."""
    holding: list[str] = field(default_factory=list)   # the mutant exists with the recorded change
    stale: list[str] = field(default_factory=list)     # the name now makes another change
    gone: list[str] = field(default_factory=list)      # no mutant of that name any more
    moved: dict[str, str] = field(default_factory=dict)  # stale or gone -> the name making its change now


def audit(module: str, diffs: dict[str, str], entries: dict[tuple[str, str], Entry]) -> Audit:
    """Sort a module's entries by `diffs`, name -> `mutmut show` diff of every mutant of the module now.
    A source edit renumbers a function's mutants, so entries go stale or gone between runs: this finds
    them before a sample happens to draw them.  A stale or gone entry whose change another mutant
    of the same function (not one whose own entry holds) makes now is `moved` to it: the change is
    the same, but whether the reason still holds in the edited function is for a person to judge."""
    result = Audit()
    own = {name: entry for (mod, name), entry in sorted(entries.items()) if mod == module}
    for name, entry in own.items():
        if name not in diffs:
            result.gone.append(name)
        elif changed_lines(diffs[name]) != entry.diff:
            result.stale.append(name)
        else:
            result.holding.append(name)
    holding = set(result.holding)
    for name in result.stale + result.gone:
        function = name.rpartition("__mutmut_")[0]
        result.moved.update((name, other) for other in sorted(diffs) if other not in holding
                            and other.rpartition("__mutmut_")[0] == function
                            and changed_lines(diffs[other]) == own[name].diff)
    return result


def without(path: Path, module: str, names: set[str]) -> int:
    """Remove the named entries of `module` from the registry at `path`, leaving every other table
    as it is written; the number removed."""
    def named(table: str) -> bool:
        entry = tomllib.loads(table)
        return entry["module"] == module and entry["mutant"] in names

    head, *tables = path.read_text().split(TABLE)
    kept = [t for t in tables if not named(t)]
    path.write_text(head + "".join(TABLE + t for t in kept))
    return len(tables) - len(kept)


@dataclass(frozen=True)
class Tally:
    killed: int           # incl. timeouts
    survived: int         # not listed as equivalent (a stale entry's mutant among them)
    equivalent: int       # survived or no tests, listed
    no_tests: int         # not listed
    others: dict[str, int]   # mutmut's other states (not checked, skipped, ...): not scored

    @property
    def raw(self) -> float:
        """killed / judged: the equivalent mutants count as survivors."""
        judged = self.killed + self.survived + self.equivalent + self.no_tests
        return 100.0 * self.killed / judged if judged else float("nan")

    @property
    def of_not_equivalent(self) -> float:
        """killed / (judged - equivalent)."""
        judged = self.killed + self.survived + self.no_tests
        return 100.0 * self.killed / judged if judged else float("nan")


def tally(status: dict[str, str], verdicts: Verdicts) -> Tally:
    counts = {"killed": 0, "survived": 0, "equivalent": 0, "no tests": 0}
    others: dict[str, int] = {}
    for name, state in status.items():
        if state in KILLED:
            counts["killed"] += 1
        elif state in UNKILLED:
            counts["equivalent" if name in verdicts.equivalent else state] += 1
        else:
            others[state] = others.get(state, 0) + 1
    return Tally(counts["killed"], counts["survived"], counts["equivalent"], counts["no tests"], others)


def _percent(value: float) -> str:
    return "n/a" if math.isnan(value) else f"{value:.1f} %"


def score_line(name: str, t: Tally, sampled: str = "") -> str:
    rest = "".join(f", {k} {v}" for k, v in sorted(t.others.items()))
    return (f"{name:10s} killed {t.killed}, survived {t.survived}, equivalent {t.equivalent} (listed), "
            f"no tests {t.no_tests}{rest}: score {_percent(t.raw)} raw, {_percent(t.of_not_equivalent)} "
            f"of the not equivalent{sampled}")


def notes(verdicts: Verdicts) -> list[str]:
    """Lines on the entries that no longer hold: stale ones, and listed mutants a test killed."""
    return ([f"    stale entry (its diff changed; counted as a survivor): {n}" for n in sorted(verdicts.stale)]
            + [f"    listed as equivalent but killed (entry wrong?): {n}" for n in sorted(verdicts.listed_killed)])


def survivor_lines(status: dict[str, str], verdicts: Verdicts) -> list[str]:
    """Every mutant not killed, a listed equivalent marked with its reason."""
    lines = []
    for name, state in sorted(status.items()):
        if state in KILLED:
            continue
        if name in verdicts.equivalent:
            lines.append(f"    {name}: {state}, equivalent: {verdicts.equivalent[name].reason}")
        elif name in verdicts.stale:
            lines.append(f"    {name}: {state}, stale entry")
        elif state != "not checked":
            lines.append(f"    {name}: {state}")
    return lines

"""The README's two Quick start commands are what CI runs and what the project installs.

CI runs `.ci/run` from a clean clone; it must run the README's test command, and
every pytest plugin that command's options need must come with the `test` extra,
or a fresh machine fails on an unknown option.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: pytest options and the distribution that provides each (pytest's own options need only pytest).
PLUGIN_OF_OPTION = {"-n": "pytest-xdist", "--dist": "pytest-xdist",
                    **{option: "pytest" for option in ("-q", "-x", "-k", "-p", "--junitxml")}}


def quick_start_commands() -> list[str]:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return [line.strip() for line in section.splitlines() if line.startswith("    ")]


def test_the_quick_start_gives_a_setup_and_run_then_a_setup_and_test_command():
    commands = quick_start_commands()
    assert len(commands) == 2
    run, test = commands
    assert run.startswith("python3 -m venv .venv") and "stgen demo" in run
    assert test.startswith("python3 -m venv .venv") and "-m pytest" in test


def test_ci_runs_the_readme_test_command_word_for_word():
    ci_lines = (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert quick_start_commands()[1] in [line.strip() for line in ci_lines]


def test_the_test_extra_installs_every_plugin_the_test_command_uses():
    test_command = quick_start_commands()[1]
    options = re.findall(r"(?<=\s)(--?[a-z][\w-]*)", test_command.split("-m pytest", 1)[1])
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    extra = {re.match(r"[\w.-]+", requirement).group(0).lower()
             for requirement in project["optional-dependencies"]["test"]}
    needed = {PLUGIN_OF_OPTION[option] for option in options if option in PLUGIN_OF_OPTION}
    assert needed <= extra, f"the test command's options need {sorted(needed - extra)} in the test extra"
    unknown = [option for option in options if option not in PLUGIN_OF_OPTION]
    assert not unknown, f"options this test does not know the plugin of: {unknown}"

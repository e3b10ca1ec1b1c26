"""The per-load tables' written-out `__init__`s (CheckedProgram, Context, WriteGraph) against
their dataclass fields: each field set, a table empty, of its factory's type and a new one for
each object (a table shared by two loads would carry one load's entries into the next), a value
its default or the argument given, and nothing else.  The fields are what the dataclass's own
`__init__` would give; a field added without its line in `__init__` fails here."""

from __future__ import annotations

from dataclasses import MISSING, fields

import pytest

from st_runtime.checker.context import Context, FastSink
from st_runtime.checker.loop_writes import WriteGraph
from st_runtime.symbols import CheckedProgram

FILES = ["a file"]
MADE = {
    "CheckedProgram": (CheckedProgram, lambda: CheckedProgram(FILES), {"files": FILES}),
    "CheckedProgram, nj": (CheckedProgram, lambda: CheckedProgram(FILES, dialect="nj"),
                           {"files": FILES, "dialect": "nj"}),
    "Context": (Context, lambda: Context(PROGRAM, SINK), {"program": None, "sink": None}),
    "Context, codesys, open": (Context, lambda: Context(PROGRAM, SINK, "codesys", True),
                               {"program": None, "sink": None, "dialect": "codesys",
                                "open_instances": True}),
    "WriteGraph": (WriteGraph, WriteGraph, {}),
}
PROGRAM, SINK = CheckedProgram(FILES), FastSink()


def _expected(f, given: dict):
    if f.name in given:
        return given[f.name]
    if f.default_factory is not MISSING:
        return f.default_factory()
    assert f.default is not MISSING, f"{f.name} has neither a default nor an argument"
    return f.default


@pytest.mark.parametrize("name", MADE)
def test_init_gives_every_field_and_nothing_else(name):
    cls, make, given = MADE[name]
    given = {**given, **({"program": PROGRAM, "sink": SINK} if cls is Context else {})}
    first, second = make(), make()
    assert set(vars(first)) == {f.name for f in fields(cls)}
    for f in fields(cls):
        value, expected = getattr(first, f.name), _expected(f, given)
        assert type(value) is type(expected) and value == expected, f.name
        if f.default_factory is not MISSING:
            assert getattr(second, f.name) is not value, f"{f.name} is shared by two objects"

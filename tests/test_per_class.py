"""`st_runtime.per_class.PerClass`: the per-class tables of the tree walks (the checker's
shapes, kinds, checks, typers and field orders) make a class's value once, on its first
look-up, and keep it."""

from __future__ import annotations

from st_runtime.per_class import PerClass


def test_a_class_value_is_made_once_and_kept():
    made = []

    def make(cls):
        made.append(cls)
        return cls.__name__.upper()

    table = PerClass(make)
    assert int not in table
    assert table[int] == "INT" and table[str] == "STR" and table[int] == "INT"
    assert made == [int, str]                   # the second look-up of int makes nothing
    assert dict(table) == {int: "INT", str: "STR"}
    assert table.get(float) is None and float not in table   # `get` and `in` make nothing

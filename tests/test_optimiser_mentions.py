"""The shared finder of a Python local in generated code (st_runtime/compiler/optimise/mentions.py):
where the name stands whole, by hand, and the places that only spell it (an attribute of another
object, the tail of a longer name or of a number's literal, the head of a longer name), which it
must refuse."""

from __future__ import annotations

import pytest

from st_runtime.compiler.optimise.mentions import count, places


@pytest.mark.parametrize("text, name, expected", [
    ("v_A", "v_A", [0]),
    ("v_B = (v_A + v_A)", "v_A", [7, 13]),
    ("(v_A := 4)", "v_A", [1]),
    ("f(v_A,v_A)", "v_A", [2, 6]),
    ("v_A\nv_A", "v_A", [0, 4]),
    ("_t1 = _t10 + _t1", "_t1", [0, 13]),
    # spelt but not standing: refused
    ("self.v_A = 1", "v_A", []),
    ("v_AB = xv_A", "v_A", []),
    ("x = 1e5 + 2e5", "e5", []),
    ("v_A_ = v_Aé", "v_A", []),
    ("", "v_A", []),
])
def test_a_name_stands_where_it_is_whole(text, name, expected):
    assert places(text, name) == expected
    assert count(text, name) == len(expected)


def test_a_refused_spelling_does_not_hide_a_place_after_it():
    """The search goes on at the next character after a place it refused, on after a place."""
    assert places("xv_A v_A.v_A v_A", "v_A") == [5, 13]


@pytest.mark.parametrize("text, word, expected", [
    # a word of a text (`attributes`): after a dot it stands too, never inside another word
    ("s.stops := stops; xstops stops_", "stops", [2, 11]),
    ("a.b.c", "b", [2]),
    # a word not ending in a word character (a keyword with its colon) stands whatever follows
    ("try:x", "try:", [0]),
    ("self.try:", "try:", [5]),
    ("retry: try:", "try:", [7]),
    ("finally:pass", "finally:", [0]),
    # one ending in a word character still needs a boundary after it
    ("returned = x", "return", []),
    ("x.return 1", "return", [2]),
])
def test_a_word_with_attributes_stands_after_a_dot_too(text, word, expected):
    """Worked by hand against `(?<!\\w)WORD` followed by `(?!\\w)` when WORD ends in a word
    character (the census's and the barrier words' patterns before this finder)."""
    assert places(text, word, attributes=True) == expected

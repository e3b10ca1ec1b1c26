"""Where a Python name stands in generated code: the one finder of the text passes that ask
where a local stands in a line or a body (aliases' `store_early`, charges' `may_set`, fuse),
and, with `attributes`, where a word stands in a text (charges' barrier words, dormant's
census of the ST texts).

A name stands where the text spells it whole: not after a word character or a dot (the tail
of a longer name, of a number's literal, `1e5`, or an attribute of another object, `self.v_X`),
and not before a word character.  The places are found by `str.find` (C) and each checked in
Python: no pattern is built, compiled or looked up per name.  The names asked for are Python
identifiers (word characters only), so two places never overlap.
"""

from __future__ import annotations


def places(text: str, name: str, attributes: bool = False) -> list[int]:
    """Where `name` stands in `text`, in order (after each place found, the search goes on
    after it, as `re.findall` does).  `attributes`: a place after a dot stands too (a word
    of ST text, `s.Stops`, or a keyword after an attribute).  A `name` that does not end in
    a word character (`try:`) stands whatever follows it, as a regex's `\\b` after it would
    not ask."""
    found, size, end = [], len(name), len(text)
    before = _in_name if attributes else _before_name
    closed = _in_name(name[-1])
    at = text.find(name)
    while at >= 0:
        after = at + size
        if (at == 0 or not before(text[at - 1])) and (after == end or not closed or not _in_name(text[after])):
            found.append(at)
            at = text.find(name, after)
        else:
            at = text.find(name, at + 1)
    return found


def count(text: str, name: str) -> int:
    """How often `name` stands in `text`."""
    return len(places(text, name)) if name in text else 0


def _in_name(char: str) -> bool:
    """A word character (the regex engine's `\\w` of a str: `isalnum` or `_`)."""
    return char.isalnum() or char == "_"


def _before_name(char: str) -> bool:
    return char.isalnum() or char in "_."

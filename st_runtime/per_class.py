"""`PerClass(make)`: a table of one value per class, made on the class's first look-up.

The walks of the syntax tree (the checker's and the compiler's) ask something of every
node's class: its shape, the method that checks it, the fields to read.  Each such
answer depends on the class alone, so it is worked out once and kept, and every later
node of that class costs one dict subscript.
"""

from __future__ import annotations


class PerClass(dict):
    """class -> `make(cls)`, made on the class's first look-up and kept (`__missing__`:
    the look-ups after it are plain dict subscripts, in C)."""

    __slots__ = ("make",)

    def __init__(self, make) -> None:
        super().__init__()
        self.make = make

    def __missing__(self, cls: type):
        value = self[cls] = self.make(cls)
        return value

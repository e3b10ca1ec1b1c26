"""Loading without the cyclic garbage collector: `@without_collections`.

A load (parse, check, compile) allocates many objects that live until its
end (tokens, AST nodes, tables, generated code) and almost no cyclic garbage:
what it drops is freed by reference counting.  The collector would still run
a young collection every 700 allocations, and now and then a full one over
the whole heap (the grammar, the shared prelude), finding nothing: about a
twentieth of a small file's load (callgrind, docs/load.md).  The collector is
off for the call and back as it was after it, so nothing is kept longer than
one load, and a caller that turned it off itself keeps it off.
"""

from __future__ import annotations

import functools
import gc


def without_collections(function):
    """`function` run with the cyclic garbage collector paused (see the module)."""
    @functools.wraps(function)
    def paused(*args, **kwargs):
        if not gc.isenabled():
            return function(*args, **kwargs)
        gc.disable()
        try:
            return function(*args, **kwargs)
        finally:
            gc.enable()
    return paused

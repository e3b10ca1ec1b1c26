"""The cyclic garbage collector paused while a load runs.

A load allocates tens of thousands of objects that live until it ends (the
AST, the checker's tables, the generated classes and functions); with the
collector running, each young collection during the load traverses them
again and promotes them, although almost none is garbage yet.  Paused, the
young objects the load leaves are traversed once, by the first collection
after it; what the load freed meanwhile was freed by reference counting, as
before.  Nothing but the timing of collections changes: no object's life,
no result.
"""

from __future__ import annotations

import functools
import gc


def collector_paused(function):
    """`function` run with the collector disabled, and the caller's state restored
    (left disabled if it was; nested calls leave it to the outermost)."""
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

"""Does a playback table fit the controller? The memory model of ``stgen generate --playback``.

TRJ_PlaybackTable holds, per knot, one LREAL time and six LREAL pose values
and six LREAL slopes. Its bytes come from st_runtime's memory model (the
checker's, issue 15: OMRON's allocation table, docs/limits.md), applied to the
three arrays the template declares: 13 × 8 bytes per knot. Two limits, both
configurable here:

* ``MAX_ARRAY_ELEMENTS`` = 65535 elements per array (the pose and slope arrays hold
  6 per knot): the NJ-series array limit as remembered from the NJ-series CPU Unit
  Software User's Manual (W501), "Array Specifications"; the page was not reached in
  this session (assumed, see docs/nj501.md).
* ``TABLE_BYTES_MAX`` = 2 MiB: half of the 4 MB variable memory without a Retain
  attribute of the NJ501 as remembered from its datasheet, leaving the other half to
  the rest of the project (assumed; W501 appendix A-10 "Size Restrictions for the User
  Program" says to confirm sizes in Sysmac Studio).

The memory model sizes the table; it has no NJ figure for either limit (docs/limits.md:
"the NJ's limits on elements per array dimension and on total variable memory were not
found"), so both numbers above stay assumed.
"""

from __future__ import annotations

from stgen.reference.playback import ADDED_KNOTS, PlaybackError, PlaybackTable

MAX_ARRAY_ELEMENTS = 65535
TABLE_BYTES_MAX = 2 * 1024 * 1024


def table_bytes(knots: int) -> int:
    """Bytes of TRJ_PlaybackTable for ``knots`` knots, by st_runtime's memory model (OMRON's
    allocation rules): TRJ_PLAYBACK_TIME, _POSE and _SLOPE as the template declares them."""
    from st_runtime import types as T
    from st_runtime.checker.memory import MemoryModel

    model = MemoryModel()
    arrays = (T.ArrayType(((1, knots),), T.LREAL),              # TRJ_PLAYBACK_TIME
              T.ArrayType(((1, knots), (1, 6)), T.LREAL),      # TRJ_PLAYBACK_POSE
              T.ArrayType(((1, knots), (1, 6)), T.LREAL))      # TRJ_PLAYBACK_SLOPE
    return sum(model.layout(array)[0] for array in arrays)


def max_knots() -> int:
    """The most knots a table may have under both limits."""
    return min(MAX_ARRAY_ELEMENTS // 6, TABLE_BYTES_MAX // table_bytes(1))


def max_rows() -> int:
    """The most rows a recorded motion may have: the knots less the ones the table adds."""
    return max_knots() - ADDED_KNOTS


def check_table_fits(table: PlaybackTable) -> None:
    """Raise :class:`PlaybackError` (``file:1:1: ...``) when the table is too large for the controller."""
    knots = len(table.t)
    if knots > max_knots():
        raise PlaybackError(
            f"{table.source}:1:1: {knots - ADDED_KNOTS} rows is too large for the controller: at most {max_rows()} rows "
            f"({table_bytes(knots)} bytes against {TABLE_BYTES_MAX} bytes for the table, "
            f"{knots * 6} elements against {MAX_ARRAY_ELEMENTS} per array); resample the recording")

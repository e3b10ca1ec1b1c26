"""Whether a source is a test file: a line that starts with `TEST 'name'`.

Apart from the runner so that `stgen check` can ask without importing the
controller and the rest of what running tests needs.
"""

from __future__ import annotations

import re

_TEST_LINE = re.compile(r"^[ \t]*TEST[ \t]*['\"]", re.IGNORECASE | re.MULTILINE)


def is_test_source(text: str) -> bool:
    return _TEST_LINE.search(text) is not None

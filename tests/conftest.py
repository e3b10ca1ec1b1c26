"""Shared pytest configuration: the Hypothesis profile.

Under CI (the environment variable CI is set, as GitHub Actions, GitLab CI
and most runners do) property tests run derandomized: each test's examples
derive from the test itself, the example database is off, so a CI run
passes or fails the same way every time and never by chance.  Locally the
"dev" profile keeps exploring fresh random examples on every run.  Both
print the `@reproduce_failure` blob of a failing example.
HYPOTHESIS_PROFILE=ci|dev picks a profile explicitly.
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
settings.register_profile("dev", print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE") or ("ci" if os.environ.get("CI") else "dev"))

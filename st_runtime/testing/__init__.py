"""Unit tests written in ST (STruC++'s TEST blocks), run in the simulated controller.

    from st_runtime.testing import run_tests, junit_xml
    run = run_tests(["src/", "tests/test_counter.st"])
    print(run.render()); open("report.xml", "w").write(junit_xml(run))
"""

from .detect import is_test_source

__all__ = ["TestResult", "TestRun", "is_test_source", "junit_xml", "run_tests"]

#: Imported on first use (PEP 562), so that `testing.detect` alone stays light.
_LAZY = {"junit_xml": "junit", "TestResult": "runner", "TestRun": "runner", "run_tests": "runner"}


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from importlib import import_module

    value = globals()[name] = getattr(import_module(f"{__name__}.{module}"), name)
    return value

"""Unit tests written in ST (STruC++'s TEST blocks), run in the simulated controller.

    from st_runtime.testing import run_tests, junit_xml
    run = run_tests(["src/", "tests/test_counter.st"])
    print(run.render()); open("report.xml", "w").write(junit_xml(run))
"""

from .junit import junit_xml
from .runner import TestResult, TestRun, is_test_source, run_tests

__all__ = ["TestResult", "TestRun", "is_test_source", "junit_xml", "run_tests"]

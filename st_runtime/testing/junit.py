"""JUnit XML of a test run, in the Ant/Surefire form CI systems read.

Elements and attributes are those of the Jenkins xUnit plugin's schema
junit-10.xsd (kept in tests/schemas, which validates this output):
<testsuites> holds one <testsuite> per test file (name, tests, failures,
errors, skipped, time, timestamp, file); each <testcase> (name, classname,
time) holds a <failure> (failed assert) or an <error> (runtime fault or a
test that never ends) whose text is the full report with file:line.
"""

from __future__ import annotations

import datetime
import xml.etree.ElementTree as ET

SUITE_NAME = "stgen test"


def junit_xml(run) -> str:
    root = ET.Element("testsuites", name=SUITE_NAME, tests=str(len(run.results)),
                      failures=str(run.count("failed")), errors=str(run.count("error")),
                      time=_seconds(sum(r.seconds for r in run.results)))
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%S")
    files = list(dict.fromkeys(r.file for r in run.results))
    for path in files:
        results = [r for r in run.results if r.file == path]
        suite = ET.SubElement(root, "testsuite", name=path, tests=str(len(results)),
                              failures=str(sum(r.status == "failed" for r in results)),
                              errors=str(sum(r.status == "error" for r in results)),
                              skipped="0", time=_seconds(sum(r.seconds for r in results)),
                              timestamp=stamp, file=path)
        for r in results:
            case = ET.SubElement(suite, "testcase", name=r.name, classname=_classname(path),
                                 time=_seconds(r.seconds))
            if r.status != "passed":
                tag = "failure" if r.status == "failed" else "error"
                kind = "AssertionError" if tag == "failure" else "RuntimeFault"
                element = ET.SubElement(case, tag, message=r.message, type=kind)
                element.text = r.detail
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def _seconds(value: float) -> str:
    return f"{value:.3f}"


def _classname(path: str) -> str:
    """`tests/test_counter.st` -> `tests.test_counter` (how CI groups the cases)."""
    stem = path[:-3] if path.lower().endswith(".st") else path
    return stem.replace("\\", "/").strip("/").replace("/", ".")

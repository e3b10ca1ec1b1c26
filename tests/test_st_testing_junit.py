"""`stgen test --junit`: the report validates against the Jenkins JUnit schema.

tests/schemas/junit-10.xsd is the schema of the Jenkins xUnit plugin (MIT,
see tests/schemas/SOURCES.md), the Ant/Surefire format CI systems read.
"""

from __future__ import annotations

import os

from lxml import etree

from stgen.cli import main

HERE = os.path.dirname(__file__)
SCHEMA = etree.XMLSchema(etree.parse(os.path.join(HERE, "schemas", "junit-10.xsd")))
LIB = os.path.join(HERE, "st_testing", "lib.st")
PASSING = os.path.join(HERE, "st_testing", "test_pass.st")
FAILING = os.path.join(HERE, "st_testing", "test_fail.st")


def _report(tmp_path, *files) -> etree._ElementTree:
    out = tmp_path / "report.xml"
    main(["test", LIB, *files, "--junit", str(out)])
    return etree.parse(str(out))


def test_report_of_failures_validates_and_counts(tmp_path):
    doc = _report(tmp_path, PASSING, FAILING)
    SCHEMA.assertValid(doc)
    root = doc.getroot()
    assert (root.tag, root.get("tests"), root.get("failures"), root.get("errors")) == \
        ("testsuites", "9", "3", "1")
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    assert set(suites) == {PASSING, FAILING}
    failing = suites[FAILING]
    assert (failing.get("tests"), failing.get("failures"), failing.get("errors")) == ("4", "3", "1")
    case = failing.find("testcase[@name='equal fails with both values']")
    failure = case.find("failure")
    assert failure.get("type") == "AssertionError"
    assert failure.text.startswith(f"{FAILING}:7:5:") and "left = 1, right = 3" in failure.text
    error = failing.find("testcase[@name='a runtime fault is an error']/error")
    assert error is not None and "F-DIV-ZERO" in error.text


def test_report_of_a_green_run_validates(tmp_path):
    doc = _report(tmp_path, PASSING)
    SCHEMA.assertValid(doc)
    cases = doc.getroot().findall("testsuite/testcase")
    assert len(cases) == 5 and all(len(c) == 0 for c in cases)


def test_schema_refuses_a_broken_report():
    """The validation can fail: a testsuite without its required counts."""
    doc = etree.fromstring(b"<testsuites><testsuite name='x'/></testsuites>")
    assert not SCHEMA.validate(doc)

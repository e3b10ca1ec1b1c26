"""The status/ErrorID table shared with the ST templates."""

from __future__ import annotations

from stgen.error_codes import ERROR_ID_BASE, ErrorCode


def test_codes_are_fixed():
    assert [(member.name, int(member)) for member in ErrorCode] == [
        ("OK", 0),
        ("SINGULAR_JACOBIAN", 1),
        ("NOT_CONVERGED", 2),
        ("NON_FINITE", 3),
        ("UNREACHABLE", 4),
    ]


def test_error_ids_are_words_with_base_16_1000():
    assert ERROR_ID_BASE == 0x1000
    assert ErrorCode.OK.error_id == 0 and ErrorCode.OK.st_literal == "16#0000"
    assert ErrorCode.SINGULAR_JACOBIAN.error_id == 0x1001
    assert ErrorCode.UNREACHABLE.st_literal == "16#1004"
    assert all(0 <= member.error_id <= 0xFFFF for member in ErrorCode)


def test_names_and_descriptions_for_the_templates():
    assert ErrorCode.NOT_CONVERGED.st_constant_name == "ERR_NOT_CONVERGED"
    assert ErrorCode.OK.st_constant_name == "ERR_OK"
    assert all(member.description for member in ErrorCode)
    assert ErrorCode(3) is ErrorCode.NON_FINITE

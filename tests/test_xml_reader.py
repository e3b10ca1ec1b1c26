"""st_runtime reads PLCopen TC6 XML 2.01 and IEC 61131-10 XML: ST bodies, interfaces, diagnostics, hostile input.

The documents here are written by hand after the two schemas' element names
(PLCopen TC6 XML 2.01; IEC 61131-10 as Sysmac Studio writes it, see
docs/nj501.md); expected values are worked out by hand.
"""

from __future__ import annotations

import math
import time

import pytest

from st_runtime import LoadError, api
from st_runtime.loader import load
from st_runtime.xml_reader import read_xml

TC6_HEAD = ('<?xml version="1.0" encoding="utf-8"?>\n'
            '<project xmlns="http://www.plcopen.org/xml/tc6_0201" xmlns:xhtml="http://www.w3.org/1999/xhtml">\n')
IEC10_HEAD = ('<?xml version="1.0" encoding="utf-8"?>\n'
              '<Project xmlns="www.iec.ch/public/TC65SC65BWG7TF10" '
              'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" schemaVersion="1">\n')


def tc6(pous: str, instances: str = "", data_types: str = "") -> str:
    return (TC6_HEAD + "<types><dataTypes>" + data_types + "</dataTypes><pous>\n" + pous + "</pous></types>\n"
            "<instances><configurations>" + instances + "</configurations></instances>\n</project>\n")


def iec10(pous: str, globals_: str = "") -> str:
    return (IEC10_HEAD + "<Types><GlobalNamespace>\n" + pous + "</GlobalNamespace></Types>\n"
            '<Instances><Configuration name="C"><Resource name="R" resourceTypeName="">\n' + globals_ +
            "</Resource></Configuration></Instances>\n</Project>\n")


HYPOT_TC6 = tc6("""<pou name="Hyp" pouType="function">
<interface>
<returnType><LREAL/></returnType>
<inputVars>
<variable name="a"><type><LREAL/></type></variable>
<variable name="b"><type><LREAL/></type><initialValue><simpleValue value="4.0"/></initialValue></variable>
</inputVars>
</interface>
<body><ST><xhtml:p><![CDATA[
Hyp := SQRT(a * a + b * b);
]]></xhtml:p></ST></body>
</pou>
""")


def test_a_tc6_function_with_a_cdata_body_is_called():
    project = api.load_sources({"hyp.xml": HYPOT_TC6})
    assert project.call("Hyp", {"a": 3.0})["outputs"]["return"] == 5.0  # b defaults to 4.0: 3-4-5


def test_a_tc6_body_as_escaped_xhtml_text_and_a_global_list_of_the_configuration():
    text = tc6("""<pou name="Main" pouType="program">
<interface>
<externalVars constant="true"><variable name="Limit"><type><INT/></type></variable></externalVars>
<localVars><variable name="Count"><type><INT/></type></variable></localVars>
</interface>
<body><ST><xhtml:p>IF Count &lt; Limit THEN Count := Count + 1; END_IF;</xhtml:p></ST></body>
</pou>
""", """<configuration name="Cfg"><resource name="Res"><globalVars constant="true">
<variable name="Limit"><type><INT/></type><initialValue><simpleValue value="3"/></initialValue></variable>
</globalVars></resource></configuration>""")
    plc = api.load_sources({"main.xml": text}).controller(period="1ms")
    main = plc.add_program("Main")
    plc.run(5)
    assert main["Count"] == 3  # counts to Limit and stops


def test_a_codesys_v3_5_export_tc6_2_00_with_an_xhtml_element_body():
    """CODESYS V3.5 writes namespace tc6_0200 and the body as <ST><xhtml xmlns=...>text</xhtml></ST>."""
    text = """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0200">
  <fileHeader companyName="" productName="CODESYS" productVersion="CODESYS V3.5 SP19" creationDateTime="2026-01-01T00:00:00" />
  <contentHeader name="Export.project"><coordinateInfo><fbd><scaling x="1" y="1" /></fbd><ld><scaling x="1" y="1" /></ld><sfc><scaling x="1" y="1" /></sfc></coordinateInfo></contentHeader>
  <types><dataTypes /><pous>
    <pou name="Twice" pouType="function">
      <interface><returnType><INT /></returnType><inputVars><variable name="x"><type><INT /></type></variable></inputVars>
        <addData><data name="http://www.3s-software.com/plcopenxml/attributes" handleUnknown="implementation"><Attributes /></data></addData>
      </interface>
      <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">Twice := x * 2;</xhtml></ST></body>
      <addData />
    </pou>
  </pous></types>
  <instances><configurations /></instances>
</project>
"""
    assert api.load_sources({"codesys.xml": text}).call("Twice", {"x": 21})["outputs"]["return"] == 42


def test_tc6_array_struct_and_enum_types_with_array_initial_values():
    data_types = """<dataType name="Pair"><baseType><struct>
<variable name="x"><type><DINT/></type></variable>
<variable name="y"><type><DINT/></type><initialValue><simpleValue value="7"/></initialValue></variable>
</struct></baseType></dataType>
<dataType name="Colour"><baseType><enum><values><value name="Red"/><value name="Green"/></values></enum></baseType></dataType>
"""
    text = tc6("""<pou name="Sum" pouType="function">
<interface><returnType><DINT/></returnType>
<localVars>
<variable name="v"><type><array><dimension lower="1" upper="4"/><baseType><DINT/></baseType></array></type>
<initialValue><arrayValue><value repetitionValue="2"><simpleValue value="5"/></value><value><simpleValue value="1"/></value><value><simpleValue value="2"/></value></arrayValue></initialValue></variable>
<variable name="p"><type><derived name="Pair"/></type></variable>
<variable name="c"><type><derived name="Colour"/></type><initialValue><simpleValue value="Colour#Green"/></initialValue></variable>
</localVars></interface>
<body><ST><xhtml:p><![CDATA[Sum := v[1] + v[2] + v[3] + v[4] + p.y; IF c = Colour#Green THEN Sum := Sum + 100; END_IF;]]></xhtml:p></ST></body>
</pou>
""", data_types=data_types)
    project = api.load_sources({"sum.xml": text})
    assert project.call("Sum", {})["outputs"]["return"] == 5 + 5 + 1 + 2 + 7 + 100


def test_an_iec_61131_10_function_block_as_sysmac_studio_writes_it():
    text = iec10("""<FunctionBlock name="Acc">
<Parameters>
<InputVars><Variable name="Step" orderWithinParamSet="0"><Type><TypeName>LREAL</TypeName></Type></Variable></InputVars>
<OutputVars><Variable name="Total" orderWithinParamSet="1"><Type><TypeName>LREAL</TypeName></Type></Variable></OutputVars>
</Parameters>
<ExternalVars constant="true"><Variable name="Gains"><Type><InstantlyDefinedType xsi:type="ArrayTypeSpec"><BaseType><TypeName>LREAL</TypeName></BaseType><DimensionSpec dimensionNumber="1"><IndexRange lower="0" upper="1"/></DimensionSpec></InstantlyDefinedType></Type></Variable></ExternalVars>
<Vars accessSpecifier="private"><Variable name="Calls"><Type><TypeName>INT</TypeName></Type></Variable></Vars>
<MainBody><BodyContent xsi:type="ST"><ST>Calls := Calls + 1;
Total := Total + Step * Gains[1];</ST></BodyContent></MainBody>
</FunctionBlock>
""", """<GlobalVars constant="true"><Variable name="Gains"><Type><InstantlyDefinedType xsi:type="ArrayTypeSpec">
<BaseType><TypeName>LREAL</TypeName></BaseType><DimensionSpec dimensionNumber="1"><IndexRange lower="0" upper="1"/></DimensionSpec>
</InstantlyDefinedType></Type><InitialValue><ArrayValue><Value><SimpleValue value="1.0"/></Value><Value><SimpleValue value="2.5"/></Value></ArrayValue></InitialValue></Variable></GlobalVars>
""")
    project = api.load_sources({"acc.xml": text}, dialect="nj")
    result = project.call("Acc", {"Step": 2.0})  # an FB without --until: one scan
    assert result["outputs"]["Total"] == 5.0  # 2.0 * Gains[1] = 2.0 * 2.5


def test_sysmac_axis_type_is_read_as_axis_ref():
    st_text, problems = read_xml(iec10("", '<GlobalVars><Variable name="Ax"><Type><TypeName>_sAXIS_REF</TypeName></Type>'
                                        '</Variable></GlobalVars>'), "ax.xml")
    assert problems == [] and "Ax : AXIS_REF;" in st_text


# --------------------------------------------------------------------------- positions


def test_a_body_error_points_at_its_line_and_column_in_the_xml_file():
    text = HYPOT_TC6.replace("Hyp := SQRT(a * a + b * b);", "Hyp := SQRT(a * a + b * b) + missing;")
    result = load_via_texts({"hyp.xml": text})
    [error] = result.errors
    lines = text.splitlines()
    line = next(i for i, t in enumerate(lines, 1) if "missing" in t)
    assert (error.pos.file, error.pos.line, error.pos.col) == ("hyp.xml", line, lines[line - 1].index("missing") + 1)
    assert "missing" in result.render()  # the caret is shown under the XML line


def test_a_declaration_error_points_at_the_variable_element():
    text = HYPOT_TC6.replace('<variable name="a"><type><LREAL/></type>', '<variable name="a"><type><derived name="NoSuchType"/></type>')
    result = load_via_texts({"hyp.xml": text})
    lines = text.splitlines()
    line = next(i for i, t in enumerate(lines, 1) if "NoSuchType" in t)
    assert [e.pos.line for e in result.errors] == [line]
    assert "NoSuchType" in result.render()


def test_a_duplicate_declaration_points_at_the_name_attribute_value():
    text = HYPOT_TC6.replace('<variable name="b">', '<variable name="a">')
    result = load_via_texts({"hyp.xml": text})
    lines = text.splitlines()
    line = [i for i, t in enumerate(lines, 1) if '<variable name="a">' in t][1]
    first = result.errors[0]  # then the body's uses of the now undeclared b
    assert (first.pos.line, first.pos.col) == (line, len('<variable name="') + 1) and "'a'" in first.message


def load_via_texts(texts):
    from st_runtime.loader import load_texts

    return load_texts(texts)


# --------------------------------------------------------------------------- not ST, not complete, not the format


@pytest.mark.parametrize("body,language", [
    ("<body><LD></LD></body>", "LD"),
    ("<body><FBD></FBD></body>", "FBD"),
    ("<body><SFC></SFC></body>", "SFC"),
    ("<body><IL><xhtml:p>LD 1</xhtml:p></IL></body>", "IL"),
])
def test_a_tc6_body_in_another_language_is_named_with_its_pou(body, language):
    text = tc6(f'<pou name="Graphic" pouType="program"><interface/>{body}</pou>\n')
    _st, [problem] = read_xml(text, "g.xml")
    assert problem.code == "E-XML-005"
    assert "'Graphic'" in problem.message and f"in {language}," in problem.message


def test_the_st_pous_beside_a_graphical_one_are_still_checked():
    text = tc6('<pou name="Graphic" pouType="functionBlock"><interface><inputVars><variable name="In">'
               '<type><BOOL/></type></variable></inputVars></interface><body><FBD/></body></pou>\n'
               '<pou name="Main" pouType="program"><interface><localVars><variable name="G"><type>'
               '<derived name="Graphic"/></type></variable></localVars></interface>\n'
               '<body><ST><xhtml:p>G(In := TRUE); Undeclared := 1;</xhtml:p></ST></body></pou>\n')
    result = load_via_texts({"mixed.xml": text})
    assert [(d.code, d.pos.line) for d in result.errors][0] == ("E-XML-005", 4)
    assert [d.code for d in result.errors][1:] and "Undeclared" in result.render()  # Main checked; G(...) fine
    assert "'G'" not in result.render() and not result.ok


def test_a_sysmac_ladder_section_is_named_ld():
    text = iec10('<Program name="Rungs"><MainBody><BodyContent xsi:type="smcext:LdSection" '
                 'xmlns:smcext="https://www.ia.omron.com/Smc" name="Section0"/></MainBody></Program>\n')
    _st, [problem] = read_xml(text, "l.xml")
    assert problem.code == "E-XML-005" and "'Rungs'" in problem.message and "in LD," in problem.message


def test_a_pou_without_body_and_a_function_without_result_type():
    text = tc6('<pou name="Empty" pouType="program"><interface/></pou>\n'
               '<pou name="F" pouType="function"><interface/><body><ST><xhtml:p>;</xhtml:p></ST></body></pou>\n')
    _st, problems = read_xml(text, "e.xml")
    assert [p.code for p in problems] == ["E-XML-004", "E-XML-004"]
    assert "'Empty' has no body" in problems[0].message and "function 'F' without a result type" in problems[1].message
    assert [p.pos.line for p in problems] == [4, 5]


def test_a_type_that_is_not_st_is_named():
    text = tc6('<pou name="P" pouType="program"><interface><localVars><variable name="p">'
               '<type><pointer><baseType><INT/></baseType></pointer></type></variable></localVars></interface>'
               '<body><ST><xhtml:p>;</xhtml:p></ST></body></pou>\n')
    _st, [problem] = read_xml(text, "p.xml")
    assert problem.code == "E-XML-006" and "P.p" in problem.message and "<pointer>" in problem.message


@pytest.mark.parametrize("root", [
    '<project xmlns="urn:example:plc"/>',
    '<Project xmlns="www.iec.ch/public/TC65SC65BWG7TF10/Other"/>',
    '<project/>',
    '<html xmlns="http://www.w3.org/1999/xhtml"/>',
])
def test_another_namespace_or_root_is_refused_by_name(root):
    _st, [problem] = read_xml('<?xml version="1.0"?>\n' + root, "w.xml")
    assert problem.code == "E-XML-003" and problem.pos.line == 2
    assert "http://www.plcopen.org/xml/tc6_0201" in problem.message


def test_not_well_formed_xml_is_reported_at_its_line():
    text = TC6_HEAD + "<types>\n<pous>\n</types>\n"
    _st, [problem] = read_xml(text, "bad.xml")
    assert problem.code == "E-XML-001" and problem.pos.line == 5  # the mismatched </types>


BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [
 <!ENTITY lol "lol">
 <!ENTITY lol1 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol2 "&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
 <!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
 <!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
 <!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
 <!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
 <!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">
]>
<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous><pou name="P" pouType="program">
<body><ST><xhtml:p xmlns:xhtml="http://www.w3.org/1999/xhtml">&lol9;</xhtml:p></ST></body></pou></pous></types></project>
"""


def test_billion_laughs_is_refused_at_its_doctype():
    _st, [problem] = read_xml(BILLION_LAUGHS, "lol.xml")
    assert problem.code == "E-XML-002" and (problem.pos.line, problem.pos.col) == (2, 1)


def test_an_external_entity_is_refused_and_the_file_never_read(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET-CONTENT", encoding="utf-8")
    text = (f'<?xml version="1.0"?>\n<!DOCTYPE p [<!ENTITY x SYSTEM "{secret.as_uri()}">]>\n'
            '<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous><pou name="P" pouType="program">'
            '<body><ST><xhtml:p xmlns:xhtml="http://www.w3.org/1999/xhtml">&x;</xhtml:p></ST></body>'
            '</pou></pous></types></project>\n')
    path = tmp_path / "xxe.xml"
    path.write_text(text, encoding="utf-8")
    result = load([str(path)])
    assert [d.code for d in result.errors] == ["E-XML-002"]
    assert "TOP-SECRET" not in result.render().replace(secret.as_uri(), "")


def test_the_parser_itself_neither_expands_without_bound_nor_reads_external_entities(tmp_path):
    """Defence in depth, below the DOCTYPE refusal: the lxml parser as configured."""
    from lxml import etree

    from st_runtime.xml_reader import _parser

    started = time.perf_counter()
    try:
        root = etree.fromstring(BILLION_LAUGHS.encode(), _parser())
        assert "lol" not in "".join(next(root.iter("{http://www.w3.org/1999/xhtml}p")).itertext())
    except etree.XMLSyntaxError as exc:  # libxml2's amplification limit stops it
        assert "amplification" in str(exc)
    assert time.perf_counter() - started < 5  # a guard against a hang, not a speed test
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET-CONTENT", encoding="utf-8")
    xxe = f'<!DOCTYPE p [<!ENTITY x SYSTEM "{secret.as_uri()}">]><p>&x;</p>'
    root = etree.fromstring(xxe.encode(), _parser())
    assert "TOP-SECRET" not in "".join(root.itertext())


def test_load_raises_loaderror_not_a_traceback_for_broken_xml():
    with pytest.raises(LoadError) as caught:
        api.load_sources({"bad.xml": "<project"})
    assert "bad.xml:1:" in str(caught.value.render())


def test_stgen_check_reports_xml_problems_gcc_style(tmp_path, capsys):
    from stgen.cli import main

    path = tmp_path / "ld.xml"
    path.write_text(tc6('<pou name="Rung" pouType="program"><interface/><body><LD/></body></pou>\n'), encoding="utf-8")
    assert main(["check", str(path)]) == 1
    err = capsys.readouterr().err
    assert f"{path}:4:" in err and "error[E-XML-005]" in err and "Traceback" not in err


def test_hyp_from_xml_agrees_with_math_hypot():
    project = api.load_sources({"hyp.xml": HYPOT_TC6})
    assert project.call("Hyp", {"a": 1.5, "b": 2.0})["outputs"]["return"] == pytest.approx(math.hypot(1.5, 2.0))


# --------------------------------------------------------------------------- fuzz

from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_SMALL_SYSMAC = None


def _documents() -> list[str]:
    from stgen.exports import sysmac_xml
    from stgen.render import render_program

    global _SMALL_SYSMAC
    if _SMALL_SYSMAC is None:
        program = render_program()
        small = type(program)(tuple(p for p in program.pous if p.name in ("SP_Constants", "SP_Atan2", "SP_Jacobian")))
        _SMALL_SYSMAC = sysmac_xml.document(small)
    return [HYPOT_TC6, _SMALL_SYSMAC]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(st.integers(0, 1), st.integers(0, 10**6), st.integers(0, 200), st.text(max_size=20))
def test_a_mutated_document_gives_st_or_diagnostics_never_an_exception(which, start, length, insert):
    document = _documents()[which]
    start %= len(document)
    mutated = document[:start] + insert + document[start + length:]
    st_text, problems = read_xml(mutated, "m.xml")
    assert (st_text is not None) or problems
    assert all(p.code.startswith("E-XML") and p.code != "E-XML-099" for p in problems)
    assert all(p.pos.line >= 1 and p.pos.col >= 1 for p in problems)

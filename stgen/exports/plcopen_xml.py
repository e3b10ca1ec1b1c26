"""PLCopen TC6 XML 2.01: the whole program as one file for CODESYS, TwinCAT, Beremiz/OpenPLC and others.

Layout (PLCopen TC6 XML schema 2.01, namespace ``http://www.plcopen.org/xml/tc6_0201``):
``project`` with ``fileHeader`` and ``contentHeader``; ``types/pous/pou`` for
every POU in dependency order, with its ``interface`` (``returnType`` for a
function, then the variable lists ``inputVars``, ``outputVars``,
``inOutVars``, ``externalVars``, ``localVars``, ``constant="true"`` on a list
of constants) and its ``body/ST`` as an xhtml paragraph; the global variable
lists in ``instances/configurations/configuration/resource/globalVars``,
constants in their own list. Elementary types are elements (``<LREAL/>``),
function block and other named types ``<derived name="..."/>``, arrays
``<array><dimension lower=".." upper=".."/>...<baseType>..</baseType></array>``.

The axis variables are written like every other global (type ``AXIS_REF`` as
a derived type): map it to your tool's PLCopen axis type after the import.
The task is not written: run ``SP_Controller`` in the primary periodic task.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from st_runtime import ast
from st_runtime.printer import format_expr
from stgen.exports import xml_common
from stgen.exports.folder import FolderUpdate, write_files
from stgen.render import RenderedProgram

NS = "http://www.plcopen.org/xml/tc6_0201"
XHTML = "http://www.w3.org/1999/xhtml"
CREATION_TIME = "2026-01-01T00:00:00"  # fixed: a regeneration gives the same bytes

FILE_NAME = "StewartPlatform.plcopen.xml"
PROJECT_NAME = "StewartPlatform"

#: Elementary types written as elements of their own (the schema's group ``elementaryTypes``).
ELEMENTARY = frozenset({"BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT", "UINT",
                        "UDINT", "ULINT", "REAL", "LREAL", "TIME", "DATE", "DT", "TOD"})
_KINDS = {"FUNCTION": "function", "FUNCTION_BLOCK": "functionBlock", "PROGRAM": "program"}
_LISTS = {"VAR_INPUT": "inputVars", "VAR_OUTPUT": "outputVars", "VAR_IN_OUT": "inOutVars",
          "VAR_EXTERNAL": "externalVars", "VAR": "localVars", "VAR_TEMP": "tempVars", "VAR_GLOBAL": "globalVars"}
_VALUES = xml_common.ValueNames(simple="simpleValue", array="arrayValue", value="value", struct="structValue")


def _e(parent, tag: str, attrs: dict | None = None):
    return etree.SubElement(parent, f"{{{NS}}}{tag}", attrs or {})


def _xhtml(parent, tag: str, text) -> None:
    """A formattedText element: one xhtml paragraph holding ``text``."""
    paragraph = etree.SubElement(_e(parent, tag), f"{{{XHTML}}}p")
    paragraph.text = text


def _type(parent, tag: str, type_ref) -> None:
    holder = _e(parent, tag)
    if isinstance(type_ref, ast.ArrayType):
        array = _e(holder, "array")
        for lower, upper in xml_common.bounds(type_ref):
            _e(array, "dimension", {"lower": lower, "upper": upper})
        _type(array, "baseType", type_ref.element)
    elif isinstance(type_ref, ast.StringType):
        attrs = {} if type_ref.length is None else {"length": format_expr(type_ref.length)}
        _e(holder, "wstring" if type_ref.wide else "string", attrs)
    elif type_ref.name.upper() in ELEMENTARY:
        _e(holder, type_ref.name.upper())
    else:
        _e(holder, "derived", {"name": type_ref.name})


def _variables(parent, block: ast.VarBlock, comments: dict[str, str]) -> None:
    attrs = {name: "true" for name, on in (("constant", block.constant), ("retain", block.retain)) if on}
    holder = _e(parent, _LISTS[block.kind], attrs)
    for decl in block.decls:
        variable = _e(holder, "variable", {"name": decl.name})
        _type(variable, "type", decl.type)
        if decl.init is not None:
            xml_common.add_value(_e(variable, "initialValue"), NS, _VALUES, decl.init)
        if comments.get(decl.name):
            _xhtml(variable, "documentation", comments[decl.name])


def _pou(parent, pou, declared: xml_common.Declared) -> None:
    element = _e(parent, "pou", {"name": pou.name, "pouType": _KINDS[pou.kind]})
    interface = _e(element, "interface")
    if declared.return_type is not None:
        _type(interface, "returnType", declared.return_type)
    for block in declared.blocks:
        _variables(interface, block, declared.comments)
    body = _e(element, "body")
    _xhtml(body, "ST", xml_common.body_cdata(pou.body))
    _xhtml(element, "documentation", pou.header.strip().removeprefix("(*").removesuffix("*)").strip())


def document(program: RenderedProgram) -> str:
    """The PLCopen TC6 XML 2.01 text of the whole program."""
    root = etree.Element(f"{{{NS}}}project", nsmap={None: NS, "xhtml": XHTML})
    _e(root, "fileHeader", {"companyName": "stgen", "productName": "stgen", "productVersion": "0.1.0",
                            "creationDateTime": CREATION_TIME,
                            "contentDescription": "Stewart platform kinematics and controller, generated by stgen"})
    header = _e(root, "contentHeader", {"name": PROJECT_NAME})
    coordinates = _e(header, "coordinateInfo")
    for language in ("fbd", "ld", "sfc"):
        _e(_e(coordinates, language), "scaling", {"x": "1", "y": "1"})
    types = _e(root, "types")
    _e(types, "dataTypes")
    pous = _e(types, "pous")
    global_lists = []
    for pou in program.pous:
        declared = xml_common.declared(pou)
        if pou.kind == "VAR_GLOBAL":
            global_lists.append(declared)
        else:
            _pou(pous, pou, declared)
    configuration = _e(_e(_e(root, "instances"), "configurations"), "configuration", {"name": PROJECT_NAME})
    resource = _e(configuration, "resource", {"name": "MainResource"})
    for declared in global_lists:
        for block in declared.blocks:
            _variables(resource, block, declared.comments)
    return xml_common.serialise(root)


def files(program: RenderedProgram) -> dict[str, str]:
    return {FILE_NAME: document(program)}


#: First lines that mark a file in the folder as written by this export (see :mod:`stgen.exports.folder`).
SIGNATURES = frozenset({xml_common.FIRST_LINE})


def write(program: RenderedProgram, out_dir: str | Path) -> FolderUpdate:
    """Write :func:`files` into ``out_dir`` and remove the stale files of earlier runs."""
    return write_files(files(program), out_dir, SIGNATURES)

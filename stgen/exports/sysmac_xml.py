"""OMRON Sysmac Studio (1.30 and later): the whole program as one IEC 61131-10 XML file.

One import of the XML file in Sysmac Studio brings in every POU with its
interface and ST body and the global variables, instead of the 51 steps of the
variable-table route (9 POUs created, 2 return types set, 40 pastes of table
rows and bodies) (:mod:`stgen.exports.sysmac`, kept
as the fallback for older Sysmac Studio versions).

The layout follows what was learned from files that Sysmac Studio imported
(sources: docs/nj501.md, section "XML import"):

* root ``Project`` in the namespace ``www.iec.ch/public/TC65SC65BWG7TF10``,
  ``schemaVersion="1"``, OMRON's extension namespace ``smcext`` and its
  schema location ``https://www.ia.omron.com/Smc IEC61131_10_Ed1_0_SmcExt1_0_Spc1_0.xsd``;
  a ``FileHeader`` naming the product version the file targets (Sysmac
  Studio 1.30, the first that imports IEC 61131-10);
* the POUs under ``Types/GlobalNamespace`` in dependency order (a POU only
  uses POUs written before it); parameters in ``Parameters`` with one
  ``orderWithinParamSet`` counter running on from the inputs to the outputs;
  globals a POU uses in ``ExternalVars`` (``constant="true"`` for the
  constants), name and type only; locals in ``Vars accessSpecifier="private"``;
  the body as ``MainBody/BodyContent xsi:type="ST"/ST``;
* an array type as ``InstantlyDefinedType xsi:type="ArrayTypeSpec"`` with a
  ``BaseType`` and one ``DimensionSpec`` per dimension, never a ``TypeName``
  "ARRAY..." (that passes the schema but the import fails: docs/nj501.md);
* the global variables under ``Instances/Configuration/Resource`` in one
  ``GlobalVars`` container per (Constant, Retain) combination, the two being
  attributes of the container, not of the variable; Network Publish as
  ``AddData/Data/smcext:GlobalVariableAdditionalProperties networkPublish``;
* ``Variable`` children in the schema's order: Documentation, AddData, Type,
  InitialValue.

The axis variables (``AXIS_REF``) are left out, as from the variable tables:
Sysmac Studio creates them with the axes (``_sAXIS_REF``). Task assignment is
not part of the format: ``SP_Controller`` is assigned to the primary task by
hand (generated/nj501/README.md).

Not confirmed by a source at hand, and said so in docs/nj501.md: array initial
values as ``ArrayValue/Value/SimpleValue`` (the IEC 61131-10 structure; the
projects consulted only wrote simple values), and CDATA for the ST bodies
(equivalent XML; OMRON's sample escapes the text instead).
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from st_runtime import ast
from st_runtime.printer import format_type
from stgen.exports import xml_common
from stgen.exports.folder import FolderUpdate
from stgen.exports.sysmac import SYSTEM_CREATED_TYPES, sysmac_type
from stgen.render import RenderedProgram

NS = "www.iec.ch/public/TC65SC65BWG7TF10"
XSI = "http://www.w3.org/2001/XMLSchema-instance"
SMC = "https://www.ia.omron.com/Smc"
#: OMRON's extension schema, as the schema location and as the name of the AddData blocks.
SMC_SCHEMA = "https://www.ia.omron.com/Smc IEC61131_10_Ed1_0_SmcExt1_0_Spc1_0.xsd"
#: The product and version the file targets (FileHeader).
PRODUCT_NAME, PRODUCT_VERSION = "Sysmac Studio", "1.30.0.0"
#: ContentHeader creation time: fixed, so that a regeneration gives the same bytes.
CREATION_TIME = "2026-01-01T00:00:00"

FILE_NAME = "StewartPlatform.xml"
PROJECT_NAME = "StewartPlatform"

_VALUES = xml_common.ValueNames(simple="SimpleValue", array="ArrayValue", value="Value", struct="StructValue")
_KINDS = {"FUNCTION": "Function", "FUNCTION_BLOCK": "FunctionBlock", "PROGRAM": "Program"}
_PARAMETERS = (("VAR_INPUT", "InputVars"), ("VAR_OUTPUT", "OutputVars"), ("VAR_IN_OUT", "InOutVars"))


def _e(parent, tag: str, attrs: dict | None = None, text: str | None = None):
    element = etree.SubElement(parent, f"{{{NS}}}{tag}", attrs or {})
    if text is not None:
        element.text = text
    return element


def _documentation(parent, text: str) -> None:
    if text:
        _e(parent, "Documentation", {f"{{{XSI}}}type": "SimpleText"}, text)


def _type(parent, tag: str, type_ref) -> None:
    holder = _e(parent, tag)
    if isinstance(type_ref, ast.ArrayType):
        spec = _e(holder, "InstantlyDefinedType", {f"{{{XSI}}}type": "ArrayTypeSpec"})
        _type(spec, "BaseType", type_ref.element)
        for number, (lower, upper) in enumerate(xml_common.bounds(type_ref), start=1):
            dimension = _e(spec, "DimensionSpec", {"dimensionNumber": str(number)})
            _e(dimension, "IndexRange", {"lower": lower, "upper": upper})
    else:
        _e(holder, "TypeName", text=sysmac_type(format_type(type_ref)))


def _variable(parent, decl: ast.VarDecl, comment: str, order: int | None = None,
              publish: bool = False, plain: bool = False) -> None:
    attrs = {"name": decl.name}
    if order is not None:
        attrs["orderWithinParamSet"] = str(order)
    variable = _e(parent, "Variable", attrs)
    if not plain:
        _documentation(variable, comment)
    if publish:
        data = _e(_e(variable, "AddData"), "Data", {"name": SMC_SCHEMA, "handleUnknown": "discard"})
        etree.SubElement(data, f"{{{SMC}}}GlobalVariableAdditionalProperties", {"networkPublish": "DoNotPublish"})
    _type(variable, "Type", decl.type)
    if decl.init is not None and not plain:
        xml_common.add_value(_e(variable, "InitialValue"), NS, _VALUES, decl.init)


def _qualifiers(block: ast.VarBlock) -> dict:
    return {name: "true" for name, on in (("constant", block.constant), ("retain", block.retain)) if on}


def _pou(parent, pou, declared: xml_common.Declared) -> None:
    element = _e(parent, _KINDS[pou.kind], {"name": pou.name})
    _documentation(element, pou.header.strip().removeprefix("(*").removesuffix("*)").strip())
    if declared.return_type is not None:
        _type(element, "ResultType", declared.return_type)
    blocks = {(b.kind, b.constant): b for b in declared.blocks}
    parameters = [(tag, blocks[(kind, False)]) for kind, tag in _PARAMETERS if (kind, False) in blocks]
    if parameters:
        holder = _e(element, "Parameters")
        order = 0
        for tag, block in parameters:
            container = _e(holder, tag)
            for decl in block.decls:
                _variable(container, decl, declared.comments.get(decl.name, ""), order)
                order += 1
    for block in declared.blocks:
        if block.kind == "VAR_EXTERNAL":
            container = _e(element, "ExternalVars", _qualifiers(block))
            for decl in block.decls:
                _variable(container, decl, "", plain=True)
    for block in declared.blocks:
        if block.kind == "VAR":
            container = _e(element, "Vars", {"accessSpecifier": "private", **_qualifiers(block)})
            for decl in block.decls:
                _variable(container, decl, declared.comments.get(decl.name, ""))
    content = _e(_e(element, "MainBody"), "BodyContent", {f"{{{XSI}}}type": "ST"})
    _e(content, "ST").text = xml_common.body_cdata(pou.body)


def _globals(resource, global_lists) -> None:
    """One ``GlobalVars`` per (constant, retain), in the order of the global lists."""
    containers: dict[tuple[bool, bool], etree._Element] = {}
    for pou, declared in global_lists:
        for block in declared.blocks:
            decls = [d for d in block.decls if not (isinstance(d.type, ast.NamedType) and d.type.name in SYSTEM_CREATED_TYPES)]
            if not decls:
                continue
            key = (block.constant, block.retain)
            if key not in containers:
                containers[key] = _e(resource, "GlobalVars", _qualifiers(block))
            for decl in decls:
                _variable(containers[key], decl, declared.comments.get(decl.name, ""), publish=True)


def document(program: RenderedProgram) -> str:
    """The IEC 61131-10 XML text of the whole program."""
    root = etree.Element(f"{{{NS}}}Project", nsmap={None: NS, "xsi": XSI, "smcext": SMC})
    root.set(f"{{{XSI}}}schemaLocation", SMC_SCHEMA)
    root.set("schemaVersion", "1")
    _e(root, "FileHeader", {"companyName": "stgen", "productName": PRODUCT_NAME, "productVersion": PRODUCT_VERSION,
                            "contentDescription": "Stewart platform kinematics and controller, generated by stgen"})
    _e(root, "ContentHeader", {"name": PROJECT_NAME, "creationDateTime": CREATION_TIME})
    namespace = _e(_e(root, "Types"), "GlobalNamespace")
    global_lists = []
    for pou in program.pous:
        declared = xml_common.declared(pou)
        if pou.kind == "VAR_GLOBAL":
            global_lists.append((pou, declared))
        else:
            _pou(namespace, pou, declared)
    resource = _e(_e(_e(root, "Instances"), "Configuration", {"name": PROJECT_NAME}), "Resource",
                  {"name": "MainResource", "resourceTypeName": ""})
    _globals(resource, global_lists)
    return xml_common.serialise(root)


def files(program: RenderedProgram) -> dict[str, str]:
    return {FILE_NAME: document(program)}


def write(program: RenderedProgram, out_dir: str | Path) -> FolderUpdate:
    """Write :func:`files` into ``out_dir`` and remove the stale files of earlier runs."""
    return xml_common.write(files(program), out_dir)

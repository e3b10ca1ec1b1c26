"""Read PLCopen TC6 XML 2.01 and IEC 61131-10 XML (Sysmac Studio) files as Structured Text.

    st_texts, diagnostics = translate({"plc.xml": xml_text, "main.st": st_text})

An XML source is turned into ST text that the ordinary parser reads: each
POU's header, VAR blocks and declarations rebuilt from its interface, its ST
body taken verbatim (CDATA, an xhtml paragraph, or plain character data).
The ST text is laid out on the XML file's own lines: a declaration stands on
the line of its ``variable`` element and a body line on its line in the
file, at its column. So every diagnostic of the parser and the checker
points at the right line of the XML file (and, inside bodies written as
CDATA, at the right column), and the loader shows the XML line with the
caret.

Formats, told apart by the root element's namespace:

* PLCopen TC6 XML 2.01 (``http://www.plcopen.org/xml/tc6_0201``): CODESYS,
  TwinCAT, Beremiz/OpenPLC, Machine Expert, IronPLC, ``stgen generate
  --target plcopen``; also TC6 2.00 (``.../tc6_0200``, which CODESYS V3.5
  exports carry) and ``http://www.plcopen.org/xml/tc6.xsd`` (Beremiz
  projects), whose POU elements are the same;
* IEC 61131-10 (``www.iec.ch/public/TC65SC65BWG7TF10``): Sysmac Studio 1.30+,
  ``stgen generate --target sysmac-xml``. OMRON's axis type ``_sAXIS_REF``
  is read as the PLCopen ``AXIS_REF``.

Only ST bodies are read: a POU in LD, FBD, SFC or IL gets an error naming
it and its language (the load fails), and stands with its interface and an
empty body, so that the ST POUs of the file are still checked. Data types (structures, enumerations, aliases)
and global variable lists of the configuration are read; tasks are not
(``stgen run --program`` picks the program).

The file is read as UTF-8 text like every source (its encoding declaration
is not followed; PLCopen and Sysmac Studio files are UTF-8). The XML parser
is hardened: a document type declaration (where entity
definitions live) is refused, entities are never expanded, nothing is
fetched from the network and libxml2's limits for huge documents stay on,
so an entity expansion attack (billion laughs) or an external entity gets a
diagnostic and never reads another file or grows without bound.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from . import ast
from .diagnostics import Diagnostic, register

# lxml.etree, imported (`_lxml`) when the first XML file is read, not on
# every `stgen check` of ST files; every use below comes after a `_parse`.
etree = None

TC6 = "http://www.plcopen.org/xml/tc6_0201"
#: Namespaces of TC6 XML before 2.01 with the same elements for POUs, interfaces and bodies:
#: 2.00 (CODESYS V3.5 and TwinCAT exports carry it) and the earlier one Beremiz projects still carry.
TC6_EARLIER = ("http://www.plcopen.org/xml/tc6_0200", "http://www.plcopen.org/xml/tc6.xsd")
IEC10 = "www.iec.ch/public/TC65SC65BWG7TF10"
XSI = "http://www.w3.org/2001/XMLSchema-instance"

CODES = register({
    "E-XML-001": "the XML file is not well-formed",
    "E-XML-002": "a document type declaration (DTD, entities) in an XML file: refused",
    "E-XML-003": "the XML file is neither PLCopen TC6 XML 2.01 nor IEC 61131-10",
    "E-XML-004": "a required element or attribute is missing (POU body, name, type)",
    "E-XML-005": "a POU body in a language other than ST (LD, FBD, SFC, IL): not read",
    "E-XML-006": "a type or value element that cannot be read as ST",
    "E-XML-099": "internal XML reader error (a bug: please report it)",
})

#: TC6 elementary types: element name -> ST type name.
_TC6_ELEMENTARY = {name: name for name in (
    "BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT",
    "ULINT", "REAL", "LREAL", "TIME", "DATE", "DT", "TOD", "LTIME")}

#: IEC 61131-10 type names of Sysmac Studio read under their IEC/PLCopen names.
_IEC10_TYPE_ALIASES = {"_SAXIS_REF": "AXIS_REF"}

#: Variable list element -> ST keyword, per format.
_TC6_LISTS = {"inputVars": "VAR_INPUT", "outputVars": "VAR_OUTPUT", "inOutVars": "VAR_IN_OUT",
              "externalVars": "VAR_EXTERNAL", "localVars": "VAR", "tempVars": "VAR_TEMP",
              "globalVars": "VAR_GLOBAL"}
_IEC10_LISTS = {"InputVars": "VAR_INPUT", "OutputVars": "VAR_OUTPUT", "InOutVars": "VAR_IN_OUT",
                "ExternalVars": "VAR_EXTERNAL", "Vars": "VAR", "TempVars": "VAR_TEMP",
                "GlobalVars": "VAR_GLOBAL"}
_TC6_KINDS = {"function": "FUNCTION", "functionBlock": "FUNCTION_BLOCK", "program": "PROGRAM"}
_IEC10_KINDS = {"Function": "FUNCTION", "FunctionBlock": "FUNCTION_BLOCK", "Program": "PROGRAM"}

#: Body languages other than ST, by element (TC6) or xsi:type (IEC 61131-10; Sysmac: smcext:LdSection).
_LANGUAGES = {"IL": "IL", "FBD": "FBD", "LD": "LD", "SFC": "SFC", "LDSECTION": "LD", "FBDSECTION": "FBD"}


def is_xml(path: str) -> bool:
    return path.lower().endswith(".xml")


def translate(texts: dict[str, str]) -> tuple[dict[str, str | None], list[Diagnostic]]:
    """ST text for every ``.xml`` source in ``texts`` (``None`` when it cannot be read), and the diagnostics."""
    result: dict[str, str | None] = {}
    diagnostics: list[Diagnostic] = []
    for path, text in texts.items():
        if is_xml(path):
            st_text, found = read_xml(text, path)
            result[path] = st_text
            diagnostics.extend(found)
    return result, diagnostics


def read_xml(text: str, path: str) -> tuple[str | None, list[Diagnostic]]:
    """The XML document ``text`` as line-aligned ST text, or ``None`` and the reasons; never raises."""
    try:
        root = _parse(text, path)
        reader = _Reader(text, path, root)
        return reader.run()
    except _Refused as refused:
        return None, [refused.diagnostic]
    except Exception as exc:  # the promise: a diagnostic, never a traceback
        return None, [Diagnostic("E-XML-099", f"internal XML reader error: {type(exc).__name__}: {exc}",
                                 ast.Pos(path, 1, 1))]


class _Refused(Exception):
    def __init__(self, diagnostic: Diagnostic):
        self.diagnostic = diagnostic


def _lxml():
    global etree
    if etree is None:
        from lxml import etree
    return etree


def _parser() -> "etree.XMLParser":
    return _lxml().XMLParser(resolve_entities=False, no_network=True, load_dtd=False, dtd_validation=False,
                           huge_tree=False, remove_comments=True, remove_pis=True, encoding="utf-8")


_DOCTYPE = re.compile(rb"<!DOCTYPE", re.IGNORECASE)


def _parse(text: str, path: str) -> "etree._Element":
    _lxml()
    data = text.encode("utf-8")
    doctype = _DOCTYPE.search(data)
    if doctype:  # refused before libxml2 sees it: no entity is ever defined, so none can expand
        line = data.count(b"\n", 0, doctype.start()) + 1
        col = doctype.start() - (data.rfind(b"\n", 0, doctype.start()) + 1) + 1
        raise _Refused(Diagnostic("E-XML-002", "the file has a document type declaration (<!DOCTYPE ...>), "
                                  "which can define entities: PLCopen and IEC 61131-10 files have none; refused",
                                  ast.Pos(path, line, col)))
    try:
        tree = etree.fromstring(data, _parser()).getroottree()
    except etree.XMLSyntaxError as exc:
        line, col = exc.position if exc.position else (1, 1)
        message = exc.msg or str(exc)
        raise _Refused(Diagnostic("E-XML-001", f"not well-formed XML: {message}",
                                  ast.Pos(path, max(line, 1), max(col, 1)))) from None
    return tree.getroot()


def _local(element) -> str:
    return etree.QName(element).localname if isinstance(element.tag, str) else ""


def _children(element, *names: str) -> list:
    return [c for c in element if isinstance(c.tag, str) and etree.QName(c).localname in names]


def _child(element, name: str):
    found = _children(element, name)
    return found[0] if found else None


@dataclass
class _Layout:
    """ST text written at given lines and columns of the XML file (see the module doc)."""

    raw: str
    parts: list[str] = field(default_factory=list)
    line: int = 1
    col: int = 1

    def __post_init__(self) -> None:
        self.starts = [0]
        for match in re.finditer("\n", self.raw):
            self.starts.append(match.end())

    def put(self, text: str, line: int | None = None, col: int = 1) -> None:
        """Write ``text`` at (line, col) if that is still ahead, else after a space where the text stands."""
        if line is not None and line > self.line:
            self.parts.append("\n" * (line - self.line))
            self.line, self.col = line, 1
        if line == self.line and col > self.col:
            self.parts.append(" " * (col - self.col))
            self.col = col
        elif self.col > 1:
            self.parts.append(" ")
            self.col += 1
        self.parts.append(text)
        newlines = text.count("\n")
        if newlines:
            self.line += newlines
            self.col = len(text) - text.rfind("\n")
        else:
            self.col += len(text)

    def position(self, offset: int) -> tuple[int, int]:
        """(line, column), 1-based, of a character offset into the XML text."""
        lo, hi = 0, len(self.starts) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if self.starts[mid] <= offset:
                lo = mid
            else:
                hi = mid - 1
        return lo + 1, offset - self.starts[lo] + 1

    def start_tag(self, element) -> int | None:
        """Offset of ``<tag`` of ``element`` on its source line, or ``None``."""
        line = element.sourceline or 0
        if not 1 <= line <= len(self.starts):
            return None
        qname = (f"{element.prefix}:" if element.prefix else "") + etree.QName(element).localname
        begin = self.starts[line - 1]
        end = self.starts[line] if line < len(self.starts) else len(self.raw)
        match = re.compile("<" + re.escape(qname) + r"(?=[\s/>])").search(self.raw, begin, end)
        return match.start() if match else None

    def where(self, element) -> tuple[int, int]:
        offset = self.start_tag(element)
        if offset is None:
            return element.sourceline or self.line, 1
        return self.position(offset)

    def name_value(self, element) -> tuple[int, int]:
        """Where the value of the ``name="..."`` attribute of ``element`` starts (else the element's start)."""
        offset = self.start_tag(element)
        if offset is None:
            return self.where(element)
        end = self.raw.find(">", offset)
        match = re.compile(r"\sname\s*=\s*[\"']").search(self.raw, offset, end if end >= 0 else len(self.raw))
        return self.position(match.end() if match else offset)

    def text_start(self, element) -> tuple[int, int] | None:
        """Where the character data of ``element`` begins (after its start tag and a ``<![CDATA[``)."""
        offset = self.start_tag(element)
        if offset is None:
            return None
        quote = None
        for index in range(offset, len(self.raw)):
            char = self.raw[index]
            if quote:
                quote = None if char == quote else quote
            elif char in "\"'":
                quote = char
            elif char == ">":
                offset = index + 1
                break
        else:
            return None
        if self.raw.startswith("<![CDATA[", offset):
            offset += len("<![CDATA[")
        return self.position(offset)

    def text(self) -> str:
        return "".join(self.parts) + "\n"


class _Reader:
    """One XML document to ST (see the module doc)."""

    def __init__(self, raw: str, path: str, root) -> None:
        self.path, self.root = path, root
        self.layout = _Layout(raw)
        self.diagnostics: list[Diagnostic] = []
        namespace = etree.QName(root).namespace
        if namespace in (TC6, *TC6_EARLIER) and _local(root) == "project":
            self.tc6 = True
        elif namespace == IEC10 and _local(root) == "Project":
            self.tc6 = False
        else:
            raise _Refused(Diagnostic(
                "E-XML-003", f"root element <{_local(root)}> in namespace '{namespace or ''}': expected "
                f"<project> of PLCopen TC6 XML 2.01 ('{TC6}') or <Project> of IEC 61131-10 ('{IEC10}')",
                self._pos(root)))

    # ------------------------------------------------------------------ helpers

    def _pos(self, element) -> ast.Pos:
        line, col = self.layout.where(element) if element is not None else (1, 1)
        return ast.Pos(self.path, line, col)

    def _error(self, code: str, message: str, element) -> None:
        self.diagnostics.append(Diagnostic(code, message, self._pos(element)))

    def _name(self, element, what: str) -> str | None:
        name = element.get("name")
        if not name:
            self._error("E-XML-004", f"<{_local(element)}> without a name attribute ({what})", element)
        return name

    def run(self) -> tuple[str | None, list[Diagnostic]]:
        if self.tc6:
            self._tc6_project()
        else:
            self._iec10_project()
        if any(d.is_error and d.code != "E-XML-005" for d in self.diagnostics):
            return None, self.diagnostics
        # POUs in other languages stand with their interface and an empty body: the ST POUs
        # that call them are checked all the same, and E-XML-005 still stops the load.
        return self.layout.text(), self.diagnostics

    # ------------------------------------------------------------------ types and values

    def _inner(self, holder, owner: str, what: str):
        """The first child element of ``holder``, or ``None`` after a diagnostic."""
        inner = [c for c in holder if isinstance(c.tag, str)]
        if not inner:
            self._error("E-XML-004", f"{owner}: <{_local(holder)}> holds no {what}", holder)
            return None
        return inner[0]

    def _type(self, holder, owner: str) -> str | None:
        """The ST text of the type held by ``holder`` (``type``, ``baseType``, ``Type``, ``ResultType``...)."""
        element = self._inner(holder, owner, "type")
        if element is None:
            return None
        tag = _local(element)
        if self.tc6:
            if tag in _TC6_ELEMENTARY:
                return _TC6_ELEMENTARY[tag]
            if tag in ("string", "wstring"):
                word = tag.upper()
                return f"{word}[{element.get('length')}]" if element.get("length") else word
            if tag == "derived" and element.get("name"):
                return element.get("name")
            if tag == "array":
                return self._array(_children(element, "dimension"), _child(element, "baseType"), owner, element)
        else:
            if tag == "TypeName" and (element.text or "").strip():
                name = element.text.strip()
                return _IEC10_TYPE_ALIASES.get(name.upper(), name)
            if tag == "InstantlyDefinedType" and _xsi_type(element) == "ArrayTypeSpec":
                dimensions = [r for d in _children(element, "DimensionSpec") for r in _children(d, "IndexRange")]
                return self._array(dimensions, _child(element, "BaseType"), owner, element)
        self._error("E-XML-006", f"{owner}: type <{tag}{_xsi_suffix(element)}> cannot be read as ST "
                    "(elementary, named, string and array types can)", element)
        return None

    def _array(self, dimensions, base, owner: str, element) -> str | None:
        if not dimensions or base is None:
            self._error("E-XML-004", f"{owner}: an array type without dimensions or base type", element)
            return None
        ranges = []
        for dimension in dimensions:
            lower, upper = dimension.get("lower"), dimension.get("upper")
            if lower is None or upper is None:
                self._error("E-XML-004", f"{owner}: an array dimension without lower and upper bound", dimension)
                return None
            ranges.append(f"{lower}..{upper}")
        base_type = self._type(base, owner)
        return None if base_type is None else f"ARRAY[{', '.join(ranges)}] OF {base_type}"

    def _value(self, element, owner: str) -> str | None:
        """The ST initializer held by an initial value element."""
        value = self._inner(element, owner, "value")
        if value is None:
            return None
        tag = _local(value).lower()
        if tag == "simplevalue" and value.get("value") is not None:
            return value.get("value")
        if tag == "arrayvalue":
            items = []
            for item in _children(value, "value", "Value"):
                text = self._value(item, owner)
                if text is None:
                    return None
                count = item.get("repetitionValue")
                items.append(f"{count}({text})" if count and count != "1" else text)
            return "[" + ", ".join(items) + "]"
        if tag == "structvalue":
            fields = []
            for item in _children(value, "value", "Value"):
                text = self._value(item, owner)
                if text is None:
                    return None
                fields.append(f"{item.get('member')} := {text}")
            return "(" + ", ".join(fields) + ")"
        self._error("E-XML-006", f"{owner}: value <{_local(value)}> cannot be read as ST", value)
        return None

    # ------------------------------------------------------------------ declarations

    def _declaration(self, variable, owner: str) -> str | None:
        name = self._name(variable, f"a variable of {owner}")
        type_holder = _child(variable, "type" if self.tc6 else "Type")
        if type_holder is None:
            self._error("E-XML-004", f"{owner}: variable '{name}' without a type", variable)
            return None
        type_text = self._type(type_holder, f"{owner}.{name}")
        if name is None or type_text is None:
            return None
        initial = _child(variable, "initialValue" if self.tc6 else "InitialValue")
        text = f"{name} : {type_text}"
        if variable.get("address"):
            text = f"{name} AT {variable.get('address')} : {type_text}"
        if initial is not None:
            value = self._value(initial, f"{owner}.{name}")
            if value is None:
                return None
            text += f" := {value}"
        return text + ";"

    def _var_list(self, element, keyword: str, owner: str) -> None:
        variables = _children(element, "variable", "Variable")
        if not variables:
            return
        qualifiers = "".join(f" {word.upper()}" for word in ("constant", "retain") if element.get(word) in ("true", "1"))
        line, col = self.layout.where(element)
        self.layout.put(keyword + qualifiers, line, col)
        for variable in variables:
            text = self._declaration(variable, owner)
            if text is not None:  # the name over the name attribute's value: the caret lands on it
                self.layout.put(text, *self.layout.name_value(variable))
        self.layout.put("END_VAR")

    def _body(self, holder, text_element) -> str:
        """Write the ST body held by ``text_element`` at its place in the file; returns the body."""
        text = "".join(text_element.itertext())
        start = self.layout.text_start(text_element)
        if start is None:
            line, _col = self.layout.where(holder)
            start = (line + 1, 1)
        self.layout.put(text, *start)
        return text

    def _pou(self, element, kind: str, lists: dict[str, str], return_holder) -> None:
        name = self._name(element, "a POU")
        if name is None:
            return
        line, col = self.layout.where(element)
        header = f"{kind} {name}"
        if kind == "FUNCTION":
            if return_holder is None:
                self._error("E-XML-004", f"function '{name}' without a result type", element)
                return
            result = self._type(return_holder, name)
            if result is None:
                return
            header += f" : {result}"
        body = self._st_body(element, name)
        if body is None and not any(d.code == "E-XML-005" and d.message.startswith(f"POU '{name}'")
                                    for d in self.diagnostics):
            return
        self.layout.put(header, line, col)
        for child in element:
            if not isinstance(child.tag, str):
                continue
            # variable lists stand in the POU (IEC 61131-10), in its Parameters (IEC 61131-10) or its interface (TC6)
            for item in (child,) if _local(child) not in ("interface", "Parameters") else child:
                if isinstance(item.tag, str) and _local(item) in lists:
                    self._var_list(item, lists[_local(item)], name)
        text = self._body(*body) if body is not None else ""
        closer = f"END_{kind}"
        if text.rsplit("\n", 1)[-1].strip():  # the body ends in a statement (or a // comment): a line of its own
            self.layout.put(closer, self.layout.line + 1, 1)
        else:
            self.layout.put(closer)

    def _st_body(self, element, name: str):
        """(holder, element holding the ST text) of a POU, or ``None`` after a diagnostic."""
        if self.tc6:
            bodies = _children(element, "body")
            languages = [c for b in bodies for c in b if isinstance(c.tag, str) and _local(c) != "addData"
                         and _local(c) != "documentation"]
            if not languages:
                self._error("E-XML-004", f"POU '{name}' has no body", element)
                return None
            language = languages[0]
            if _local(language) != "ST":
                self._error("E-XML-005", f"POU '{name}' has a body in {_LANGUAGES.get(_local(language).upper(), _local(language))}, "
                            "not ST: only ST bodies are read", language)
                return None
            paragraphs = [c for c in language if isinstance(c.tag, str)]
            return language, (paragraphs[0] if paragraphs else language)
        contents = [c for m in _children(element, "MainBody") for c in _children(m, "BodyContent")]
        if not contents:
            self._error("E-XML-004", f"POU '{name}' has no MainBody/BodyContent", element)
            return None
        content = contents[0]
        language = _xsi_type(content)
        if language != "ST":
            self._error("E-XML-005", f"POU '{name}' has a body in {_LANGUAGES.get(language.upper(), language or '(no xsi:type)')}, "
                        "not ST: only ST bodies are read", content)
            return None
        st = _child(content, "ST")
        if st is None:
            self._error("E-XML-004", f"POU '{name}': BodyContent of type ST without an <ST> element", content)
            return None
        return content, st

    # ------------------------------------------------------------------ data types

    def _data_type(self, element, name: str, spec, members, enumerators, initial) -> None:
        line, col = self.layout.where(element)
        if members is not None:
            self.layout.put(f"TYPE {name} : STRUCT", line, col)
            for member in members:
                text = self._declaration(member, name)
                if text is not None:
                    self.layout.put(text, *self.layout.name_value(member))
            self.layout.put("END_STRUCT; END_TYPE")
            return
        if enumerators is not None:
            values = [e.get("name") + (f" := {e.get('value')}" if e.get("value") else "") for e in enumerators]
            self.layout.put(f"TYPE {name} : ({', '.join(values)}); END_TYPE", line, col)
            return
        type_text = self._type(spec, name)
        if type_text is None:
            return
        value = self._value(initial, name) if initial is not None else None
        self.layout.put(f"TYPE {name} : {type_text}" + (f" := {value}" if value else "") + "; END_TYPE", line, col)

    # ------------------------------------------------------------------ PLCopen TC6

    def _tc6_project(self) -> None:
        root = self.root
        for types in _children(root, "types"):
            for data_types in _children(types, "dataTypes"):
                for data_type in _children(data_types, "dataType"):
                    self._tc6_data_type(data_type)
            for pous in _children(types, "pous"):
                for pou in _children(pous, "pou"):
                    kind = _TC6_KINDS.get(pou.get("pouType", ""))
                    if kind is None:
                        self._error("E-XML-004", f"POU '{pou.get('name')}': pouType '{pou.get('pouType')}' "
                                    "is not function, functionBlock or program", pou)
                        continue
                    returns = [r for i in _children(pou, "interface") for r in _children(i, "returnType")]
                    self._pou(pou, kind, _TC6_LISTS, returns[0] if returns else None)
        for instances in _children(root, "instances"):
            for configurations in _children(instances, "configurations"):
                for configuration in _children(configurations, "configuration"):
                    self._globals(configuration, "globalVars", "resource")

    def _tc6_data_type(self, element) -> None:
        name = self._name(element, "a data type")
        base = _child(element, "baseType")
        if name is None or base is None:
            if base is None:
                self._error("E-XML-004", f"data type '{name}' without a baseType", element)
            return
        inner = [c for c in base if isinstance(c.tag, str)]
        kind = _local(inner[0]) if inner else ""
        members = _children(inner[0], "variable") if kind == "struct" else None
        enumerators = None
        if kind == "enum":
            enumerators = [v for vs in _children(inner[0], "values") for v in _children(vs, "value")]
        self._data_type(element, name, base, members, enumerators, _child(element, "initialValue"))

    # ------------------------------------------------------------------ IEC 61131-10

    def _iec10_project(self) -> None:
        for types in _children(self.root, "Types"):
            for namespace in _children(types, "GlobalNamespace"):
                self._iec10_namespace(namespace)
        for instances in _children(self.root, "Instances"):
            for configuration in _children(instances, "Configuration"):
                self._globals(configuration, "GlobalVars", "Resource")

    def _iec10_namespace(self, namespace) -> None:
        for element in namespace:
            if not isinstance(element.tag, str):
                continue
            tag = _local(element)
            if tag in _IEC10_KINDS:
                self._pou(element, _IEC10_KINDS[tag], _IEC10_LISTS, _child(element, "ResultType"))
            elif tag == "DataTypeDecl":
                self._iec10_data_type(element)
            elif tag == "NamespaceDecl":  # ST here has no namespaces: their members are read as global names
                self._iec10_namespace(element)

    def _iec10_data_type(self, element) -> None:
        name = self._name(element, "a data type")
        if name is None:
            return
        spec = _child(element, "UserDefinedTypeSpec")
        if spec is not None and _xsi_type(spec) == "StructTypeSpec":
            self._data_type(element, name, None, _children(spec, "Member"), None, None)
        elif spec is not None and _xsi_type(spec).startswith("EnumType"):
            self._data_type(element, name, None, None, _children(spec, "Enumerator"), None)
        else:
            self._error("E-XML-006", f"data type '{name}': only structures and enumerations are read",
                        element if spec is None else spec)

    # ------------------------------------------------------------------ both

    def _globals(self, configuration, tag: str, resource_tag: str) -> None:
        holders = [configuration] + _children(configuration, resource_tag)
        for block in configuration.iter():  # document order: the configuration's own lists follow its resources
            if isinstance(block.tag, str) and _local(block) == tag and any(block.getparent() is h for h in holders):
                self._var_list(block, "VAR_GLOBAL", "global variables")


def _xsi_type(element) -> str:
    """The local part of an element's ``xsi:type`` (``smcext:LdSection`` -> ``LdSection``)."""
    value = element.get(f"{{{XSI}}}type") or ""
    return value.rsplit(":", 1)[-1]


def _xsi_suffix(element) -> str:
    value = element.get(f"{{{XSI}}}type")
    return f' xsi:type="{value}"' if value else ""

"""Diagnostic codes of the loader and the checker, with one-line explanations."""

from __future__ import annotations

from ..diagnostics import register

CHECKER_CODES = register({
    # loading files
    "E-LOAD-001": "a file or directory given on the command line does not exist",
    "E-LOAD-002": "a file cannot be read (permissions, I/O error, not a regular file)",
    "E-LOAD-003": "a file is not valid UTF-8 text",
    "W-LOAD-004": "a directory holds no .st file",
    "W-LOAD-005": "an entry of a directory was skipped (a link to a directory, an unreadable directory, "
                  "a .st name that is not a regular file)",
    # declarations
    "E-DECL-001": "a name is used but not declared (a qualified call NS.F(...) whose NAMESPACE NS declares "
                  "no POU F: NS.F names an element of NS, never a variable or method F of the caller)",
    "E-DECL-002": "a variable, member or enumeration value is declared twice in the same scope",
    "E-DECL-003": "a POU or data type name is declared twice or redefines a standard function",
    "E-DECL-004": "a type name does not denote a declared type",
    "E-DECL-005": "a data type is defined in terms of itself",
    "E-DECL-006": "array bounds or a string length are not valid constant integers",
    "E-DECL-007": "an initial value does not fit the declared variable (too many elements, unknown member)",
    "E-DECL-008": "an initial value is not a constant expression",
    "E-DECL-009": "a FUNCTION declares a function block instance (functions keep no state)",
    "E-DECL-010": "a VAR_EXTERNAL has no matching VAR_GLOBAL of the same type",
    "E-DECL-011": "a CONSTANT variable has no initial value",
    "E-DECL-012": "a VAR_IN_OUT or VAR_EXTERNAL has an initial value (it refers to another variable)",
    # types
    "E-TYPE-001": "an operator is applied to an operand type it does not accept",
    "E-TYPE-002": "the operands of an operator have types with no common implicit conversion",
    "E-TYPE-003": "a condition (IF, ELSIF, WHILE, UNTIL) is not BOOL",
    "E-TYPE-004": "a value of one type is assigned or passed where another type is needed and no implicit conversion exists",
    "E-TYPE-005": "a literal or constant value does not fit its type's range",
    "E-TYPE-006": "indexing something that is not an array, or with the wrong number of indices",
    "E-TYPE-007": "an array index is not an integer",
    "E-TYPE-008": "a constant array index lies outside the array's bounds",
    "E-TYPE-009": "a member does not exist in the struct or function block, or is not accessible",
    "E-TYPE-010": "a FOR control variable or bound is not an integer",
    "E-TYPE-011": "a CASE selector is neither an integer nor an enumeration",
    "E-TYPE-012": "a CASE label is not a constant of the selector's type",
    "E-TYPE-013": "a CASE label value appears more than once",
    "E-TYPE-014": "the left side of an assignment or an output target is not a variable",
    "E-TYPE-015": "an enumeration value does not belong to the named enumeration type",
    "E-TYPE-016": "a name that is not a value (a POU, a type, an FB instance) is used as a value",
    "E-TYPE-017": "division by zero in a constant expression",
    "E-TYPE-018": "a PROPERTY without GET is read (CODESYS C0143; one without SET written is E-ASSIGN-004)",
    "W-DECL-001": "a project's FUNCTION_BLOCK replaces the built-in standard FB of the same name (TON, CTU, MC_Power)",
    "E-SFC-002": "an SFC chart that is not well formed: an unknown or duplicate step, no INITIAL_STEP",
    "W-TYPE-001": "a string literal is longer than the STRING it is stored in and will be truncated",
    # assignments
    "E-ASSIGN-001": "assignment to a CONSTANT variable",
    "E-ASSIGN-002": "assignment to a VAR_INPUT inside its own POU (inputs are read-only)",
    "E-ASSIGN-003": "a FOR control variable written inside its loop: assigned, an output (=>) target, taken by REF or ADR, or the control variable of a nested FOR",
    "W-ASSIGN-001": "a FOR control variable that a FUNCTION, FB or METHOD called in its loop writes (a global: a METHOD of any instance, overrides included; a variable of the FB: a METHOD of this instance), or a write through a reference known to refer to it, in the loop or by a callee handed it: IEC 61131-3 forbids it; the loop goes on from the value the callee leaves",
    "E-ASSIGN-004": "assignment to an output or internal variable of a function block instance from outside, or to a PROPERTY without SET",
    # calls
    "E-CALL-001": "a call of something that is not a function or function block instance (NS.F() of "
                  "an FB type F of NAMESPACE NS, whatever the caller declares named F)",
    "E-CALL-002": "a call names a parameter (pin) the callee does not have",
    "E-CALL-003": "a call gives the same parameter twice",
    "E-CALL-004": "a call omits a VAR_IN_OUT parameter (required at every call)",
    "E-CALL-005": "a parameter is passed in the wrong direction (:= on an output, => on an input)",
    "E-CALL-006": "a call has more positional arguments than the callee has inputs",
    "E-CALL-007": "a VAR_IN_OUT argument is not a writable variable (an expression, a bit access, a CONSTANT, an input of the calling POU, a FOR control variable)",
    "E-CALL-008": "a positional argument follows a formal (named) argument",
    "E-CALL-009": "a call has fewer arguments than the callee requires",
    "E-CALL-010": "a function block instance is called inside an expression (FB calls are statements)",
    "E-CALL-011": "a VAR_IN_OUT argument's type differs from the parameter's type",
    # control flow, recursion
    "E-FLOW-001": "EXIT outside a loop",
    "E-FLOW-002": "CONTINUE outside a loop",
    "E-REC-001": "recursion: a POU calls itself directly or through other POUs (IEC and OMRON forbid it)",
    # OMRON NJ identifier rules (errors under --dialect nj, warnings otherwise)
    "E-NJ-001": "identifier longer than 127 bytes (UTF-8), the NJ limit",
    "E-NJ-002": "identifier starts or ends with an underscore, not allowed on the NJ",
    "E-NJ-003": "identifier contains two consecutive underscores, not allowed on the NJ",
    "E-NJ-004": "identifier equals an NJ instruction name",
    "E-NJ-005": "identifier starts with 'P_', reserved on the NJ for system-defined variables",
    "W-NJ-001": "identifier longer than 127 bytes (UTF-8): rejected by an OMRON NJ",
    "W-NJ-002": "identifier starts or ends with an underscore: rejected by an OMRON NJ",
    "W-NJ-003": "identifier contains two consecutive underscores: rejected by an OMRON NJ",
    "W-NJ-004": "identifier equals an NJ instruction name: rejected by an OMRON NJ",
    "W-NJ-005": "identifier starts with 'P_': rejected by an OMRON NJ",
    # Sysmac Studio Build rules (st_runtime/dialects.py NJ_RULES, docs/nj501.md)
    "E-NJ-006": "an element of an array or a member of a structure that is a variable of a function block instance (Inst.Arr[i]): refused at Build",
    "E-NJ-007": "a CASE label is not an integer literal or an enumerator (e.g. a constant's name)",
    "E-NJ-008": "an initial value is not a literal (e.g. a constant's name)",
    "W-NJ-006": "an element or member of a function block instance's variable (Inst.Arr[i]): Sysmac Studio refuses it at Build",
    "W-NJ-007": "a CASE label is not an integer literal or an enumerator: Sysmac Studio expects integer constants",
    "W-NJ-008": "an initial value is not a literal: Sysmac Studio's variable tables take literals",
    "E-PIN-001": "a standard FB pin is named as another dialect names it (OMRON's Reset for IEC's R of CTU, and the reverse)",
    # the rest of IEC 61131-3 (issue 13)
    "E-DECL-013": "R_EDGE / F_EDGE on something other than a BOOL input of a function block or program",
    "E-DECL-014": "a subrange type whose base is not an integer type or whose limits are not lower <= upper inside the base",
    "E-DECL-015": "a located variable (AT %IX0.0) with an invalid address, in the wrong place, or of a type whose width differs from the address's size",
    "E-DECL-016": "object orientation: an unknown or wrong base / interface, a missing or FINAL-overridden method, an ABSTRACT FB instantiated",
    "E-DECL-017": "a UNION member that is not BOOL, an integer, a bit string or a real",
    "E-DECL-018": "a STRUCT or UNION declares no member (IEC 61131-3 Annex A, Struct_Decl: one at least)",
    "E-DIALECT-001": "a construct the chosen --dialect does not accept (the message names the dialects that do)",
    "E-CALL-012": "a method is called from where its access specifier (PRIVATE, PROTECTED) does not allow it",
    "E-CALL-013": "dynamic memory (__NEW, __DELETE) is not supported by the runtime",
})

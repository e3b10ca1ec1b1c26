"""Rendering the kinematics POUs: literals, interfaces, constants, variants and the exports."""

from __future__ import annotations

import itertools
import math
import random
import re

import jinja2
import pytest

from stgen.cli import main
from stgen.config import GeometryConfig, PlatformConfig
from stgen.error_codes import ErrorCode
from stgen.exports import iec, sysmac
from stgen.render import (
    RenderError,
    RenderOptions,
    comment_text,
    lreal_literal,
    make_environment,
    render_pou,
    render_program,
    template_context,
)

DEFAULT = render_program()


def _interface(pou, usage):
    return [(v.name, v.type) for v in pou.variables_of(usage)]


def _array_values(initial: str) -> list[float]:
    return [float(item) for item in initial.strip("[]").replace("\n", " ").split(",")]


# --------------------------------------------------------------------------- literals


@pytest.mark.parametrize(
    "value, text",
    [(1e16, "1.0E16"), (1e15, "1000000000000000.0"), (1e-9, "1.0E-9"), (0.1, "0.1"), (-115.0, "-115.0"), (1374, "1374.0"),
     (1.7976931348623157e308, "1.7976931348623157E308"), (2.5e-5, "2.5E-5")],
)
def test_lreal_literal_has_a_decimal_point_and_iec_exponent(value, text):
    assert lreal_literal(value) == text


def test_lreal_literal_round_trips_every_double():
    rng = random.Random(7)
    for _ in range(2000):
        value = rng.choice([rng.uniform(-1e3, 1e3), rng.uniform(-1, 1) * 10.0 ** rng.randint(-300, 300)])
        text = lreal_literal(value)
        assert re.fullmatch(r"-?\d+\.\d+(E-?\d+)?", text), text
        assert float(text) == value


@pytest.mark.parametrize("value", [math.inf, -math.inf, math.nan])
def test_non_finite_values_are_refused(value):
    with pytest.raises(RenderError):
        lreal_literal(value)


def test_comment_text_cannot_close_a_comment():
    with pytest.raises(RenderError):
        comment_text("evil *) X := 1; (*")


def test_undefined_template_names_are_errors_not_blanks():
    env = make_environment()
    env.loader = jinja2.DictLoader({"Bad.st.j2": '{% set kind = "FUNCTION" %}{% set header = "" %}'
                                                  "{% set variables = [] %}X := {{ no_such_value }};"})
    with pytest.raises(RenderError, match="no_such_value"):
        render_pou(env, "Bad", template_context(PlatformConfig.default(), RenderOptions()))


def test_unknown_determinant_option_is_refused():
    with pytest.raises(RenderError, match="determinant"):
        RenderOptions(determinant="recursive")


# --------------------------------------------------------------------------- fixed interfaces


def test_inverse_kinematics_interface_is_the_fixed_one():
    pou = DEFAULT.pou("SP_InverseKinematics")
    assert pou.kind == "FUNCTION_BLOCK"
    assert _interface(pou, "Input") == [("Pose", "ARRAY[1..6] OF LREAL")]
    outputs = _interface(pou, "Output")
    assert outputs[:4] == [("CylinderPos", "ARRAY[1..6] OF LREAL"), ("Reachable", "BOOL"), ("Error", "BOOL"),
                           ("ErrorID", "WORD")]


def test_forward_kinematics_interface_and_defaults():
    pou = DEFAULT.pou("SP_ForwardKinematics")
    assert pou.kind == "FUNCTION_BLOCK"
    inputs = {v.name: v for v in pou.variables_of("Input")}
    assert [(v.name, v.type) for v in inputs.values()] == [
        ("Execute", "BOOL"), ("CylinderPos", "ARRAY[1..6] OF LREAL"), ("StartPose", "ARRAY[1..6] OF LREAL"),
        ("Tolerance", "LREAL"), ("IterationsPerScan", "INT"), ("MaxIterations", "INT")]
    assert float(inputs["Tolerance"].initial) == 0.01
    assert int(inputs["IterationsPerScan"].initial) == PlatformConfig.default().solver.iterations_per_scan
    assert int(inputs["MaxIterations"].initial) == PlatformConfig.default().solver.max_iterations
    assert _interface(pou, "Output") == [
        ("Done", "BOOL"), ("Busy", "BOOL"), ("Error", "BOOL"), ("ErrorID", "WORD"),
        ("Pose", "ARRAY[1..6] OF LREAL"), ("Iterations", "INT")]


def test_the_pous_are_all_there_with_their_kinds():
    kinds = {pou.name: pou.kind for pou in DEFAULT.pous}
    assert kinds.items() >= {
        "SP_Constants": "VAR_GLOBAL", "SP_Atan2": "FUNCTION", "SP_LuSolve": "FUNCTION",
        "SP_LeibnizDeterminant": "FUNCTION_BLOCK", "SP_Jacobian": "FUNCTION_BLOCK",
        "SP_InverseKinematics": "FUNCTION_BLOCK", "SP_ForwardKinematics": "FUNCTION_BLOCK",
        "SP_Controller": "PROGRAM"}.items()


# --------------------------------------------------------------------------- constants from the configuration


def _constants(program):
    return {v.name: v for v in program.pou("SP_Constants").variables}


def test_joint_constants_follow_equations_2_to_4():
    """Hand formula of docs/mathematics.md section 1 ([2]-[4]), independent of the reference."""
    g = GeometryConfig()
    constants = _constants(DEFAULT)
    phi_b, phi_p = math.radians(g.phi_b_deg), math.radians(g.phi_p_deg)
    for leg in range(1, 7):
        odd = leg if leg % 2 else leg - 1
        theta = (2 * odd * math.pi - 3 * phi_b) / 6 + (0 if leg % 2 else phi_b)
        phi = (2 * odd * math.pi - 3 * phi_p) / 6 + (0 if leg % 2 else phi_p)
        expected = {"SP_BASE_JOINT_X": g.rb * math.cos(theta), "SP_BASE_JOINT_Y": g.rb * math.sin(theta),
                    "SP_BASE_JOINT_Z": g.hb, "SP_PLATFORM_JOINT_X": g.rp * math.cos(phi),
                    "SP_PLATFORM_JOINT_Y": g.rp * math.sin(phi), "SP_PLATFORM_JOINT_Z": g.hp}
        for name, value in expected.items():
            assert _array_values(constants[name].initial)[leg - 1] == pytest.approx(value, abs=1e-9), (name, leg)


def test_scalar_constants_and_error_ids():
    constants = _constants(DEFAULT)
    config = PlatformConfig.default()
    assert float(constants["SP_HOME_HEIGHT"].initial) == 1374.0
    assert float(constants["SP_RETRACTED_LENGTH"].initial) == 1192.63
    assert float(constants["SP_STROKE_MAX"].initial) == 600.0
    assert float(constants["SP_SINGULARITY_THRESHOLD"].initial) == config.solver.singularity_threshold
    assert float(constants["SP_RAD_PER_DEG"].initial) * 180.0 == pytest.approx(math.pi, rel=1e-16)
    assert constants["ERR_SINGULAR_JACOBIAN"].initial == "16#1001"
    assert constants["ERR_NOT_CONVERGED"].initial == "16#1002"
    assert constants["ERR_NON_FINITE"].initial == "16#1003"
    assert constants["ERR_UNREACHABLE"].initial == "16#1004"
    assert {c.st_constant_name for c in ErrorCode} <= set(constants)
    assert all(v.constant for v in constants.values())


def test_another_configuration_changes_the_constants():
    config = PlatformConfig(geometry=GeometryConfig(rb=500.0, h0=1400.0))
    constants = _constants(render_program(config))
    assert float(constants["SP_HOME_HEIGHT"].initial) == 1400.0
    assert math.hypot(_array_values(constants["SP_BASE_JOINT_X"].initial)[0],
                      _array_values(constants["SP_BASE_JOINT_Y"].initial)[0]) == pytest.approx(500.0)


# --------------------------------------------------------------------------- determinant variants


def _inversions(perm):
    return sum(1 for a, b in itertools.combinations(perm, 2) if a > b)


def test_permutation_table_lists_every_permutation_once_in_lexicographic_order_with_its_sign():
    det = DEFAULT.pou("SP_LeibnizDeterminant")
    constants = {v.name: v for v in det.variables}
    flat = [int(x) for x in constants["PERMUTATION"].initial.strip("[]").replace("\n", " ").split(",")]
    rows = [tuple(flat[i : i + 6]) for i in range(0, len(flat), 6)]
    assert rows == list(itertools.permutations(range(1, 7)))
    signs = [int(x) for x in constants["PERMUTATION_SIGN"].initial.strip("[]").replace("\n", " ").split(",")]
    assert signs == [(-1) ** _inversions(p) for p in rows]
    assert constants["PERMUTATION"].type == "ARRAY[1..720, 1..6] OF USINT"


def test_unrolled_determinant_writes_out_720_signed_terms():
    det = render_program(options=RenderOptions("unrolled")).pou("SP_LeibnizDeterminant")
    terms = re.findall(r"^Determinant := Determinant ([+-]) ((?:Matrix\[\d, \d\](?: \* )?){6});$", det.body, re.M)
    assert len(terms) == 720
    for sign, product in terms:
        columns = tuple(int(c) for c in re.findall(r"Matrix\[\d, (\d)\]", product))
        rows = [int(r) for r in re.findall(r"Matrix\[(\d), \d\]", product)]
        assert rows == [1, 2, 3, 4, 5, 6]
        assert sign == ("+" if _inversions(columns) % 2 == 0 else "-")
    assert len({product for _, product in terms}) == 720
    assert "PERMUTATION" not in det.body


def test_lu_variant_takes_the_determinant_from_the_lu_diagonal():
    fk = render_program(options=RenderOptions("lu")).pou("SP_ForwardKinematics")
    assert "Determinant => DetJ" in fk.body
    assert "DeterminantBlock" not in fk.body
    assert "DeterminantBlock" in DEFAULT.pou("SP_ForwardKinematics").body


# --------------------------------------------------------------------------- NJ rules


NJ_INSTRUCTION_NAMES = {"LIMIT", "MAX", "MIN", "SEL", "MUX", "MOVE", "ABS", "SQRT", "SIN", "COS", "TAN", "ASIN",
                        "ACOS", "ATAN", "EXPT", "EXP", "LN", "LOG", "TRUNC", "MOD", "AND", "OR", "XOR", "NOT"}
#: IEC 61131-3 keywords outside ST proper (SFC, configuration) that some tools still reserve.
IEC_RESERVED = {"STEP", "INITIAL_STEP", "TRANSITION", "ACTION", "FROM", "ON", "WITH", "TASK", "RESOURCE",
                "PROGRAM", "CONFIGURATION", "AT", "RETAIN", "CONSTANT", "EN", "ENO"}


@pytest.mark.parametrize("options", [RenderOptions("table"), RenderOptions("unrolled"), RenderOptions("lu")])
def test_every_identifier_obeys_the_nj_rules(options):
    program = render_program(options=options)
    for pou in program.pous:
        names = [pou.name] + [v.name for v in pou.variables]
        for name in names:
            assert len(name.encode("utf-8")) <= 127
            assert not name.startswith("_") and not name.endswith("_") and "__" not in name, name
            assert name.upper() not in NJ_INSTRUCTION_NAMES | IEC_RESERVED, name
        text = iec.pou_text(pou)
        assert not re.search(r"\bREAL\b", text), f"{pou.name} uses 32-bit REAL"
        code = re.sub(r"\(\*.*?\*\)", "", text, flags=re.S)
        assert not re.search(r"\bATAN2\b", code, re.I), f"{pou.name} calls an ATAN2 the NJ lacks"
        assert not re.search(r"\b(POINTER|REF_TO|REFERENCE|METHOD|EXTENDS)\b", text)


# --------------------------------------------------------------------------- exports


def test_iec_text_declares_and_closes_each_pou():
    text = iec.pou_text(DEFAULT.pou("SP_Atan2"))
    assert "FUNCTION SP_Atan2 : LREAL\nVAR_INPUT\n" in text
    assert text.rstrip().endswith("END_FUNCTION")
    gvl = iec.pou_text(DEFAULT.pou("SP_Constants"))
    assert "VAR_GLOBAL CONSTANT\n" in gvl and gvl.rstrip().endswith("END_VAR")


def test_sysmac_tables_have_the_column_layout_and_every_variable():
    for pou in DEFAULT.pous:
        if pou.kind == "VAR_GLOBAL":
            continue
        rows = [line.split("\t") for line in sysmac.pou_table(pou).splitlines()]
        assert tuple(rows[0]) == sysmac.POU_COLUMNS
        assert all(len(row) == len(sysmac.POU_COLUMNS) for row in rows)
        names = [row[0] for row in rows[1:]]
        expected = [v.name for v in pou.variables] + ([pou.name] if pou.kind == "FUNCTION" else [])
        assert sorted(names) == sorted(expected)
        body = sysmac.body_text(pou)
        assert not re.search(r"^\s*(VAR\w*|END_VAR|END_FUNCTION\w*|FUNCTION\w*)\b", body, re.M), pou.name


def test_sysmac_table_rows_and_usage_words():
    rows = {r.split("\t")[0]: r.split("\t") for r in sysmac.pou_table(DEFAULT.pou("SP_LuSolve")).splitlines()[1:]}
    assert rows["SP_LuSolve"][1:3] == ["Output", "BOOL"]
    assert rows["Matrix"][1:3] == ["In-Out", "ARRAY[1..6, 1..6] OF LREAL"]
    assert rows["SIZE"][1:6] == ["Internal", "INT", "6", "FALSE", "TRUE"]


def test_sysmac_global_table_holds_every_constant_on_one_line_each():
    rows = [line.split("\t") for line in sysmac.global_table([DEFAULT.pou("SP_Constants")]).splitlines()]
    assert tuple(rows[0]) == sysmac.GLOBAL_COLUMNS
    by_name = {row[0]: row for row in rows[1:]}
    assert len(by_name) == len(DEFAULT.pou("SP_Constants").variables)
    assert by_name["SP_HOME_HEIGHT"][1:3] == ["LREAL", "1374.0"]
    assert len(_array_values(by_name["SP_BASE_JOINT_X"][2])) == 6
    assert all(row[5] == "TRUE" for row in rows[1:])


# --------------------------------------------------------------------------- the command


def test_generate_writes_both_targets(tmp_path, capsys):
    assert main(["generate", "--target", "iec", "--out", str(tmp_path / "iec")]) == 0
    assert main(["generate", "--target", "nj", "--determinant", "unrolled", "--out", str(tmp_path / "nj")]) == 0
    assert (tmp_path / "iec" / "SP_ForwardKinematics.st").read_text().startswith("(* Generated by stgen")
    assert (tmp_path / "nj" / "SP_InverseKinematics.variables.tsv").exists()
    assert (tmp_path / "nj" / "GlobalVariables.tsv").exists()
    assert "Determinant := Determinant +" in (tmp_path / "nj" / "SP_LeibnizDeterminant.st").read_text()


def test_generate_reports_a_bad_config_with_file_and_key(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[geometry]\nrb = -1.0\n")
    assert main(["generate", "--config", str(bad), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert str(bad) in err and "geometry.rb" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_generate_reports_a_toml_syntax_error_and_a_missing_file(tmp_path, capsys):
    broken = tmp_path / "broken.toml"
    broken.write_text("[geometry\nrb = 1\n")
    assert main(["generate", "--config", str(broken), "--out", str(tmp_path / "o")]) == 1
    assert f"{broken}:1:" in capsys.readouterr().err
    assert main(["generate", "--config", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "o")]) == 1
    assert "missing.toml" in capsys.readouterr().err


def test_generate_without_out_is_a_usage_error():
    with pytest.raises(SystemExit) as exit_info:
        main(["generate"])
    assert exit_info.value.code == 2


def test_sysmac_leaves_the_axis_variables_to_the_motion_setup():
    globals_ = [pou for pou in DEFAULT.pous if pou.kind == "VAR_GLOBAL"]
    table = sysmac.global_table(globals_)
    assert "AXIS_REF" not in table and "MC_Axis000" not in table
    assert [v.name for v in sysmac.system_created(globals_)] == [f"MC_Axis{i:03d}" for i in range(6)]
    controller = sysmac.pou_table(DEFAULT.pou("SP_Controller"))
    assert "MC_Axis000\tExternal\t_sAXIS_REF\t" in controller


def test_sysmac_readme_lists_every_command_and_status_variable():
    readme = sysmac.files(DEFAULT)["README.md"]
    commands = readme[readme.index("## Commanding the controller"):readme.index("Status, written by")]
    status = readme[readme.index("Status, written by"):]
    # Every global of SP_ControllerGlobals is documented in the table its comment names.
    for variable in DEFAULT.pou("SP_ControllerGlobals").variables:
        row = f"| `{variable.name}` | `{variable.type}` |"
        section = commands if variable.comment.startswith("command:") else status
        assert variable.comment.split(":")[0] in ("command", "status"), variable.name
        assert row in section, variable.name
    assert "| `SpPowerOn` | `BOOL` | TRUE servo on, FALSE servo off |" in commands
    assert "| `SpFaultAxis` | `INT` | axis or leg 1..6 of the fault, 0 when none applies |" in status


def test_sysmac_readme_does_not_call_every_external_a_constant():
    readme = sysmac.files(DEFAULT)["README.md"]
    assert "global constants the POU reads; declare them with *Constant* ticked" not in readme
    # SP_Controller's externals include non-constant globals: their rows say Constant FALSE.
    rows = [r.split("\t") for r in sysmac.pou_table(DEFAULT.pou("SP_Controller")).splitlines()[1:]]
    externals = {r[0]: r[5] for r in rows if r[1] == "External"}
    assert externals["SpPowerOn"] == "FALSE" and externals["SP_STATE_STANDBY"] == "TRUE"
    assert "leave it\n     clear where it says `FALSE`" in readme

"""The `stgen` command line: one subcommand per job.

Each subcommand lives in `stgen/commands/<name>.py` and provides
`add_arguments(parser)` and `run(args) -> int`.  Exit codes: 0 success,
1 diagnostics, faults or failed checks, 2 usage errors.  No input ever
yields a Python traceback: unexpected errors are reported as internal errors.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import sys

COMMANDS = {
    "check": "parse and check Structured Text files",
    "run": "run a PROGRAM scan by scan in the simulated controller",
    "call": "call a FUNCTION or FB and print its outputs as JSON",
    "generate": "render the platform's POUs as Structured Text",
    "verify": "hold the generated ST against the NumPy reference",
    "demo": "generate, run the study's scenarios, write traces and figures",
    "test": "run the TEST blocks of ST test files (JUnit XML for CI)",
    "workspace": "map the reachable workspace: coordinate ranges and slices (NumPy, offline)",
    "plan": "plan a path or a playback: duration and actuator extremes against the limits",
}


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The parser of every command, or (`only`) of that one command alone.

    A command's module (with what it imports: NumPy, the renderer, ...) is
    imported only when its options are needed, so `stgen check` never pays
    for `stgen demo` (issue 15: start-up time).
    """
    parser = argparse.ArgumentParser(
        prog="stgen",
        description="Stewart-platform kinematics as IEC 61131-3 ST, proven in a simulated NJ501.",
    )
    parser.add_argument("--version", action=_VersionAction)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    one_line_usage_errors(parser, hint=f"commands: {', '.join(COMMANDS)}; ")
    parser.command_parsers = {}
    for name, help_text in COMMANDS.items():
        command_parser = sub.add_parser(name, help=help_text, description=help_text)
        parser.command_parsers[name] = command_parser
        module = _command_module(name) if only in (None, name) else None
        if module is not None:
            module.add_arguments(command_parser)
            command_parser.set_defaults(handler=module.run)
        one_line_usage_errors(command_parser)
    return parser


class _VersionAction(argparse.Action):
    """`--version`: the installed version, looked up only when asked for."""

    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, help="show the version and exit")

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"stgen {_version()}")
        parser.exit()


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("stgen")
    except PackageNotFoundError:    # run from a source tree that was never installed
        return "(not installed)"


def _command_in(argv: list[str]) -> str | None:
    """The command named by the arguments (the first word that is one), if any."""
    for word in argv:
        if word in COMMANDS:
            return word
        if not word.startswith("-"):
            return None
    return None


def one_line_usage_errors(parser: argparse.ArgumentParser, hint: str = "") -> None:
    """Make argparse report a usage error as one line (exit 2), not a usage block.

    argparse calls `parser.error` for an unknown option, a missing required
    argument or subcommand, a bad choice or a value of the wrong type; it is
    replaced on this parser only, so every parser of `stgen` speaks alike.
    """
    def error(message: str):
        if message.endswith("expected one argument") and _dash_value_follows(message):
            message += " (write a value that starts with '-' as --option=VALUE)"
        more = hint if message.endswith("required: COMMAND") else ""
        print(f"{parser.prog}: error: {message} ({more}see '{parser.prog} --help')", file=sys.stderr)
        sys.exit(2)

    parser.error = error


_ARGV: list[str] = []   # the arguments being parsed (for the hint below)


def _dash_value_follows(message: str) -> bool:
    """Whether the option argparse found without a value was followed by a
    word starting with '-' (`--period -1ms`): argparse takes it for an option."""
    option = message.removeprefix("argument ").split(":", 1)[0].split("/")[-1]
    for here, word in enumerate(_ARGV[:-1]):
        if word == option and _ARGV[here + 1].startswith("-"):
            return True
    return False


def _command_module(name: str):
    try:
        return importlib.import_module(f"stgen.commands.{name}")
    except ModuleNotFoundError as exc:
        if exc.name == f"stgen.commands.{name}":
            return None  # not built yet
        raise


def main(argv: list[str] | None = None) -> int:
    _ARGV[:] = sys.argv[1:] if argv is None else argv
    command = _command_in(_ARGV)
    if argv is None:    # the process's own command line (not a call from Python)
        gc.disable()    # importing makes only long-lived objects: collecting them is wasted
    parser = build_parser(only=command) if command else build_parser()
    if argv is None:    # a tenth of `stgen check`'s start-up was collections of them
        gc.freeze()     # and later collections skip them
        gc.enable()
    args, extra = parser.parse_known_args(argv)  # exits 2 on usage errors
    if extra:   # named by the subcommand, whose --help lists what it takes
        command_parser = parser.command_parsers.get(args.command, parser)
        command_parser.error(f"unrecognized arguments: {' '.join(extra)}")
    handler = getattr(args, "handler", None)
    if handler is None:
        parser.error(f"the '{args.command}' command is not available in this build")
    try:
        return handler(args)
    except KeyboardInterrupt:
        print("stgen: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # the promise: never a traceback
        print(f"stgen: internal error: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())

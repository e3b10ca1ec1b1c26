"""``stgen generate [--config FILE] [--target nj|iec|sysmac-xml|plcopen] [--determinant table|unrolled|lu] [--tests] --out DIR``.

Renders the platform's POUs from ``st_templates/`` and writes them for one
target: ``nj`` (Sysmac Studio bodies and variable tables), ``iec`` (plain
IEC 61131-3 files), ``sysmac-xml`` (one IEC 61131-10 XML file that Sysmac
Studio 1.30+ imports) or ``plcopen`` (one PLCopen TC6 XML 2.01 file). A configuration that cannot be read or is invalid is
reported as ``file[:line:col]: key: rule`` with exit status 1.

The folder is kept in step with the configuration: generated files of an
earlier run that this run does not write (a POU renamed, say) are removed,
and a file there that stgen did not write is never overwritten (exit status
1, nothing written); see :mod:`stgen.exports.folder`. An --out that names a
file is a usage error (exit status 2).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from stgen.commands.config_option import add_config_argument, config_from_args
from stgen.config import PlatformConfig
from stgen.exports import iec, plcopen_xml, sysmac, sysmac_xml
from stgen.exports.folder import FolderUpdate, ForeignFileError
from stgen.render import DETERMINANT_METHODS, RenderedProgram, RenderError, RenderOptions, render_program

#: Target name -> writer(program, out_dir) -> FolderUpdate.
TARGETS = {"nj": sysmac.write, "iec": iec.write, "sysmac-xml": sysmac_xml.write, "plcopen": plcopen_xml.write}


def write_program(program: RenderedProgram, out_dir: str | Path, target: str = "nj") -> FolderUpdate:
    """Write ``program`` for ``target`` into ``out_dir``; stale generated files there are removed
    and a file stgen did not write is never overwritten (:mod:`stgen.exports.folder`)."""
    if target not in TARGETS:
        raise ValueError(f"unknown target {target!r}; expected one of {', '.join(TARGETS)}")
    return TARGETS[target](program, out_dir)


def generate(out_dir: str | Path, target: str = "nj", config: PlatformConfig | None = None,
             options: RenderOptions | None = None) -> FolderUpdate:
    """Render ``config`` (default platform if ``None``) and write ``target``'s files into ``out_dir``."""
    return write_program(render_program(config, options), out_dir, target)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_config_argument(parser)
    parser.add_argument("--target", choices=sorted(TARGETS), default="nj",
                        help="nj: Sysmac Studio bodies + variable tables; iec: plain IEC 61131-3 files; "
                             "sysmac-xml: one IEC 61131-10 XML file for Sysmac Studio 1.30+; "
                             "plcopen: one PLCopen TC6 XML 2.01 file (default: nj)")
    parser.add_argument("--determinant", choices=DETERMINANT_METHODS, default="table",
                        help="Leibniz determinant as a permutation table loop, fully unrolled, "
                             "or the FK's det J from the LU diagonal (default: table)")
    parser.add_argument("--out", metavar="DIR", required=True, help="output folder (created if missing)")
    parser.add_argument("--tests", action="store_true",
                        help="also the test benches: one PROGRAM per bench (TB_...) with vectors from the "
                             "NumPy reference and results in TB_Globals; with --target iec also "
                             "test_benches.st for stgen test")


def run(args: argparse.Namespace) -> int:
    config = config_from_args(args, "generate")
    if config is None:
        return 1
    if Path(args.out).exists() and not Path(args.out).is_dir():
        print(f"stgen generate: error: --out {args.out}: is a file; --out names a folder",
              file=sys.stderr)
        return 2
    try:
        update = generate(args.out, args.target, config, RenderOptions(determinant=args.determinant,
                                                                          tests=args.tests))
    except (RenderError, ForeignFileError) as error:
        print(f"stgen generate: error: {error}", file=sys.stderr)
        return 1
    except OSError as error:
        print(f"stgen generate: error: cannot write {error.filename or args.out}: {error.strerror}", file=sys.stderr)
        return 1
    removed = f"; removed {len(update.removed)} stale: " + ", ".join(p.name for p in update.removed) if update.removed else ""
    print(f"stgen generate: wrote {len(update.written)} files for target '{args.target}' to {args.out}{removed}")
    return 0

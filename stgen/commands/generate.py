"""``stgen generate [--config FILE] [--target nj|iec] [--determinant table|unrolled|lu] --out DIR``.

Renders the platform's POUs from ``st_templates/`` and writes them for one
target: ``nj`` (Sysmac Studio bodies and variable tables) or ``iec`` (plain
IEC 61131-3 files). A configuration that cannot be read or is invalid is
reported as ``file[:line:col]: key: rule`` with exit status 1.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from stgen.config import ConfigError, PlatformConfig, load_config
from stgen.exports import iec, sysmac
from stgen.render import DETERMINANT_METHODS, RenderError, RenderOptions, render_program

#: Target name -> writer(program, out_dir) -> list of paths.
TARGETS = {"nj": sysmac.write, "iec": iec.write}


def generate(out_dir: str | Path, target: str = "nj", config: PlatformConfig | None = None,
             options: RenderOptions | None = None) -> list[Path]:
    """Render ``config`` (default platform if ``None``) and write ``target``'s files into ``out_dir``."""
    if target not in TARGETS:
        raise ValueError(f"unknown target {target!r}; expected one of {', '.join(TARGETS)}")
    program = render_program(config, options)
    return TARGETS[target](program, out_dir)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--config", metavar="FILE", help="platform TOML file (default: the study's platform)")
    parser.add_argument("--target", choices=sorted(TARGETS), default="nj",
                        help="nj: Sysmac Studio bodies + variable tables; iec: plain IEC 61131-3 files (default: nj)")
    parser.add_argument("--determinant", choices=DETERMINANT_METHODS, default="table",
                        help="Leibniz determinant as a permutation table loop, fully unrolled, "
                             "or the FK's det J from the LU diagonal (default: table)")
    parser.add_argument("--out", metavar="DIR", required=True, help="output folder (created if missing)")


def run(args: argparse.Namespace) -> int:
    try:
        config = load_config(args.config)
    except ConfigError as error:
        print(f"stgen generate: error: {error}", file=sys.stderr)
        return 1
    try:
        written = generate(args.out, args.target, config, RenderOptions(determinant=args.determinant))
    except RenderError as error:
        print(f"stgen generate: error: {error}", file=sys.stderr)
        return 1
    except OSError as error:
        print(f"stgen generate: error: cannot write {error.filename or args.out}: {error.strerror}", file=sys.stderr)
        return 1
    print(f"stgen generate: wrote {len(written)} files for target '{args.target}' to {args.out}")
    return 0

"""The ``--config FILE`` option shared by ``stgen generate``, ``verify`` and ``demo``."""

from __future__ import annotations

import argparse
import sys

from stgen.config import ConfigError, PlatformConfig, load_config


def add_config_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--config", metavar="FILE", help="platform TOML file (default: the study's platform)")


def config_from_args(args: argparse.Namespace, command: str) -> PlatformConfig | None:
    """The configuration named by ``--config`` (the default platform without it).

    A file that cannot be read or is invalid is reported on stderr as
    ``stgen <command>: error: file[:line:col]: key: rule`` and gives ``None``;
    the caller then exits with status 1.
    """
    try:
        return load_config(args.config)
    except ConfigError as error:
        print(f"stgen {command}: error: {error}", file=sys.stderr)
        return None

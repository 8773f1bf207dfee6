"""The ``femoat`` command line: one subcommand per module in :mod:`femoat.commands`."""

import argparse
import importlib
import sys

# Subcommand modules, each with ``add_parser(subparsers)`` and ``run(args) -> int``.
COMMANDS = ["impact", "contact_curves", "run", "paper", "wall", "render", "opensees", "compile",
            "suite", "study"]


def build_parser():
    parser = argparse.ArgumentParser(
        prog="femoat",
        description="Base-isolated buildings pounding their moat walls (units: kip, in, s).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    usages = []
    for name in COMMANDS:
        module = importlib.import_module(f"femoat.commands.{name}")
        p = module.add_parser(sub)
        p.set_defaults(_run=module.run)
        usages.append(p.format_usage().replace("usage: ", "  ").rstrip())
    # the options of every command in `femoat --help`; `femoat COMMAND --help` explains them
    parser.epilog = ("options of each command (femoat COMMAND --help explains them):\n"
                     + "\n".join(usages))
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    return parser


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args._run(args)
    except (ValueError, FileNotFoundError) as exc:
        print(f"femoat {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # Ctrl-C: one line, no traceback
        print(f"\nfemoat {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())

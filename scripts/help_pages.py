#!/usr/bin/env python3
"""Writes dfrecon's man page and bash completion from the built program's
--help (called by the build, cmake/dfreconInstall.cmake):

    help_pages.py PROGRAM --version 0.1.0 --man OUT.1 --completion OUT
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bash_completion  # noqa: E402
import dfrecon_help  # noqa: E402
import man_page  # noqa: E402


def write_replacing(path, text):
    """Writes `path` whole or not at all: a failed build leaves no half file."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    temporary = path + ".new"
    with open(temporary, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(temporary, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("program", help="the built dfrecon")
    parser.add_argument("--version", required=True, help="the version the man page names")
    parser.add_argument("--man", required=True, help="man page to write (roff)")
    parser.add_argument("--completion", required=True, help="bash completion script to write")
    args = parser.parse_args()
    root, commands = dfrecon_help.read_help(args.program)
    if not commands:
        sys.exit("help_pages.py: %s --help lists no subcommands" % args.program)
    write_replacing(args.man, man_page.render(root, commands, args.version))
    write_replacing(args.completion, bash_completion.render(root, commands))


if __name__ == "__main__":
    main()

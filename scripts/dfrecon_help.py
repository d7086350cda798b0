"""What `dfrecon --help` and `dfrecon COMMAND --help` say, as data.

The man page (man_page.py) and the bash completion (bash_completion.py) are
made from this, so they list exactly the subcommands and options the program
has. It reads CLI11's help layout: a description, a "Usage:" line, the
sections "Positionals:", "Options:" and "Subcommands:" of entries indented two
spaces, then the footer.
"""

import re
import subprocess
from dataclasses import dataclass, field

# CLI11 pads an entry's names and value to this column; a longer entry puts
# its description on the next line, indented to it.
HELP_COLUMN = 30
SECTIONS = {"Positionals:": "positionals", "Options:": "options", "Subcommands:": "subcommands"}


@dataclass
class Entry:
    """One positional, option or subcommand line."""

    names: list  # ["-o", "--output"]; ["file"] for a positional; ["info"] for a subcommand
    value: str  # what the option takes ("TEXT REQUIRED", "TEXT:{flat,dome,none}=flat"); "" for a flag
    description: str

    @property
    def choices(self):
        """The values a {a,b,c} set allows, else []."""
        match = re.search(r"\{([^}]*)\}", self.value)
        return match.group(1).split(",") if match else []


@dataclass
class Help:
    """One program's or subcommand's help."""

    name: str  # "dfrecon" or the subcommand's name
    description: str
    usage: str
    positionals: list = field(default_factory=list)
    options: list = field(default_factory=list)
    subcommands: list = field(default_factory=list)
    footer: str = ""


def _entry(line, continuation):
    """The entry on `line`; `continuation` is the next line (its description
    when the entry reached the help column)."""
    if continuation is not None and continuation.startswith(" " * HELP_COLUMN):
        head, description = line.strip(), continuation.strip()
    else:
        head, description = line[:HELP_COLUMN].strip(), line[HELP_COLUMN:].strip()
    names, _, value = head.partition(" ")
    return Entry(names.split(","), value.strip(), description)


def parse_help(name, text):
    """The Help that `text` (the output of NAME --help) describes."""
    lines = text.rstrip("\n").split("\n")
    usage_at = next(i for i, line in enumerate(lines) if line.startswith("Usage: "))
    help_ = Help(name, "\n".join(lines[:usage_at]).strip(), lines[usage_at][len("Usage: "):])
    section = None
    footer = []
    i = usage_at + 1
    while i < len(lines):
        line = lines[i]
        following = lines[i + 1] if i + 1 < len(lines) else None
        if footer:
            footer.append(line)
        elif line in SECTIONS:
            section = SECTIONS[line]
        elif not line.strip() or line.startswith(" " * HELP_COLUMN):
            pass  # a gap, or a description _entry took already
        elif line.startswith("  ") and section:
            getattr(help_, section).append(_entry(line, following))
        else:
            footer.append(line)
        i += 1
    help_.footer = "\n".join(footer).strip()
    return help_


def _run_help(program, *command):
    return subprocess.run([program, *command, "--help"], check=True, capture_output=True,
                          encoding="utf-8").stdout


def read_help(program):
    """(the program's Help, [each subcommand's Help]) from running `program`."""
    root = parse_help("dfrecon", _run_help(program))
    commands = [parse_help(s.names[0], _run_help(program, s.names[0])) for s in root.subcommands]
    return root, commands

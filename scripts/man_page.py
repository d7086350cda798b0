"""dfrecon(1) in roff, from the program's help (dfrecon_help.Help)."""

import re


def _text(s):
    """`s` as roff text: backslashes and hyphens escaped, characters beyond
    ASCII as \\[uXXXX] (troff reads bytes), no line taken for a request."""
    s = s.replace("\\", "\\e").replace("-", "\\-")
    s = "".join(c if ord(c) < 128 else "\\[u%04X]" % ord(c) for c in s)
    return "\n".join("\\&" + line if line[:1] in (".", "'") else line for line in s.split("\n"))


def _entry(entry):
    names = ", ".join("\\fB" + _text(n) + "\\fR" for n in entry.names)
    value = " \\fI" + _text(entry.value) + "\\fR" if entry.value else ""
    return ".TP\n" + names + value + "\n" + _text(entry.description) + "\n"


def _footer(footer):
    # Indented footer lines (lists such as synth's shapes) keep their lines.
    out = ""
    for line in footer.split("\n"):
        if not line.strip():
            out += ".PP\n"
        elif line.startswith(" "):
            out += ".br\n" + _text(line.strip()) + "\n"
        else:
            out += _text(line) + "\n"
    return out


def render(root, commands, version):
    """The whole page: name, synopsis, description, global options, then one
    subsection per subcommand with its usage, arguments, options and notes.
    Undated, so the same program always gives the same page."""
    summary = root.description.split("\n")[0]
    summary = re.sub(r"^dfrecon:\s*", "", summary).rstrip(".")
    page = '.TH DFRECON 1 "" "dfrecon %s" "User Commands"\n' % _text(version)
    page += ".SH NAME\ndfrecon \\- " + _text(summary) + "\n"
    page += ".SH SYNOPSIS\n.B dfrecon\n[\\fIOPTIONS\\fR] \\fISUBCOMMAND\\fR [\\fIARGUMENTS\\fR]\n"
    page += ".SH DESCRIPTION\n" + _text(root.description) + "\n"
    page += ".PP\nSubcommands:\n"
    for s in root.subcommands:
        page += ".TP\n\\fB" + _text(s.names[0]) + "\\fR\n" + _text(s.description) + "\n"
    page += ".SH OPTIONS\nThese come before the subcommand or after it.\n"
    page += "".join(_entry(o) for o in root.options)
    page += ".SH SUBCOMMANDS\n"
    for command in commands:
        page += '.SS "dfrecon %s"\n' % _text(command.name)
        page += _text(command.description) + "\n.PP\n"
        page += "\\fBUsage:\\fR " + _text(command.usage) + "\n"
        page += "".join(_entry(p) for p in command.positionals)
        page += "".join(_entry(o) for o in command.options)
        if command.footer:
            page += ".PP\n" + _footer(command.footer)
    page += (".SH FILES\nA file argument \\fB\\-\\fR is standard input or output where the "
             "format can stream (see docs/cli.md in the sources).\n")
    page += ".SH SEE ALSO\ndocs/cli.md, docs/formats.md and README.md in the dfrecon sources.\n"
    return page

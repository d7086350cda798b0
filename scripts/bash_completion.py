"""The bash completion for dfrecon, from the program's help
(dfrecon_help.Help): subcommand names, each subcommand's options (and the
global ones, which may follow it), an option's choices where it lists them,
file names for everything else."""


def _quote(words):
    return '"' + " ".join(words) + '"'


def _names(entries):
    """Every name of `entries`, each once, in order."""
    return list(dict.fromkeys(n for e in entries for n in e.names))


def render(root, commands):
    """A bash script defining _dfrecon and registering it for dfrecon."""
    global_valued = _names(o for o in root.options if o.value)
    out = [
        "# bash completion for dfrecon. Generated from `dfrecon --help` by",
        "# scripts/help_pages.py at build time; do not edit.",
        "_dfrecon() {",
        '    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}',
        "    # The subcommand: the first word that is neither an option nor a global",
        "    # option's value.",
        "    local command= i",
        "    for ((i = 1; i < COMP_CWORD; i++)); do",
        '        case ${COMP_WORDS[i]} in',
        "            %s) ((i++)) ;;" % "|".join(global_valued or ["--device"]),
        "            -*) ;;",
        '            *) command=${COMP_WORDS[i]}; break ;;',
        "        esac",
        "    done",
        "    local options valued",
        '    case $command in',
        '        "") options=%s; valued=%s ;;' % (_quote(_names(root.options)),
                                                  _quote(global_valued)),
    ]
    value_choices, positional_choices = [], []
    for command in commands:
        options = _names(command.options + root.options)
        valued = _names(o for o in command.options + root.options if o.value)
        out.append("        %s) options=%s; valued=%s ;;" % (command.name, _quote(options),
                                                              _quote(valued)))
        value_choices += ["        %s:%s) words=%s ;;" % (command.name, n, _quote(o.choices))
                          for o in command.options if o.choices for n in o.names]
        positional_choices += ["        %s) words=%s ;;" % (command.name, _quote(p.choices))
                               for p in command.positionals if p.choices]
    out += [
        "        *) return ;;",
        "    esac",
        "    local words=",
        "    case $command:$prev in",
        *value_choices,
        "    esac",
        '    if [[ -n $words ]]; then',
        '        COMPREPLY=($(compgen -W "$words" -- "$cur"))',
        '    elif [[ " $valued " == *" $prev "* ]]; then',
        '        COMPREPLY=($(compgen -f -- "$cur"))',
        "    elif [[ $cur == -* ]]; then",
        '        COMPREPLY=($(compgen -W "$options" -- "$cur"))',
        "    elif [[ -z $command ]]; then",
        '        COMPREPLY=($(compgen -W %s -- "$cur"))' % _quote(_names(root.subcommands)),
        "    else",
        "        case $command in",
        *positional_choices,
        "        esac",
        '        if [[ -n $words ]]; then',
        '            COMPREPLY=($(compgen -W "$words" -- "$cur"))',
        "        else",
        '            COMPREPLY=($(compgen -f -- "$cur"))',
        "        fi",
        "    fi",
        "}",
        "complete -o filenames -o bashdefault -F _dfrecon dfrecon",
        "",
    ]
    return "\n".join(out)

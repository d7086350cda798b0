#!/usr/bin/env bash
# The man page made at build time names every subcommand the program lists
# (read here from `dfrecon --help` on its own) and every option of each.
#   test_man_page.sh DFRECON MAN_PAGE
set -euo pipefail
program=$1 page=$2
fail() { echo "test_man_page: $*" >&2; exit 1; }
head -n 1 "$page" | grep -q '^\.TH DFRECON 1 ' || fail "$page does not start with .TH DFRECON 1"
commands=$("$program" --help | awk '/^Subcommands:/ { on = 1; next } on && /^  [a-z]/ { print $1 }')
[ -n "$commands" ] || fail "dfrecon --help lists no subcommands"
for command in $commands; do
  # Hyphens in roff are \-, as in batch\-report.
  grep -qF ".SS \"dfrecon ${command//-/\\-}\"" "$page" || fail "no section for $command"
  # Options as the page writes them: \fB\-\-name\fR.
  for option in $("$program" "$command" --help | grep -oE '^  (-[a-zA-Z],)?--[a-z0-9-]+' |
    sed 's/.*--//'); do
    grep -qF "\\fB\\-\\-${option//-/\\-}\\fR" "$page" || fail "$command --$option is not on the page"
  done
done
echo "man page names $(echo $commands | wc -w) subcommands and their options"

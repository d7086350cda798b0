#!/usr/bin/env bash
# The bash completion made at build time completes subcommands, their
# options and the values an option lists.
#   test_completion.sh COMPLETION_SCRIPT
set -uo pipefail
# shellcheck source=/dev/null
source "$1"
failures=0
expect() {
  local want=$1
  shift
  COMP_WORDS=("$@")
  COMP_CWORD=$(($# - 1))
  COMPREPLY=()
  _dfrecon
  if [ "${COMPREPLY[*]}" != "$want" ]; then
    echo "test_completion: '$*' gave '${COMPREPLY[*]}', want '$want'" >&2
    failures=$((failures + 1))
  fi
}
expect reconstruct dfrecon rec
expect info dfrecon --device cpu in
expect "--cap --cap-offset" dfrecon reconstruct --ca
expect "flat dome none" dfrecon reconstruct --cap ""
expect "--quiet" dfrecon reconstruct --qu
expect "--max-error --max-normal-turn" dfrecon simplify --max-
expect sphere dfrecon synth sph
exit $((failures > 0))

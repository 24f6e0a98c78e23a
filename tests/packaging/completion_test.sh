#!/usr/bin/env bash
# scripts/debian/completion.bash against the built programs: what <TAB> offers after a few command
# lines (plain bash; the programs' own --help is what it reads).
#   completion_test.sh COMPLETION_FILE BUILD_DIR (rigsimd, rigsimctl and rigsim-replay in it)
set -uo pipefail
source "$1"
PATH="$2:$PATH"
failed=0
expect() {   # expect "command line" "what <TAB> offers (sorted, spaces)"
  local line=$1 want=$2 got
  read -r -a COMP_WORDS <<< "$line"
  [[ $line == *" " ]] && COMP_WORDS+=("")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  case ${COMP_WORDS[0]} in
    rigsimd) _rigsimd ;;
    rigsimctl) _rigsimctl ;;
    rigsim-replay) _rigsim_replay ;;
  esac
  got=$(printf '%s\n' "${COMPREPLY[@]}" | sort | tr '\n' ' ' | sed 's/ $//')
  if [ "$got" = "$want" ]; then echo "ok   [$line] -> $got"; else echo "FAIL [$line] -> '$got', expected '$want'"; failed=1; fi
}
expect "rigsimd --pty-g" "--pty-group"
expect "rigsimd --state-" "--state-file --state-sync"
expect "rigsimd --log-level w" "warn"
expect "rigsimd --pty-group root" "root"
expect "rigsimctl cl" "clock"
expect "rigsimctl " "clock events fault frames log reset rig set state"
expect "rigsimctl clock " "pause resume run-until-idle scale show step"
expect "rigsimctl --format table fault " "add clear list rm"
expect "rigsimctl fault add --ch" "--channel"
expect "rigsimctl --format t" "table"
expect "rigsim-replay --tim" "--timeout --timing --timing-slack"
exit $failed

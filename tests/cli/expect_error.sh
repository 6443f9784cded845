#!/usr/bin/env bash
# Runs a command and checks how it ends: its exit code and what it prints.
#
#   expect_error.sh [--absent PATH] EXPECTED_EXIT REGEX -- command args...
#
# Passes (exit 0) when the command, run under `timeout ${EXPECT_TIMEOUT:-60}`,
#   - exits with EXPECTED_EXIT (0 for a command that must succeed), and
#   - its combined stdout+stderr matches the extended regular expression REGEX (grep -E),
#   - and, with --absent PATH, PATH does not exist afterwards (a refused `run --out PATH`
#     must not have started writing results). PATH is removed first so that a stale
#     folder cannot fail the check; for safety it must contain "/cli_out/".
# Fails (exit 1) otherwise, and always when the command timed out, could not be
# started or died of a signal (exit code >= 124): bad input must end in a clear
# error, never a hang or a crash. The captured output is printed either way.
set -u

usage() {
  echo "usage: $0 [--absent PATH] EXPECTED_EXIT REGEX -- command args..." >&2
  exit 1
}

absent=""
if [[ $# -ge 2 && "$1" == "--absent" ]]; then
  absent="$2"
  shift 2
  [[ "$absent" == */cli_out/* ]] || { echo "expect_error.sh: --absent path '$absent' must contain /cli_out/" >&2; exit 1; }
fi
[[ $# -ge 4 && "$3" == "--" ]] || usage
expected="$1"
regex="$2"
shift 3
[[ "$expected" =~ ^[0-9]+$ && "$expected" -lt 124 ]] ||
  { echo "expect_error.sh: EXPECTED_EXIT must be an integer below 124, got '$expected'" >&2; exit 1; }

[[ -n "$absent" ]] && rm -rf -- "$absent"

output="$(timeout "${EXPECT_TIMEOUT:-60}" "$@" 2>&1)"
rc=$?

echo "---- command: $*"
echo "---- exit code: $rc (expected $expected)"
echo "---- output:"
printf '%s\n' "$output"
echo "----"

failures=()
if [[ $rc -ge 124 ]]; then
  case $rc in
    124) why="timed out after ${EXPECT_TIMEOUT:-60} s" ;;
    125) why="timeout itself failed" ;;
    126) why="command found but not executable" ;;
    127) why="command not found" ;;
    *) why="killed by signal $((rc - 128)) ($(kill -l $((rc - 128)) 2>/dev/null || echo '?'))" ;;
  esac
  failures+=("exit code $rc: $why (a crash or hang, never acceptable)")
fi
[[ $rc -eq $expected ]] || failures+=("exit code $rc, expected $expected")
printf '%s\n' "$output" | grep -Eq -- "$regex" ||
  failures+=("output does not match the regular expression: $regex")
if [[ -n "$absent" && -e "$absent" ]]; then
  failures+=("'$absent' exists: the command wrote results although it should have refused first")
fi

if [[ ${#failures[@]} -gt 0 ]]; then
  for f in "${failures[@]}"; do echo "FAIL: $f"; done
  exit 1
fi
echo "PASS: exit code $rc and output matches: $regex"
exit 0

#!/usr/bin/env bash
# A run's log must keep what happened, whichever rank it happened on:
#   expect_in_log.sh DIR REGEX -- command args...
# Removes the run folder DIR first (so an earlier log cannot pass), runs the command
# (itself a check, e.g. expect_error.sh: it must exit 0), then requires a line of
# DIR/fe2heart.log to match the extended regular expression REGEX.
set -uo pipefail
dir=$1 regex=$2
[[ $3 == -- ]] || { echo "usage: $0 DIR REGEX -- command args..."; exit 1; }
shift 3
[[ "$dir" == */mpi_out/* || "$dir" == */cli_out/* ]] || { echo "DIR '$dir' must contain /mpi_out/ or /cli_out/"; exit 1; }
rm -rf "$dir"
"$@" || { echo "FAIL: the command failed"; exit 1; }
echo "---- $dir/fe2heart.log:"
cat "$dir/fe2heart.log" 2>/dev/null || { echo "FAIL: no $dir/fe2heart.log"; exit 1; }
echo "----"
grep -Eq -- "$regex" "$dir/fe2heart.log" || { echo "FAIL: no line of the log matches: $regex"; exit 1; }
echo "PASS: the log has: $regex"

#!/usr/bin/env bash
# Re-running into a folder that holds an earlier run (issue 7, item 10):
#   rerun_folder.sh refuse|overwrite FE2HEART SPEC DIR
# Both modes: run SPEC into DIR, then add a stale displacement_00099.vtu (a step this
# run never reaches) and a user file notes.txt.
#   refuse:    run again without --overwrite: exit 2, a message naming DIR and the
#              remedy, and nothing in DIR written or removed (summary.json, the stale
#              VTU and notes.txt unchanged).
#   overwrite: run again with --overwrite: exit 0, the stale VTU is gone, notes.txt is
#              kept, and the new summary.json is complete.
set -uo pipefail
mode=$1 fe2heart=$2 spec=$3 dir=$4
[[ "$dir" == */cli_out/* ]] || { echo "DIR '$dir' must contain /cli_out/"; exit 1; }
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$dir"
mkdir -p "$dir"  # an existing empty folder is fine
"$fe2heart" run "$spec" --out "$dir" --log-level warn || fail "first run into an empty folder failed"
echo stale > "$dir/displacement_00099.vtu"
echo "my notes" > "$dir/notes.txt"
cp "$dir/summary.json" "$dir.summary.before"  # per test: refuse and overwrite run in parallel
case $mode in
  refuse)
    output=$("$fe2heart" run "$spec" --out "$dir" 2>&1); rc=$?
    printf '%s\n' "$output"
    [[ $rc -eq 2 ]] || fail "exit code $rc, expected 2"
    printf '%s\n' "$output" | grep -Fq -- "--out '$dir' already holds an fe2heart run (" ||
      fail "the message does not name the folder"
    printf '%s\n' "$output" | grep -Eq -- "run [(]1[0-9] files: .*[)]. use --overwrite to replace it, or another --out" ||
      fail "the message does not count the files and name the remedy"
    cmp -s "$dir/summary.json" "$dir.summary.before" || fail "summary.json was rewritten"
    [[ -f "$dir/displacement_00099.vtu" ]] || fail "the refused run removed displacement_00099.vtu"
    [[ $(cat "$dir/notes.txt") == "my notes" ]] || fail "notes.txt changed"
    ;;
  overwrite)
    "$fe2heart" run "$spec" --out "$dir" --overwrite --log-level warn || fail "run with --overwrite failed"
    [[ ! -e "$dir/displacement_00099.vtu" ]] || fail "the stale displacement_00099.vtu is still there"
    [[ -f "$dir/displacement_00001.vtu" ]] || fail "the new run wrote no displacement_00001.vtu"
    [[ $(cat "$dir/notes.txt") == "my notes" ]] || fail "notes.txt (not fe2heart's) was removed or changed"
    grep -q '"complete": true' "$dir/summary.json" || fail "summary.json is not complete"
    ;;
  *) fail "mode must be refuse or overwrite" ;;
esac
echo "PASS ($mode)"

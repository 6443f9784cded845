#!/bin/bash
# Every shipped scene, unit and study in configs/ validates (exit 0) without a warning:
# an example whose unit does not resolve its own cell layout (or that warns otherwise)
# teaches users to ignore warnings.
#   validate_shipped_configs.sh FE2HEART CONFIG_DIR
fe2heart=$1 dir=$2 failures=0 count=0
for f in "$dir"/*.json; do
  count=$((count + 1))
  out=$("$fe2heart" validate "$f" 2>&1)
  rc=$?
  if [ $rc -ne 0 ]; then
    echo "FAIL: $f: exit $rc"; echo "$out" | tail -3; failures=$((failures + 1))
  elif echo "$out" | grep -q "\[warning\]"; then
    echo "FAIL: $f warns:"; echo "$out" | grep "\[warning\]"; failures=$((failures + 1))
  fi
done
echo "$count configs, $failures failing"
[ "$count" -gt 0 ] && [ "$failures" -eq 0 ]

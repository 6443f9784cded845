#!/bin/bash
# Every relative markdown link in README.md, BENCHMARKS.md and docs/ must name a file or
# folder of the worktree (anchors are stripped; http(s) links skipped).
cd "$(dirname "$0")/.."
bad=0; n=0
for f in README.md BENCHMARKS.md $(find docs -name '*.md'); do
  dir=$(dirname "$f")
  while IFS= read -r t; do
    t=${t#*](}; t=${t%)}; t=${t%%#*}
    [[ -z $t || $t == http* ]] && continue
    n=$((n+1))
    [[ -e "$dir/$t" ]] || { echo "MISSING $f -> $t"; bad=$((bad+1)); }
  done < <(grep -o '](\([^)# ]*\)\(#[^) ]*\)\?)' "$f")
done
echo "$n links, $bad missing"
if grep -rn "\.\./shared" README.md BENCHMARKS.md docs; then echo "points outside the repository"; bad=$((bad+1)); fi
((bad == 0))

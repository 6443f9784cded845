#!/bin/bash
# `fe2heart bench blas` and the warning of `fe2heart run` when OpenBLAS runs kernels
# below the CPU's vector extension (worker/blas_core.h). Forced to the generic
# "Prescott" kernels, a CPU with AVX2 or AVX-512 must get a suggestion and the run must
# warn naming it; with the suggestion set, OpenBLAS must take it and nothing is said.
#   check_blas_core.sh FE2HEART SPEC OUT
fe2heart=$1 spec=$2 out=$3
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/^ *\"$1\": \"\(.*\)\",\{0,1\}$/\1/p"; }

generic=$(OPENBLAS_CORETYPE=Prescott "$fe2heart" bench blas) || fail "bench blas exit $?"
echo "$generic"
core=$(echo "$generic" | field openblas_core)
cpu=$(echo "$generic" | field cpu)
suggested=$(echo "$generic" | field suggested_OPENBLAS_CORETYPE)
[ -n "$cpu" ] || fail "no cpu field"
if [ -z "$core" ]; then echo "not OpenBLAS: nothing to check"; exit 0; fi
[ "$core" = Prescott ] || fail "OPENBLAS_CORETYPE=Prescott gave core '$core'"
case $cpu in
  avx512) [ "$suggested" = SkylakeX ] || fail "AVX-512 CPU on Prescott kernels: suggested '$suggested'" ;;
  avx2) [ "$suggested" = Haswell ] || fail "AVX2 CPU on Prescott kernels: suggested '$suggested'" ;;
  *) [ -z "$suggested" ] || fail "CPU without AVX2: suggested '$suggested'"; echo "no AVX2: nothing more to check"; exit 0 ;;
esac
[ "$(OPENBLAS_CORETYPE=Prescott "$fe2heart" bench blas --suggested-coretype)" = "$suggested" ] ||
  fail "--suggested-coretype does not print '$suggested'"

log=$(OPENBLAS_CORETYPE=Prescott "$fe2heart" run "$spec" --out "$out/generic" --overwrite 2>&1) ||
  fail "run exit $?: $(echo "$log" | tail -2)"
echo "$log" | grep "\[warning\].*OpenBLAS runs its 'Prescott' kernels.*OPENBLAS_CORETYPE=$suggested" ||
  fail "the run does not warn about the Prescott kernels"
grep -q "OPENBLAS_CORETYPE=$suggested" "$out/generic/fe2heart.log" || fail "the warning is not in fe2heart.log"

fitted=$(OPENBLAS_CORETYPE=$suggested "$fe2heart" bench blas)
[ "$(echo "$fitted" | field openblas_core)" = "$suggested" ] || fail "OPENBLAS_CORETYPE=$suggested not taken: $fitted"
[ -z "$(echo "$fitted" | field suggested_OPENBLAS_CORETYPE)" ] || fail "a suggestion although the kernels fit: $fitted"
log=$(OPENBLAS_CORETYPE=$suggested "$fe2heart" run "$spec" --out "$out/fitted" --overwrite 2>&1) ||
  fail "run exit $?"
if echo "$log" | grep -q "OpenBLAS runs"; then fail "the run warns although the kernels fit"; fi
echo "ok: $cpu CPU, Prescott kernels warned with $suggested, $suggested taken silently"

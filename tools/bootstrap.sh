#!/usr/bin/env bash
# fe2heart on a fresh Debian 12 machine, as root. Idempotent, non-interactive.
#   tools/bootstrap.sh demo   install what is missing, build, run the default beat
#   tools/bootstrap.sh test   install what is missing, build, run the whole test suite
set -euo pipefail
mode=${1:-}
[[ $mode == demo || $mode == test ]] || { echo "usage: $0 demo|test" >&2; exit 2; }
top=$(cd "$(dirname "$0")/.." && pwd)
cd "$top"

packages=(build-essential cmake pkg-config openmpi-bin libopenmpi-dev libeigen3-dev
          libsuitesparse-dev libopenblas-dev libmumps-dev libmetis-dev libspdlog-dev nlohmann-json3-dev
          libcli11-dev libgtest-dev python3-matplotlib python3-jsonschema python3-meshio python3-gmsh clang libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Ranks must not fight over the two cores with BLAS threads; root may run mpirun.
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

# The machine's cores: GNU nproc would answer OMP_NUM_THREADS (1, set above).
jobs=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)
# The test build is warning-free and stays so (-Werror); the demo build only warns.
werror=OFF
[[ $mode == test ]] && werror=ON
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
# Paths relative to the checkout in ccache's keys: a clone elsewhere reuses the cache;
# the precompiled headers (CMakeLists.txt, FE2_PCH) are cacheable only with this sloppiness.
export CCACHE_BASEDIR="$top"
export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFE2_WERROR=$werror "${launcher[@]}" >/dev/null
cmake --build build -j"$jobs"

# OpenBLAS falls back to its generic SSE3 kernels on CPU models it does not know (seen
# on an AVX-512 Xeon, model 207: factorizations 3.3x slower); take the kernels that fit.
if [[ -z ${OPENBLAS_CORETYPE:-} ]]; then
  coretype=$(./build/tools/fe2heart bench blas --suggested-coretype 2>/dev/null || true)
  if [[ -n $coretype ]]; then
    echo "OpenBLAS did not recognise this CPU; using OPENBLAS_CORETYPE=$coretype"
    export OPENBLAS_CORETYPE=$coretype
  fi
fi

if [[ $mode == demo ]]; then
  # The default beat: a human-sized LV whose cells contract inside FE² units, on the
  # machine's cores (two ranks at least: one coordinates and works, one works).
  out="$top/out/lv-beat"
  ranks=$(( jobs > 2 ? jobs : 2 ))
  extra=()
  (( ranks > jobs )) && extra=(--oversubscribe)
  echo "running the default beat (configs/lv-beat.json) on $ranks ranks; about 1.5 minutes on 2 cores"
  mpirun -n "$ranks" "${extra[@]}" ./build/tools/fe2heart run configs/lv-beat.json --out "$out" --overwrite
  echo
  echo "PV loop:   $out/pv_loop.png  (pressures and volumes over the beat: $out/pv_time.png)"
  echo "figures:   $out/summary.json  (circulation: EDV, ESV, EF, peak pressure; history: every step)"
  echo "ParaView:  $out/displacement.pvd  (Warp By Vector 'displacement'; units at systole: $out/units/)"
else
  cd build
  # Every label but "long" (tests of minutes each; ctest -L long runs them).
  ctest -j"$jobs" --output-on-failure --timeout 900 -LE long
fi

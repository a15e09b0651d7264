#!/usr/bin/env bash
# Instructions per particle-step of the collapsing column (one thread) counted by valgrind's
# callgrind: a figure free of timing noise, to see a 10% change. valgrind 3.19 cannot run AVX-512
# code, so this builds its own tree for AVX2 + FMA (-march=haswell; ISA=x86-64 for the SSE2
# baseline) in build-instructions/ and counts only the measured steps (not the set-up).
# Usage: bench/instructions.sh [elastic|drucker_prager] [PARTICLES] [STEPS] [usf|usl]
# (defaults: elastic 9800 20 usf). Prints instructions per particle-step and the stages' shares.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
model="${1:-elastic}" particles="${2:-9800}" steps="${3:-20}" update="${4:-usf}"
isa="${ISA:-haswell}"
# Highway's SSE4 and AVX2 targets ask for AES, which GCC's -march=haswell leaves out (the CPUs
# have it): without it the SIMD sweeps would be counted in their SSSE3 form.
aes="$([ "$isa" = x86-64 ] || echo -maes)"
dir="${INSTRUCTIONS_BUILD_DIR:-$root/build-instructions-$isa}"
export PATH="/usr/bin:$PATH"  # Debian's python3 for catkin (shared/ros-on-debian.md)
mkdir -p "$dir/devel/lib/python3/dist-packages"
cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DMPM_SDEM_NATIVE=OFF \
  -DCMAKE_CXX_FLAGS="-march=$isa $aes" -DMPM_SDEM_STATIC_SIMD=ON -DCATKIN_ENABLE_TESTING=OFF \
  >"$dir/cmake.log" 2>&1 ||
  { cat "$dir/cmake.log"; exit 1; }
cmake --build "$dir" -j"${JOBS:-2}" --target mpm_sdem_bench_instructions >"$dir/build.log" 2>&1 ||
  { tail -30 "$dir/build.log"; exit 1; }
out="$dir/callgrind.$model.$particles.$update.out"
log="$(OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$out" \
  --toggle-collect='measuredSteps*' "$dir/devel/lib/mpm_sdem/mpm_sdem_bench_instructions" \
  "$model" "$particles" "$steps" "$update" 2>&1)"
n="$(echo "$log" | sed -n 's/^particles \([0-9]*\)$/\1/p')"
total="$(callgrind_annotate "$out" 2>/dev/null | sed -n 's/^ *\([0-9,]*\) .*PROGRAM TOTALS.*/\1/p' | tr -d ,)"
echo "column $model ($update), $n points, $steps steps, -march=$isa, one thread"
awk -v t="$total" -v n="$n" -v s="$steps" \
  'BEGIN { printf "instructions per particle-step: %.0f (%s in the measured steps)\n", t / (n * s), t }'
# The stages (inclusive): where the instructions go.
callgrind_annotate --inclusive=yes "$out" 2>/dev/null |
  grep -E "World::(particleToGrid|gridToParticle|stressAndInternalForce|binParticles|clearGrid|gridVelocity|chooseTimeStep|constitutiveUpdate|couplingStage|stepBodies)" |
  awk -v t="$total" '{ gsub(",", "", $1); printf "  %5.1f%%  %s\n", 100 * $1 / t, $0 }' |
  sed 's/  *\[.*//' | cut -c1-110

#!/usr/bin/env bash
# The validation report's cases at CI resolution, each (or each run of a split case) a run of
# the validation sweep as scripts/validate runs them (two at once here, one thread each), the
# split cases combined at the gather: fails when a run or a combine step fails or measures a
# non-finite quantity (mpm_sdem_validate's exit status 3 leaves its run not done).
# usage: test/validate_fast.sh MPM_SDEM_VALIDATE MPM_SDEM_SWEEP OUT_DIR
set -euo pipefail
validate="$1" sweep="$2" out="$3"
rm -rf "$out" && mkdir -p "$out"  # never resume: the runs are this build's
{
  echo "name: validation_fast"
  echo "validation:"
  echo "  fast: true"
  echo "  cases: [$("$validate" --fast --list --runs | paste -sd, -)]"
} >"$out/validation.yaml"
status=0
"$sweep" "$out/validation.yaml" --out "$out" || status=$?
if [ "$status" != 0 ]; then
  for log in "$out"/runs/*/log.txt; do
    [ -f "$(dirname "$log")/summary.csv" ] && grep -q "^0," "$(dirname "$log")/summary.csv" && continue
    echo "---- $log"; tail -20 "$log"
  done
  [ -f "$out/combine.log" ] && { echo "---- $out/combine.log"; tail -20 "$out/combine.log"; }
fi
exit "$status"

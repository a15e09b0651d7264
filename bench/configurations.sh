#!/usr/bin/env bash
# One table of the particle-step's configurations (issue 78): precision (a double and a float
# build), stress update (USF, USL) and material (the columns of bench_scenes.cpp), each a row,
# with a reference program timed in the same rounds. Each round runs the reference, then each
# build's mpm_sdem_bench_throughput on every configuration, so that a drift of the machine's
# speed falls on all of them; the table gives the medians over the rounds and their ratios to
# the reference's median.
# Usage: bench/configurations.sh DOUBLE_BIN_DIR FLOAT_BIN_DIR OUT.csv [throughput arguments...]
#   BIN_DIR: a build's devel/lib/mpm_sdem; the float build is configured with
#     -DMPM_SDEM_SINGLE_PRECISION=ON (docs/building.md).
#   REFERENCE_10K, REFERENCE_100K: commands that print "... N M particle-steps/s" for the
#     reference at 9,800 and 100,352 points (../shared/peers/mls88.md); omitted when unset.
#   ROUNDS (default 3); default arguments: --particles 10000,100000 --threads 1,2 --steps 200
#     --repeats 3 --update usf,usl
set -euo pipefail
double="$1" float="$2" out="$3"
shift 3
args=("$@")
[ ${#args[@]} -gt 0 ] ||
  args=(--particles 10000,100000 --threads 1,2 --steps 200 --repeats 3 --update usf,usl)
rounds="${ROUNDS:-3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$rounds"); do
  for size in 10K 100K; do
    command="REFERENCE_$size"
    if [ -n "${!command:-}" ]; then
      ${!command} | grep -o '[0-9.]* M particle-steps/s' | cut -d' ' -f1 >> "$tmp/reference_$size"
    fi
  done
  for build in double float; do
    dir="$double"
    [ "$build" = float ] && dir="$float"
    "$dir/mpm_sdem_bench_throughput" "${args[@]}" --csv "$tmp/$build.$r.csv" >/dev/null
  done
  echo "round $r/$rounds done" >&2
done
python3 - "$tmp" "$out" "$rounds" <<'EOF'
import csv, os, statistics, sys
tmp, out, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])
reference = {}
for size, points in (("10K", 10000), ("100K", 100000)):
    path = f"{tmp}/reference_{size}"
    if os.path.exists(path):
        reference[points] = statistics.median(float(x) for x in open(path).read().split())
rates = {}
for build in ("double", "float"):
    for r in range(1, rounds + 1):
        for row in csv.DictReader(open(f"{tmp}/{build}.{r}.csv")):
            key = (build, row["case"], int(row["particles"]), int(row["threads"]))
            rates.setdefault(key, []).append(float(row["median_particle_steps_per_s"]) * 1e-6)
def nominal(points):  # the column's requested size: 9,800 and 100,352 points are 10k and 100k
    return min(reference or {points: 0}, key=lambda n: abs(n - points))
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["precision", "case", "particles", "threads", "median_m_per_s",
                "reference_m_per_s", "ratio_to_reference", "ratio_to_one_thread"])
    if reference:
        print("reference (M/s): " + ", ".join(f"{n}: {v:.2f}" for n, v in sorted(reference.items())))
    print("precision | case | points | threads | M/s | x reference | x one thread")
    for key in sorted(rates, key=lambda k: (k[1], k[2], k[0], k[3])):
        build, case, points, threads = key
        m = statistics.median(rates[key])
        ref = reference.get(nominal(points))
        one = rates.get((build, case, points, 1))
        ratio = m / ref if ref else float("nan")
        scaling = m / statistics.median(one) if one else float("nan")
        w.writerow([build, case, points, threads, f"{m:.4g}", f"{ref or float('nan'):.4g}",
                    f"{ratio:.3f}", f"{scaling:.3f}"])
        print(f"{build} | {case} | {points} | {threads} | {m:.2f} | {ratio:.2f} | {scaling:.2f}")
EOF
echo "table: $out"

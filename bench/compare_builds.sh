#!/usr/bin/env bash
# Before/after throughput of two builds of mpm_sdem on the same cases, interleaved so that a
# drift of the machine's speed falls on both: ROUNDS times (default 3) the baseline's
# mpm_sdem_bench_throughput, then the candidate's, each taking the median of its own repeats.
# Writes one CSV row per build and case with the median over the rounds of every figure
# (particle-steps per second and each stage's microseconds per step), and prints the ratios.
# Usage: bench/compare_builds.sh BASE_BIN_DIR NEW_BIN_DIR OUT.csv [throughput arguments...]
#   BIN_DIR: a build's devel/lib/mpm_sdem (holding mpm_sdem_bench_throughput).
#   default arguments: --particles 10000,100000 --threads 1,2 --steps 200 --repeats 3
#   BASE_LABEL and NEW_LABEL (default base, new) name the builds in the CSV.
set -euo pipefail
base="$1" new="$2" out="$3"
shift 3
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(--particles 10000,100000 --threads 1,2 --steps 200 --repeats 3)
rounds="${ROUNDS:-3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$rounds"); do
  for which in base new; do
    dir="$base"
    [ "$which" = new ] && dir="$new"
    "$dir/mpm_sdem_bench_throughput" "${args[@]}" --csv "$tmp/$which.$r.csv" >/dev/null
    echo "round $r/$rounds: $which done" >&2
  done
done
python3 - "$tmp" "$out" "$rounds" "${BASE_LABEL:-base}" "${NEW_LABEL:-new}" <<'EOF'
import csv, statistics, sys
tmp, out, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])
label = {"base": sys.argv[4], "new": sys.argv[5]}
rows = {}
for which in ("base", "new"):
    for r in range(1, rounds + 1):
        for row in csv.DictReader(open(f"{tmp}/{which}.{r}.csv")):
            rows.setdefault((which, row["case"], row["particles"], row["threads"]), []).append(row)
with open(out, "w", newline="") as f:
    w = None
    for key, runs in sorted(rows.items(), key=lambda kv: (kv[0][1], int(kv[0][2]), int(kv[0][3]), kv[0][0])):
        numeric = [k for k in runs[0] if k not in ("case", "particles", "threads", "steps")]
        med = {k: statistics.median(float(x[k]) for x in runs) for k in numeric}
        row = {"build": label[key[0]], "case": key[1], "particles": key[2], "threads": key[3]}
        row.update({k: f"{v:.4g}" for k, v in med.items()})
        if w is None:
            w = csv.DictWriter(f, fieldnames=list(row))
            w.writeheader()
        w.writerow(row)
        rows[key] = med
cases = sorted({k[1:] for k in rows}, key=lambda c: (c[0], int(c[1]), int(c[2])))
print("case | points | threads | before (M/s) | after (M/s) | ratio")
for c in cases:
    b, n = rows[("base",) + c], rows[("new",) + c]
    sb, sn = b["median_particle_steps_per_s"], n["median_particle_steps_per_s"]
    print(f"{c[0]} | {c[1]} | {c[2]} | {sb / 1e6:.2f} | {sn / 1e6:.2f} | {sn / sb:.2f}")
EOF
echo "table: $out"

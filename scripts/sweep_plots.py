#!/usr/bin/python3
"""Plots of a gathered sweep (mpm_sdem_sweep writes summary.csv, then calls this).

usage: sweep_plots.py SWEEP_DIR
Writes SWEEP_DIR/error_vs_cost.png (the error of each setting's ensemble mean against the mean
wall time of its runs, one panel per output with a reference) and SWEEP_DIR/spread.png (each
output's mean, standard deviation and min/max per setting, the reference as a line).
"""
import csv
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    return float(text) if text not in ("", None) else None


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    with open(os.path.join(folder, "summary.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if int(r["runs"]) > 0]
    if not rows:
        print("sweep_plots: no finished setting to plot", file=sys.stderr)
        return
    columns = list(rows[0].keys())
    keys = columns[1:columns.index("runs")]
    outputs = [c[:-len("_mean")] for c in columns
               if c.endswith("_mean") and c not in ("steps_mean", "wall_s_mean")]
    # A setting is labelled by the keys that vary across the sweep.
    varying = [k for k in keys if len({r[k] for r in rows}) > 1] or keys
    labels = [textwrap.fill(", ".join(r[k] for k in varying), 22) for r in rows]

    with_reference = [o for o in outputs if f"{o}_error" in columns]
    if with_reference:
        fig, axes = plt.subplots(1, len(with_reference), figsize=(6 * len(with_reference), 4.5),
                                 squeeze=False)
        for ax, o in zip(axes[0], with_reference):
            for r, label in zip(rows, labels):
                cost, error = number(r["wall_s_mean"]), number(r[f"{o}_error"])
                if cost is None or error is None:
                    continue
                ax.loglog(cost, max(error, 1e-16), "o")
                ax.annotate(label.replace("\n", " "), (cost, max(error, 1e-16)), fontsize=7,
                            xytext=(4, 2), textcoords="offset points")
            ax.set_xlabel("wall time per run (s)")
            ax.set_ylabel(f"|mean - reference| / reference")
            ax.set_title(o)
            ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "error_vs_cost.png"), dpi=110)
        plt.close(fig)

    fig, axes = plt.subplots(len(outputs), 1, figsize=(max(6, 1.4 * len(rows) + 2),
                                                      3.4 * len(outputs)), squeeze=False)
    x = list(range(len(rows)))
    for ax, o in zip(axes[:, 0], outputs):
        mean = [number(r[f"{o}_mean"]) for r in rows]
        std = [number(r[f"{o}_std"]) for r in rows]
        low = [number(r[f"{o}_min"]) for r in rows]
        high = [number(r[f"{o}_max"]) for r in rows]
        ax.errorbar(x, mean, yerr=std, fmt="o", capsize=4, label="mean, standard deviation")
        ax.plot(x, low, "v", color="gray", label="min, max")
        ax.plot(x, high, "^", color="gray")
        if f"{o}_reference" in columns:
            ax.axhline(number(rows[0][f"{o}_reference"]), color="k", ls="--", lw=1,
                       label="reference")
        ax.set_ylabel(o)
        ax.set_xticks(x)
        ax.set_xticklabels(labels, fontsize=7)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    axes[0, 0].set_title("settings: " + ", ".join(varying), fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "spread.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()

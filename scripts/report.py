#!/usr/bin/python3
"""Writes docs/validation/REPORT.md and its plots from what mpm_sdem_validate measured.

usage: report.py DATA_DIR REPORT_DIR MODE MACHINE
DATA_DIR holds results.csv and the case series; MODE is 'fast' or 'report'.
"""
import csv
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCHEMES = ["imp", "imp_grid", "multi_velocity", "particle_surface", "partitioned"]

# The cases issue 7 lists, and which of them this report reproduces so far.
CASES = [
    ("collision", "Seed 000 sec. 5.1: collision energy transfer (5.1.1)", True),
    ("drop", "Seed 000 sec. 5.1: drop and bounce energy", True),
    ("forces", "Seed 000 sec. 5.2: normal force at Table 2's grid sizes, friction force", True),
    ("silo", "Seed 000 sec. 5.3: silo discharge against Beverloo", False),
    ("contact_schemes", "Seed 000 sec. 5.4: contact-scheme comparison (1D rod)", True),
    ("debris", "Seed 000 sec. 6 / seed 003: granular flow hitting three wooden blocks", True),
    ("compression", "Seed 000 sec. 7: granular matrix compression", False),
    ("incline", "Seed 002 sec. 4.1: disk rolling on an incline", True),
    ("bar", "Seed 001: 1D reversibility and bar under a stress boundary condition", False),
    ("stability", "Stability on hard cases (so far: 50 m/s impact, 1 kPa material under a heavy "
                  "block; a fixed step above the bound is refused before the run, see "
                  "test_free_fall)", True),
]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def fmt(x, digits=4):
    v = float(x)
    if v == 0:
        return "0"
    if abs(v) >= 1e5 or abs(v) < 1e-3:
        return "%.3g" % v
    return "%.*g" % (digits, v)


def table(rows):
    out = ["| quantity | value | reference | unit | source | error | wall (s) | settings |",
           "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        out.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["quantity"], fmt(r["value"], 6), fmt(r["reference"], 6), r["unit"], r["source"],
            fmt(r["error"]), fmt(r["wall_s"]), r["settings"]))
    return "\n".join(out)


def plot_collision(data, out):
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5), sharey=True)
    for ax, name in zip(axes, ["hard", "soft"]):
        path = os.path.join(data, "collision_%s.csv" % name)
        if not os.path.exists(path):
            return None
        rows = read_csv(path)
        t = [float(r["time"]) * 1e3 for r in rows]
        for key, label in [("disk_kinetic", "disk kinetic"), ("block_kinetic", "block kinetic"),
                           ("elastic", "disk elastic")]:
            ax.plot(t, [float(r[key]) for r in rows], label=label)
        ax.set_title("%s disk" % name)
        ax.set_xlabel("time (ms)")
        ax.set_xlim(0, 20)
    axes[0].set_ylabel("energy (J/m)")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "collision_energy.png"), dpi=110)
    plt.close(fig)
    return "collision_energy.png"


def plot_contact_schemes(data, out):
    path = os.path.join(data, "contact_schemes.csv")
    if not os.path.exists(path):
        return None
    rows = read_csv(path)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    for s in SCHEMES:
        rs = [r for r in rows if r["scheme"] == s]
        h = [100 * float(r["cell_size_m"]) for r in rs]
        axes[0].semilogy(h, [max(float(r["v2_error"]), 1e-16) for r in rs], "o-", label=s)
        axes[1].semilogx([float(r["us_per_step"]) for r in rs],
                         [max(float(r["v2_error"]), 1e-16) for r in rs], "o", label=s)
    axes[0].set_xlabel("grid size d_g (cm)")
    axes[0].set_ylabel("|change of sum m v^2| / initial")
    axes[0].legend(fontsize=8)
    axes[1].set_yscale("log")
    axes[1].set_xlabel("wall time per step (us)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "contact_schemes.png"), dpi=110)
    plt.close(fig)
    return "contact_schemes.png"


def plot_debris(data, out):
    fig, ax = plt.subplots(figsize=(6, 3.5))
    found = False
    for s in SCHEMES:
        path = os.path.join(data, "debris_%s.csv" % s)
        if not os.path.exists(path):
            continue
        found = True
        rows = read_csv(path)
        ax.plot([float(r["time"]) for r in rows],
                [-float(r["block2_angle_deg"]) for r in rows], label=s)
    if not found:
        plt.close(fig)
        return None
    ax.set_xlabel("time (s)")
    ax.set_ylabel("block 2 rotation (deg, clockwise)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "debris_block2_angle.png"), dpi=110)
    plt.close(fig)
    return "debris_block2_angle.png"


def main():
    data, out, mode, machine = sys.argv[1:5]
    rows = read_csv(os.path.join(data, "results.csv"))
    by_case = OrderedDict()
    for r in rows:
        by_case.setdefault(r["case"], []).append(r)
    plots = {"collision": plot_collision(data, out),
             "contact_schemes": plot_contact_schemes(data, out),
             "debris": plot_debris(data, out)}
    lines = ["# Validation report", "",
             "Generated by `scripts/validate` (%s resolution) on %s. Every row: the quantity, our value,"
             " the reference and where it comes from, the error (relative to the reference; absolute"
             " when the reference is 0), the wall time of the run and its settings. Do not edit by"
             " hand: rerun `scripts/validate`." % (mode, machine), "",
             "## Cases", ""]
    for key, title, done in CASES:
        lines.append("- %s: %s" % (title, "below" if key in by_case else
                                   ("not in this run" if done else "not reproduced yet")))
    for key, title, _ in CASES:
        if key not in by_case:
            continue
        lines += ["", "## " + title, "", table(by_case[key])]
        if plots.get(key):
            lines += ["", "![%s](%s)" % (key, plots[key])]
    with open(os.path.join(out, "REPORT.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

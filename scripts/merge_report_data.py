#!/usr/bin/python3
"""Merges a run of some validation cases into the committed report's data.

usage: merge_report_data.py OLD_DATA NEW_DATA COMMIT DATE MACHINE

NEW_DATA holds what `mpm_sdem_validate --cases ...` measured now; OLD_DATA the committed report's
data (docs/validation/data). Writes into NEW_DATA: the old rows of every case this run did not
measure, ahead of the new rows in the old order of cases; every old series file the run did not
write again; and runs.csv, which case was measured by which commit, on which date and machine
(report.py prints it beside each case: the wall times are that machine's). A report merged this way is a set of runs, each stated; a case's
rows always come from one run.
"""
import csv
import os
import shutil
import sys


def read(path):
    if not os.path.exists(path):
        return [], []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        return list(reader), reader.fieldnames or []


def write(path, rows, fields):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


def main():
    old, new, commit, date, machine = sys.argv[1:6]
    new_rows, fields = read(os.path.join(new, "results.csv"))
    old_rows, old_fields = read(os.path.join(old, "results.csv"))
    fields = fields or old_fields
    measured = {r["case"] for r in new_rows}
    order = []
    for r in old_rows + new_rows:
        if r["case"] not in order:
            order.append(r["case"])
    kept = [r for r in old_rows if r["case"] not in measured]
    rows = sorted(kept + new_rows, key=lambda r: order.index(r["case"]))  # stable within a case
    write(os.path.join(new, "results.csv"), rows, fields)
    for name in os.listdir(old) if os.path.isdir(old) else []:
        source, target = os.path.join(old, name), os.path.join(new, name)
        if name not in ("results.csv", "runs.csv") and os.path.isfile(source) \
                and not os.path.exists(target):
            shutil.copy2(source, target)
    # A run's note (e.g. that the code a case runs has changed since) goes with the run.
    runs, _ = read(os.path.join(old, "runs.csv"))
    runs = [r for r in runs if r["case"] not in measured]
    runs += [{"case": c, "commit": commit, "date": date, "machine": machine, "note": ""}
             for c in order if c in measured]
    write(os.path.join(new, "runs.csv"), runs, ["case", "commit", "date", "machine", "note"])


if __name__ == "__main__":
    main()

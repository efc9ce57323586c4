"""Rows (dicts with the same keys) written as a CSV file atomically: a reader
never sees half a table (written beside it, then renamed over it)."""
import csv
import os


def write_rows_atomically(path, rows):
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, path)

"""Reading the speed-against-accuracy CSVs that the rock-fall and mud-flow sweeps write."""
import csv
import sys


def read_rows(path, numbers):
    """(rows that finished cleanly, with the `numbers` columns as floats; names of the others with their status)."""
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    kept, left_out = [], []
    for row in rows:
        if row["status"] != "ok":
            print(f"left out ({row['status']}): {row['configuration']}", file=sys.stderr)
            left_out.append(f"{row['configuration']} ({row['status'].replace('_', ' ')})")
            continue
        for key in numbers:
            row[key] = float(row[key])
        kept.append(row)
    return kept, left_out

#!/usr/bin/env python3
"""Reads a sweep's Parquet dataset directory with pyarrow.dataset and checks
that every value equals the CSV of the same spec.

    benches/parquet_check.py SWEEP.parquet SWEEP.csv

Numbers are compared bit for bit (the CSV's shortest round-trip text read by
Python's float(), which is correctly rounded); labels and booleans as text;
an empty CSV cell must be a null. Prints the checked counts; exits 1 on the
first difference.
"""
import csv
import struct
import sys

import pyarrow.dataset as ds


def bits(x):
    return struct.pack("<d", x)


def main(pq_path, csv_path):
    table = ds.dataset(pq_path, format="parquet").to_table().sort_by("id")
    with open(csv_path, newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    if table.column_names != header:
        sys.exit(f"columns differ: {table.column_names} vs {header}")
    if table.num_rows != len(rows):
        sys.exit(f"rows differ: {table.num_rows} vs {len(rows)}")
    meta = table.schema.metadata or {}
    if not meta.get(b"subdiv-lab.fingerprint", b"").startswith(b"# subdiv-lab sweep: digest "):
        sys.exit("no sweep fingerprint in the metadata")
    checked = 0
    for k, name in enumerate(header):
        col = table.column(name).to_pylist()
        for r, v in enumerate(col):
            cell = rows[r][k]
            if cell == "":
                ok = v is None
            elif isinstance(v, bool):
                ok = cell == ("true" if v else "false")
            elif isinstance(v, int):
                ok = int(cell) == v
            elif isinstance(v, float):
                ok = bits(float(cell)) == bits(v)
            else:
                ok = cell == v
            if not ok:
                sys.exit(f"row {r} column {name}: parquet {v!r}, csv {cell!r}")
            checked += 1
    print(f"pyarrow: {table.num_rows} rows, {checked} cells equal to the CSV")
    for lib in ("pandas", "polars"):
        try:
            mod = __import__(lib)
        except ImportError:
            print(f"{lib}: not installed, skipped")
            continue
        df = mod.read_parquet(pq_path)
        print(f"{lib}: read {len(df)} rows")


if __name__ == "__main__":
    main(*sys.argv[1:3])

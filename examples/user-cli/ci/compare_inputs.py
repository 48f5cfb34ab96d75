"""Compare the inputs of two `results.csv` at the times both hold.

    python3 compare_inputs.py A.csv B.csv TOLERANCE [--from T]

Fails (exit 1) unless max |u_A - u_B| <= TOLERANCE * max |u_A| over the
common times t >= T (default 0), and prints the measured ratio.
"""

import csv
import sys


def inputs(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    columns = [c for c in rows[0] if c.startswith("u")]
    # times to the microsecond: both runs step from t0 by their own dt
    return columns, {round(float(r["t"]) * 1e6): [float(r[c]) for c in columns] for r in rows}


def main():
    a_path, b_path, tolerance = sys.argv[1], sys.argv[2], float(sys.argv[3])
    start = float(sys.argv[5]) if len(sys.argv) > 5 and sys.argv[4] == "--from" else 0.0
    columns, a = inputs(a_path)
    columns_b, b = inputs(b_path)
    if columns != columns_b:
        sys.exit(f"different inputs: {columns} and {columns_b}")
    common = [t for t in a if t in b and t >= start * 1e6]
    if len(common) < 10:
        sys.exit(f"only {len(common)} common times")
    scale = max(abs(u) for t in common for u in a[t])
    worst = max(abs(x - y) for t in common for x, y in zip(a[t], b[t]))
    ratio = worst / scale
    print(f"{a_path} vs {b_path}: max |du| = {worst:.3e} over {len(common)} times, {ratio:.2e} of the peak |u|")
    if not ratio <= tolerance:
        sys.exit(f"above the tolerance {tolerance:.1e}")


if __name__ == "__main__":
    main()

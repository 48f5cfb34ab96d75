"""The observed order of the inputs of runs at halving steps.

    python3 orders.py ORDER REFERENCE.csv RUN1.csv RUN2.csv ...

Each run's error is max |u - u_ref| over the reference's times that the run
also holds, relative to the reference's peak |u|; the runs are given from
the longest step to the shortest, each half the one before. Fails (exit 1)
unless every halving's order log2(e_i / e_(i+1)) is within 0.25 of ORDER,
which also means that no error grows as the step shrinks.
"""

import math
import sys

from compare_inputs import inputs


def main():
    order, reference_path, runs = float(sys.argv[1]), sys.argv[2], sys.argv[3:]
    columns, reference = inputs(reference_path)
    scale = max(abs(u) for us in reference.values() for u in us)
    errors = []
    for path in runs:
        run_columns, run = inputs(path)
        if run_columns != columns:
            sys.exit(f"different inputs: {columns} and {run_columns}")
        common = [t for t in run if t in reference]
        if len(common) < 10:
            sys.exit(f"{path}: only {len(common)} times in common with the reference")
        errors.append(max(abs(x - y) for t in common for x, y in zip(run[t], reference[t])) / scale)
    for path, error in zip(runs, errors):
        print(f"{path}: max |du| = {error:.3e} of the peak |u|")
    observed = [math.log2(a / b) for a, b in zip(errors, errors[1:])]
    print("observed orders: " + ", ".join(f"{p:.3f}" for p in observed))
    if not all(abs(p - order) <= 0.25 for p in observed):
        sys.exit(f"an observed order is not within 0.25 of {order}")


if __name__ == "__main__":
    main()

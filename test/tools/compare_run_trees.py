#!/usr/bin/env python3
"""Compare the history.csv of every run two ctest build trees both wrote.

    python3 test/tools/compare_run_trees.py OLD/test/runs NEW/test/runs

For each run directory present in both: identical in every column but
wall_seconds, or the largest difference relative to the column's peak.
Used to show that a refactor gives the same results as before; runs of
the Monolithic strategy with MUMPS on two or more ranks are not bitwise
repeatable (MUMPS sums in message order), so compare those with a
tolerance, not bit for bit.
"""
import csv
import glob
import os
import sys


def main(old, new):
    identical, differ = 0, []
    for path in sorted(glob.glob(os.path.join(new, '*', 'history.csv'))):
        name = os.path.basename(os.path.dirname(path))
        ref = os.path.join(old, name, 'history.csv')
        if not os.path.exists(ref):
            continue
        a, b = list(csv.reader(open(ref))), list(csv.reader(open(path)))
        if a[0] != b[0] or len(a) != len(b):
            differ.append((float('inf'), name, 'header or row count'))
            continue
        worst, where = 0.0, ''
        for i, column in enumerate(a[0]):
            if column == 'wall_seconds':
                continue
            peak = max((abs(float(r[i])) for r in a[1:]), default=0.0) or 1.0
            for k in range(1, len(a)):
                d = abs(float(a[k][i]) - float(b[k][i])) / peak
                if d > worst:
                    worst, where = d, f'{column}, row {k}'
        if worst == 0.0:
            identical += 1
        else:
            differ.append((worst, name, where))
    for worst, name, where in sorted(differ, reverse=True):
        print(f'{worst:.2e}  {name}  ({where})')
    print(f'{identical} identical, {len(differ)} different')


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])

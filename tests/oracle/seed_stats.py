#!/usr/bin/env python3
"""Check `sylva compare --seeds N --csv` against N single-seed runs: every metric's mean and
(sample) standard deviation must be those of the single runs' values, to the 6 digits CSV
prints.   Usage: seed_stats.py ALL.csv ONE.csv...   prints "N metrics: mean and sd agree"
"""

import csv
import statistics
import sys


def table(path):
    return list(csv.reader(open(path, encoding="utf-8")))[1:]


def main():
    agg = {r[0]: (float(r[2]), float(r[3])) for r in table(sys.argv[1]) if r[2]}
    ones = [{r[0]: float(r[2]) for r in table(p) if r[2]} for p in sys.argv[2:]]
    bad = []
    for k, (mean, sd) in agg.items():
        v = [one[k] for one in ones]
        tol = 1e-5 * max(1.0, abs(mean))
        if abs(statistics.mean(v) - mean) > tol or abs(statistics.stdev(v) - sd) > tol:
            bad.append("%s: %g +- %g, but the seeds give %s" % (k, mean, sd, v))
    print("\n".join(bad) or "%d metrics: mean and sd agree" % len(agg))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

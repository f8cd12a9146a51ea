#!/usr/bin/env python3
"""Regenerate tests/golden/abop/ from examples/abop/*.syl with the reference deriver.

For every deterministic model (the first model of each file) this writes
  NAME.out   the derived string in canonical form, followed by one newline
  NAME.args  the command-line arguments that select the step count, e.g. "-n 4"
choosing the largest n <= the model's `derive` whose string stays under LIMIT characters.
It also writes module_counts.tsv (model, step, number of modules, for every step up to
`derive`) and prints the list of skipped (stochastic / unsupported) models.

Usage: make_goldens.py [--check]   (--check: compare instead of writing; exit 1 on a diff;
       it ends with "oracle: N passed, N failed", N counting golden files)
"""

import glob
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import ref_lsys  # noqa: E402

LIMIT = 20000
EXAMPLES = os.path.join(ROOT, "examples", "abop")
GOLDEN = os.path.join(ROOT, "tests", "golden", "abop")


def main():
    check = "--check" in sys.argv[1:]
    os.makedirs(GOLDEN, exist_ok=True)
    skipped, rows, bad, good = [], [], 0, 0
    for path in sorted(glob.glob(os.path.join(EXAMPLES, "*.syl"))):
        name = os.path.splitext(os.path.basename(path))[0]
        try:
            ls = ref_lsys.load(path)
        except ref_lsys.Unsupported as e:
            skipped.append((name, str(e)))
            continue
        s = ls.axiom
        counts = [len(s)]
        best_n, best_text = 0, ref_lsys.to_text(s)
        for k in range(1, ls.derive + 1):
            s = ls.step(s, k)
            counts.append(len(s))
            text = ref_lsys.to_text(s)
            if len(text) + 1 <= LIMIT:
                best_n, best_text = k, text
        for k, c in enumerate(counts):
            rows.append("%s\t%d\t%d\n" % (name, k, c))
        files = {name + ".out": best_text + "\n", name + ".args": "-n %d\n" % best_n}
        for fn, content in files.items():
            p = os.path.join(GOLDEN, fn)
            if check:
                old = open(p, encoding="utf-8").read() if os.path.exists(p) else None
                if old != content:
                    print("DIFF", fn)
                    bad += 1
                else:
                    good += 1
            else:
                with open(p, "w", encoding="utf-8") as f:
                    f.write(content)
        print("%-36s derive %3d  golden -n %3d  (%d modules, %d chars)  counts %s" % (
            name, ls.derive, best_n, counts[best_n], len(best_text),
            " ".join(str(c) for c in counts)))
    if not check:
        with open(os.path.join(GOLDEN, "module_counts.tsv"), "w", encoding="utf-8") as f:
            f.write("model\tstep\tmodules\n")
            f.writelines(rows)
    for name, why in skipped:
        print("skipped %s: %s (see tests/oracle/stochastic.py)" % (name, why))
    if check:
        print("oracle: %d passed, %d failed" % (good, bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Property check for the stochastic example examples/abop/fig1_27_stochastic.syl.

Sylva's random streams are its own, so no independent deriver can predict the string a seed
gives. What can be checked without them: every string Sylva derives in n steps must be one
the grammar can produce in exactly n steps (each F replaced by one of the three successors,
every other symbol kept), different seeds must give different plants, and the same seed the
same plant with 1 and 4 threads.

Usage: stochastic.py SYLVA    prints "stochastic: N passed, N failed"
"""

import functools
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
MODEL = os.path.join(ROOT, "examples", "abop", "fig1_27_stochastic.syl")
# Fig. 1.27's three successors of F (the only symbol with rules).
SUCCESSORS = ("F[+F]F[-F]F", "F[+F]F", "F[-F]F")
STEPS = 4
SEEDS = range(1, 9)


def derivable(text, n):
    """True when text is a derivation of the axiom F in exactly n parallel steps."""

    @functools.lru_cache(maxsize=None)
    def ends(pos, k):
        # every end position of a substring from pos that is F after k steps
        if k == 0:
            return frozenset([pos + 1]) if text.startswith("F", pos) else frozenset()
        out = set()
        for succ in SUCCESSORS:
            here = {pos}
            for sym in succ:
                nxt = set()
                for p in here:
                    if sym == "F":
                        nxt |= ends(p, k - 1)
                    elif text.startswith(sym, p):
                        nxt.add(p + 1)
                here = nxt
                if not here:
                    break
            out |= here
        return frozenset(out)

    sys.setrecursionlimit(10000)
    return len(text) in ends(0, n)


def derive(sylva, seed, threads):
    r = subprocess.run([sylva, "derive", MODEL, "-n", str(STEPS), "--seed", str(seed), "-j", str(threads)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("sylva derive --seed %d exited %d: %s" % (seed, r.returncode, r.stderr.strip()))
    return r.stdout.strip()


def main():
    sylva = sys.argv[1]
    passed = failed = 0

    def check(ok, what):
        nonlocal passed, failed
        if ok:
            passed += 1
        else:
            failed += 1
            print("FAIL stochastic: " + what)

    # the checker itself: it accepts a hand derivation and refuses near misses
    hand = "F[+F]F[-F]F".replace("F", "F[-F]F")  # step 1 rule 1, step 2 rule 3 everywhere
    check(derivable(hand, 2) and not derivable(hand, 1) and not derivable(hand + "F", 2)
          and not derivable(hand[:-1], 2), "the grammar checker itself")
    plants = set()
    for seed in SEEDS:
        s = derive(sylva, seed, 1)
        check(derivable(s, STEPS), "seed %d: %.60s... is not a %d-step derivation" % (seed, s, STEPS))
        check(derive(sylva, seed, 4) == s, "seed %d: 4 threads give another string" % seed)
        plants.add(s)
    # 8 seeds, 4 steps: the chance that a correct engine gives fewer than 4 plants is nil
    check(len(plants) >= 4, "only %d different plants from %d seeds" % (len(plants), len(SEEDS)))
    print("stochastic: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

"""bench/run's Python section (docs/python.md): what a call from Python costs beside the
command, each figure the best of RUNS runs, one thread, processor time where a process is
compared with a process.
    python3 bench/python.py SYLVA RUNS        (PYTHONPATH must find the sylva package)"""
import re
import subprocess
import sys
import time

import numpy as np

import sylva

SYLVA, RUNS = sys.argv[1], int(sys.argv[2])
LPY_MODULES_PER_S = 6e6  # the top of L-Py's 2-6 M modules/s measured on these machines (issue 31)
passes = misses = 0


def verdict(label, ok):
    global passes, misses
    passes += ok
    misses += not ok
    return f"{'PASS' if ok else 'MISS'} ({label})"


def cli_derive_cpu(path, n):
    best = None
    for _ in range(RUNS):
        err = subprocess.run([SYLVA, "derive", path, "-n", str(n), "-j", "1", "--stats"], capture_output=True,
                             text=True).stderr
        t = float(re.search(r"derive cpu time: ([0-9.e-]+)", err).group(1))
        best = t if best is None else min(best, t)
    return best


# 1. Deriving ABOP 1.24e (3.18 M modules) from Python against the command's own derive time.
path = "examples/abop/fig1_24e_plant.syl"
m = sylva.load(path).model
n = len(m.derive(12, threads=1))
# each run a fresh interpreter, as each of the command's is a fresh process: a second derivation
# in one process reuses pages the first one touched, which the command never gets
first = "import sylva; print(sylva.load(%r).model.derive(12, threads=1).cpu_seconds)" % path
py = min(float(subprocess.run([sys.executable, "-c", first], capture_output=True, text=True, check=True).stdout)
         for _ in range(RUNS))
c = cli_derive_cpu(path, 12)
ratio = py / c
print(f"  derive 1.24e n=12 ({n / 1e6:.2f} M modules): Python {py * 1e3:.1f} ms, command {c * 1e3:.1f} ms, "
      f"{ratio:.3f}x  {verdict('<= 1.05x', ratio <= 1.05)}")
rate = n / py  # modules per CPU second
print(f"  from Python: {rate / 1e6:.0f} M modules/s = {rate / LPY_MODULES_PER_S:.0f}x L-Py's best 6 M/s  "
      f"{verdict('>= 50x', rate >= 50 * LPY_MODULES_PER_S)}")

# 2. The parameters of every F of a parametric plant into one numpy array.
s = sylva.load("examples/abop/fig2_06_monopodial.syl").model.derive(17, threads=1)
best = None
for _ in range(max(RUNS, 5)):
    t0 = time.perf_counter()
    f = s.params("F")
    t = time.perf_counter() - t0
    best = t if best is None else min(best, t)
ns = best / len(s) * 1e9
print(f"  params('F') of Fig. 2.6 n=17 ({len(s) / 1e6:.2f} M modules, {len(f)} Fs): {best * 1e3:.2f} ms, "
      f"{ns:.2f} ns a module  {verdict('<= 10 ns', ns <= 10)}")

# 3. A Python environment: what answering one ?E query costs, the derivation's own time off.
probe = """lsystem Probes {
  derive 8
  angle 30
  axiom A
  A -> F(0.2) [ &(120) A ?E(2, 0) ] /(90) [ &(100) A ?E(2, 0) ] /(90) A
}
"""
pm = sylva.compile(probe)["Probes"]
q = {"n": 0}


def ground(step, qs):
    if not len(qs):
        return
    asked = qs.params[:, 0] == 2
    hy = qs.headings[:, 1].astype(np.float64)
    down = hy < 0
    qs.params[asked, 1] = np.where(down, qs.positions[:, 1] / np.where(down, -hy, 1), 1e9)[asked]
    q["n"] += len(qs)


plain = min(pm.derive(threads=1, environment=lambda step, qs: None).seconds for _ in range(RUNS))
q["n"] = 0
with_env = min(pm.derive(threads=1, environment=ground).seconds for _ in range(RUNS))
queries = q["n"] // RUNS
per = max(with_env - plain, 0) / max(queries, 1) * 1e6
print(f"  Python environment: {queries} ?E queries a derivation; {per:.3f} us a query answered in numpy "
      f"(beyond the call per step)  {verdict('<= 1 us', per <= 1)}")

# A Python function called from a rule (`extern`): the derivation with it bound, against the same
# derivation running the extern's default body (the same arithmetic in the VM), per call.
calls = sylva.compile("""lsystem Calls {
  extern f(x) = 2 * x + 1
  derive 16
  axiom A(0)
  A(x) -> A(f(x)) A(x)
}
""").model
vm = min(calls.derive(threads=1).cpu_seconds for _ in range(RUNS))
bound = min(calls.derive(threads=1, functions={"f": lambda x: 2 * x + 1}).cpu_seconds for _ in range(RUNS))
ncalls = 2 ** 16 - 1  # one a module A, 2^k of them at step k
print(f"  Python extern function: {ncalls} calls a derivation; {max(bound - vm, 0) / ncalls * 1e6:.3f} us a call "
      f"(lambda x: 2 * x + 1, against the default body in the VM)")
print(f"python targets: {passes} PASS, {misses} MISS")

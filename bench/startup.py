#!/usr/bin/env python3
"""bench/startup.py RUNS CMD...: the processor time (user + system, of the child alone, from
wait4's rusage) of running CMD, best of RUNS, in ms. Prints the figure; exit 1 if CMD fails."""
import os
import sys


def main():
    runs, cmd = int(sys.argv[1]), sys.argv[2:]
    best = None
    for _ in range(runs):
        # posix_spawn (vfork underneath): a fork of Python would charge the child for copying it
        pid = os.posix_spawnp(cmd[0], cmd, os.environ,
                              file_actions=[(os.POSIX_SPAWN_OPEN, 1, os.devnull, os.O_WRONLY, 0)])
        _, status, ru = os.wait4(pid, 0)
        if os.waitstatus_to_exitcode(status) != 0:
            sys.stderr.write("%s: exit %d\n" % (" ".join(cmd), os.waitstatus_to_exitcode(status)))
            sys.exit(1)
        ms = (ru.ru_utime + ru.ru_stime) * 1000
        best = ms if best is None else min(best, ms)
    print("%.2f" % best)


main()

#!/usr/bin/env python3
"""Write hills.dmr, the terrain of zamuda.syl, in Zamuda's DMR text (Zamuda 2006, §4.1): every
vertex as x, z and its height y, one value a line, 25 m apart. 48 x 48 vertices (1.2 km a
side, heights about 330..700 m): a valley running north-south with a stream at its floor, the
slope west of it rising to a rounded hill, a lower ridge east of it, and waves across the
valley so that slopes face north and south as well as east and west.
    python3 examples/ecosystem/make_dmr.py > examples/ecosystem/hills.dmr"""
import math

N, K = 48, 25.0
for k in range(N):
    for i in range(N):
        x, z = i * K, k * K
        u = (x - 700.0) / 600.0
        h = 340 + 220 * u * u                                                   # the valley
        h += 160 * math.exp(-((x - 250) ** 2 + (z - 750) ** 2) / (2 * 200.0 ** 2))  # the hill
        h += 35 * math.sin(z / 180.0) * (1 - math.exp(-((x - 700) / 250.0) ** 2 * 4))  # waves
        print(f"{x:g}\n{z:g}\n{h:.2f}")

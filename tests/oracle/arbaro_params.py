#!/usr/bin/env python3
"""Independent reader for tests/cases/arbaro.test and convert.test: Python's xml.etree reads
Arbaro species files, and the checks compare what Sylva read or wrote against it.

  arbaro_params.py read SYLVA FILE.xml...     every <param> of each file is a directive line of
                                              `sylva compile --dump`, same name, same value, in order
  arbaro_params.py written ORIGINAL CONVERTED each file's params have the same values in the
                                              converted file (which holds every parameter)
"""
import subprocess
import sys
import xml.etree.ElementTree as ET


def params(path):
    root = ET.parse(path).getroot()
    (sp,) = root.findall("species")
    return sp.get("name"), [(p.get("name"), p.get("value")) for p in sp.findall("param")]


def same(a, b):
    try:
        return float(a) == float(b)
    except ValueError:
        return a == b


def read(sylva, files):
    total = 0
    for f in files:
        name, want = params(f)
        out = subprocess.run([sylva, "compile", "--dump", f], capture_output=True, text=True, check=True).stdout
        lines = out.splitlines()
        assert lines[0] == "weber " + name, (f, lines[0])
        got = [l.split(None, 1) for l in lines[2:]]
        assert got[0] == ["convention", "arbaro"], (f, got[0])
        got = got[1:]
        assert len(got) == len(want), (f, len(got), len(want))
        for (gn, gv), (wn, wv) in zip(got, want):
            assert gn == wn and same(gv, wv), (f, gn, gv, wn, wv)
        total += len(want)
    print(f"{len(files)} files, {total} params: each read with its name and value")


def written(pairs):
    for orig, conv in pairs:
        _, want = params(orig)
        _, got = params(conv)
        got = dict(got)
        assert len(got) == 28 + 4 * 16, (conv, len(got))
        for n, v in want:
            assert n in got and same(got[n], v), (conv, n, v, got.get(n))
    print(f"{len(pairs)} files: every param kept, every parameter written")


if __name__ == "__main__":
    if sys.argv[1] == "read":
        read(sys.argv[2], sys.argv[3:])
    else:
        a = sys.argv[2:]
        written(list(zip(a[0::2], a[1::2])))

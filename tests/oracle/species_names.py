#!/usr/bin/env python3
"""Species names as the language allows them (a string holds any byte but a quote and a line
end), for the plant table's round trip (tests/cases/trust.test):
  species_names.py model TERRAIN   an ecosystem block with one species per name, on stdout
  species_names.py check CSV       read CSV with Python's csv module (RFC 4180) and say whether
                                   its species column holds exactly those names"""
import csv
import sys

CHARS = [chr(c) for c in range(1, 128) if chr(c) not in '"\n']
NAMES = [''.join(CHARS[i:i + 40]) for i in range(0, len(CHARS), 40)] + ['a,b', ',', 'x,,y', 'é, ü', 'plain']

if sys.argv[1] == 'model':
    out = ['ecosystem Names {', '  terrain "%s"' % sys.argv[2], '  years 2', '  seed 1', '  snapshots 2']
    for n in NAMES:
        out += ['  species "%s"' % n, '    height_max 1', '    arrivals 40']
    sys.stdout.write('\n'.join(out + ['}']) + '\n')
else:
    with open(sys.argv[2], newline='', encoding='utf-8') as f:
        rows = list(csv.reader(f))
    ok = rows[0][1] == 'species' and all(len(r) == len(rows[0]) for r in rows)
    got = {r[1] for r in rows[1:]}
    print('%d names of %d read back' % (len(got & set(NAMES)), len(NAMES)) + ('' if ok and got == set(NAMES) else ', and others'))

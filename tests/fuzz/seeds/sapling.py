# a Sapling preset written for the fuzzer's seeds (Sylva's own numbers)
{'levels': 3, 'scale': 9.0, 'scaleV': 2.0, 'branches': (0, 30, 12, 4), 'length': (1.0, 0.4, 0.5, 0.4), 'downAngle': (90.0, 60.0, 45.0, 45.0), 'curve': (0.0, -30.0, -20.0, 0.0), 'attractUp': (0.0, 0.0, 0.4, 0.4), 'prune': True, 'pruneRatio': 0.5, 'shape': '7', 'leafShape': 'hex', 'leaves': 12, 'bevel': True}

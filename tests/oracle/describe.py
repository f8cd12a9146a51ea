#!/usr/bin/env python3
"""Read `sylva describe --json` output (docs/cli.md#sylva-describe) for tests/cases/schema.test.

  describe.py shape FILE.json          check every parameter's fields and types; print the models
  describe.py get FILE.json M.P.FIELD  print one field of parameter P of model M (P may hold dots)
  describe.py bounds FILE.json MODEL   print "MODEL.NAME VALUE EXIT" (a scene's: NAME) for MODEL's numbers: one past each
                                       finite bound (exit 2 expected), and the default (exit 0)
"""
import json
import sys

KEYS = ["name", "type", "min", "max", "default", "value", "unit", "doc", "values", "aliases"]
TYPES = {"number", "integer", "boolean", "enum", "list", "curve", "file", "string", "vector"}


def main(argv):
    what, path = argv[1], argv[2]
    d = json.load(open(path))
    models = {m["name"]: m for m in d["models"]}
    if what == "shape":
        for m in d["models"]:
            for q in m["params"]:
                missing = [k for k in KEYS if k not in q]
                if missing or q["type"] not in TYPES:
                    print("bad parameter", m["name"], q)
                    return 1
                if (q["values"] is not None) != (q["type"] == "enum"):
                    print("values without an enum, or an enum without values:", m["name"], q["name"])
                    return 1
        print(d["file"], " ".join("%s:%s:%d" % (m["name"], m["kind"], m["line"]) for m in d["models"]))
    elif what == "get":
        for spec in argv[3:]:
            model, rest = spec.split(".", 1)
            name, field = rest.rsplit(".", 1)
            q = next(q for q in models[model]["params"] if q["name"] == name)
            print(json.dumps(q[field]))
    elif what == "bounds":
        for q in models[argv[3]]["params"]:
            if q["type"] not in ("number", "integer"):
                continue
            # a scene's are named as --set takes them already (scene.plant.1.x)
            name = q["name"] if q["name"].startswith(argv[3] + ".") else argv[3] + "." + q["name"]
            if q["max"] is not None and q["max"] < 2 ** 52:  # beyond, + 1 is not a double apart
                print(name, q["max"] + 1, 2)
            if q["min"] is not None:
                print(name, q["min"] - 1, 2)
            if q["default"] is not None:
                print(name, q["default"], 0)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

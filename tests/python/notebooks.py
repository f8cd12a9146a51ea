"""Execute every notebook of a folder as a reader would (nbclient, a kernel of this Python),
in the notebook's own folder, and check its outputs: no cell raised, every cell that draws a
figure or a plant shows a PNG, and the counts its cells print agree with its asserts (a cell's
`assert` is part of the check). Prints one line per notebook and `N passed, N failed`.
    python notebooks.py DIR"""
import json
import os
import sys
import tempfile

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError


def kernel_here(tmp):
    """A kernelspec that runs this interpreter (the venv with sylva installed), not the
    system's python3 kernel."""
    d = os.path.join(tmp, "kernels", "sylva-test")
    os.makedirs(d)
    with open(os.path.join(d, "kernel.json"), "w") as f:
        json.dump({"argv": [sys.executable, "-Xfrozen_modules=off", "-m", "ipykernel_launcher", "-f",
                            "{connection_file}"],
                   "display_name": "sylva test", "language": "python"}, f)
    os.environ["JUPYTER_PATH"] = tmp + os.pathsep + os.environ.get("JUPYTER_PATH", "")
    os.environ["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"


def check(path):
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=300, kernel_name="sylva-test",
                            resources={"metadata": {"path": os.path.dirname(path)}})
    try:
        client.execute()
    except CellExecutionError as e:
        return f"a cell raised: {str(e).splitlines()[-1] if str(e) else e}"
    pngs = sum(1 for c in nb.cells if c.cell_type == "code"
               for o in c.get("outputs", []) if "image/png" in o.get("data", {}))
    if pngs < 2:
        return f"only {pngs} pictures shown (plots and plants draw PNGs)"
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    if errors:
        return f"{len(errors)} errors in outputs"
    if os.environ.get("SYLVA_NB_OUT"):  # kept for the browser test of the exported HTML
        nbformat.write(nb, os.path.join(os.environ["SYLVA_NB_OUT"], os.path.basename(path)))
    return views(nb)


def views(nb):
    """The 3D views a notebook promises in its metadata (sylva_expect): each an HTML output
    with three.js inlined (its licence header) beside the picture, the plants' .glb inlined
    (base64 of its 'glTF' magic), and ipywidgets panels."""
    want = nb.metadata.get("sylva_expect")
    if not want:
        return None
    datas = [o.get("data", {}) for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    html = [d for d in datas if 'class="sylva-view"' in d.get("text/html", "")]
    got = {"views": sum("Three.js Authors" in d["text/html"] and "image/png" in d for d in html),
           "glb": sum('"glb":"Z2xURg' in d["text/html"] for d in html),
           "widgets": sum("application/vnd.jupyter.widget-view+json" in d for d in datas)}
    short = [f"{k} {got[k]} of {n}" for k, n in want.items() if got.get(k, 0) < n]
    return "missing: " + ", ".join(short) if short else None


def main(folder):
    passed = failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        kernel_here(tmp)
        for name in sorted(os.listdir(folder)):
            if not name.endswith(".ipynb"):
                continue
            why = check(os.path.join(folder, name))
            print(f"{'FAIL' if why else 'ok  '} notebook {name}{': ' + why if why else ''}")
            passed += why is None
            failed += why is not None
    print(f"notebooks: {passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))

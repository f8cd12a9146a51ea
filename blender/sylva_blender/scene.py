"""The scene drives the model: for a `curvetree` block the active curve is the trunk and a
selected mesh the crown envelope; for a `grow` block the selected meshes are obstacles; for an
`ecosystem` block the selected mesh is the terrain (forest.py makes the plants). Each
is given to Sylva in world coordinates (Blender's z-up turned to Sylva's y-up) by rewriting
the block's `trunk`/`envelope` lines, or by planting the grown tree in a `scene` block with
`obstacle` lines, and compiling the changed text under the model file's own name.

The meshes are written as OBJ files into a hidden folder beside the model file
(`.sylva-blender/`, removed after the build): a model may read files in its own folder and
below only (docs/cli.md, `--allow-path`), and the model's other files (`bark`, textures)
stay where it names them."""
from __future__ import annotations

import os
import re
import shutil
import tempfile

import bpy
from mathutils import Vector
from mathutils.geometry import interpolate_bezier


def to_sylva(v) -> tuple[float, float, float]:
    """Blender's world (z up) to Sylva's (y up): the inverse of the mesh's (x, -z, y)."""
    return (v[0], v[2], -v[1])


def curve_points(obj) -> list[Vector]:
    """The first spline of a curve object in world coordinates, as Blender draws it: a Bézier
    spline evaluated at its resolution, a poly or NURBS spline's points."""
    sp = obj.data.splines[0]
    mw = obj.matrix_world
    if sp.type == "BEZIER":
        bp = list(sp.bezier_points)
        pairs = list(zip(bp, bp[1:] + ([bp[0]] if sp.use_cyclic_u else [])))
        res = max(sp.resolution_u, 1) + 1
        pts = []
        for a, b in pairs:
            seg = interpolate_bezier(a.co, a.handle_right, b.handle_left, b.co, res)
            pts.extend(seg if not pts else seg[1:])
    else:
        pts = [p.co.xyz for p in sp.points]
    return [mw @ p for p in pts]


def write_obj(obj, path: str) -> None:
    """A mesh object's triangles (modifiers applied) in world coordinates, as an OBJ of v and f."""
    dg = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(dg)
    me = ev.to_mesh()
    try:
        mw = obj.matrix_world
        with open(path, "w") as f:
            for v in me.vertices:
                f.write("v %.6f %.6f %.6f\n" % to_sylva(mw @ v.co))
            for p in me.polygons:
                f.write("f " + " ".join(str(i + 1) for i in p.vertices) + "\n")
    finally:
        ev.to_mesh_clear()


def inputs(context) -> tuple:
    """(the active curve or None, the selected meshes other than the active curve)."""
    act = context.active_object
    curve = act if act is not None and act.type == "CURVE" and act.data.splines else None
    meshes = [o for o in context.selected_objects if o.type == "MESH"]
    return curve, meshes


def _block(lines: list[str], kind: str, name: str) -> tuple[int, int]:
    """The first and last line (indices) of `kind name { … }`, its closing brace alone on a line."""
    head = re.compile(rf"^\s*{kind}\s+{re.escape(name)}\s*\{{")
    for i, line in enumerate(lines):
        if head.match(line):
            for j in range(i + 1, len(lines)):
                if lines[j].strip() == "}":
                    return i, j
    raise ValueError(f"the {kind} block {name} is not written as `{kind} {name} {{` … `}}`: "
                     "the scene cannot give it its inputs")


def _set_line(lines: list[str], first: int, last: int, word: str, text: str) -> None:
    for k in range(first + 1, last):
        if re.match(rf"^\s*{word}\b", lines[k]):
            lines[k] = text
            return
    lines.insert(first + 1, text)


class Inputs:
    """The scene's inputs for one build, written beside the model file; a context manager that
    removes them."""

    def __init__(self, path: str):
        self.model_dir = os.path.dirname(os.path.abspath(path))
        self.dir = None

    def file(self, name: str) -> str:
        if self.dir is None:
            base = os.path.join(self.model_dir, ".sylva-blender")
            os.makedirs(base, exist_ok=True)
            self.dir = tempfile.mkdtemp(dir=base)
        return os.path.join(self.dir, name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.dir:
            shutil.rmtree(self.dir, ignore_errors=True)
            try:
                os.rmdir(os.path.dirname(self.dir))
            except OSError:  # another build's inputs are still there
                pass


def rewrite(context, path: str, m, io: Inputs) -> tuple[str | None, str, bool]:
    """The model's source changed so that the scene's objects are its inputs, what they are
    ("trunk from Curve, envelope from Sphere") and whether the text now has a scene block that
    plants the model; (None, "", False) when the scene gives nothing. Which objects a kind takes
    is asked of the library's table of kinds (m.caps.takes_*), each written as the directive
    the capability names, so a new kind needs no change here."""
    curve, meshes = inputs(context)
    caps = m.caps
    trunk, envelope = caps.takes_trunk and curve, caps.takes_envelope and meshes
    if trunk or envelope:
        lines = open(path, encoding="utf-8").read().split("\n")
        first, last = _block(lines, m.kind, m.name)
        said = []
        if trunk:
            pts = " ".join("(%.6f,%.6f,%.6f)" % to_sylva(p) for p in curve_points(curve))
            _set_line(lines, first, last, "trunk", f"  trunk polyline {pts}")
            said.append(f"trunk from {curve.name}")
        if envelope:
            env = io.file("envelope.obj")
            write_obj(meshes[0], env)
            _set_line(lines, first, last, "envelope", f'  envelope "{os.path.relpath(env, io.model_dir)}"')
            said.append(f"envelope from {meshes[0].name}")
        return "\n".join(lines), ", ".join(said), False
    if caps.takes_terrain and meshes:
        lines = open(path, encoding="utf-8").read().split("\n")
        first, last = _block(lines, m.kind, m.name)
        ter = io.file("terrain.obj")
        write_obj(meshes[0], ter)
        _set_line(lines, first, last, "terrain", f'  terrain "{os.path.relpath(ter, io.model_dir)}"')
        return "\n".join(lines), f"terrain from {meshes[0].name}", False
    if caps.takes_obstacles and meshes:
        text = open(path, encoding="utf-8").read()
        obst = []
        for k, o in enumerate(meshes):
            f = io.file(f"obstacle{k}.obj")
            write_obj(o, f)
            obst.append(f'  obstacle "{os.path.relpath(f, io.model_dir)}"')
        scene = "\n".join(["", "scene {", *obst, f"  plant {m.name} at (0, 0, 0)", "}", ""])
        return text + scene, "obstacles " + ", ".join(o.name for o in meshes), True
    return None, "", False

"""The real-time options of build() (lod=, impostor=, billboards=, wind=) against `sylva mesh
--lod/--impostor/--wind`: its --stats counts and the arrays of the .glb it writes, read here
(docs/python.md). SYLVA names the command (default: build/sylva of the checkout)."""
import json
import os
import struct
import subprocess

import numpy as np
import pytest

import sylva

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("SYLVA", os.path.join(ROOT, "build", "sylva"))
MODEL = os.path.join(ROOT, "examples", "abop", "fig2_06_monopodial.syl")


def stats(*args, out):
    r = subprocess.run([CLI, "mesh", MODEL, *args, "--stats", "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return {k.strip(): v.strip() for k, _, v in (line.partition(":") for line in r.stderr.splitlines())}


def glb(path):
    """(json, bin chunk) of a .glb, and an accessor reader: the file as any glTF reader sees it."""
    data = open(path, "rb").read()
    n = struct.unpack_from("<I", data, 12)[0]
    js = json.loads(data[20:20 + n])
    binary = data[20 + n + 8:]
    fmt = {5126: "f", 5125: "I", 5123: "H", 5121: "B"}
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}

    def accessor(i):
        a = js["accessors"][i]
        v = js["bufferViews"][a["bufferView"]]
        k, dt = width[a["type"]], np.dtype("<" + fmt[a["componentType"]])
        stride = v.get("byteStride", k * dt.itemsize)
        off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
        rows = np.ndarray((a["count"], k), dt, binary, off, (stride, dt.itemsize))
        return rows.copy()
    return js, accessor


@pytest.fixture(scope="module")
def model():
    return sylva.load(MODEL).model


def test_levels_and_billboards_are_the_commands(model, tmp_path):
    st = stats("--lod", "3", "--impostor", "--impostor-view", "64", out=tmp_path / "lod.glb")
    plant = model.build(lod=3, impostor=True, impostor_view=64)
    levels = plant.levels
    assert [lv.level for lv in levels] == [0, 1, 2, 3]
    assert levels[0].triangles == int(st["triangles"]) == len(plant.mesh.triangles)
    for lv in levels[1:]:  # "LOD1: 4472 triangles (44.99%), ..." and "LOD3: 12 triangles, 3 crossed billboards"
        assert lv.triangles == int(st[f"LOD{lv.level}"].split()[0])
    assert [lv.billboards for lv in levels] == [False, False, False, True]
    assert "3 crossed billboards" in st["LOD3"]
    # each level cheaper than the last, its coverage where the next takes over
    assert all(a.triangles > b.triangles for a, b in zip(levels, levels[1:]))
    assert all(a.coverage > b.coverage for a, b in zip(levels, levels[1:]))
    imp = plant.impostor
    assert (imp.grid, imp.view, imp.size) == (8, 64, 8 * 64)
    assert imp.color.shape == imp.normal.shape == (512, 512, 4)
    assert imp.billboard_atlas.shape == (64, 2 * 3 * 64, 4)
    assert 0 < (imp.color[..., 3] > 0).mean() < 1  # the plant covers part of each view, not all
    assert model.mesh(lod=3, impostor=True, impostor_view=64).levels[3].triangles == levels[3].triangles


def test_billboards_alone_have_no_octahedral_atlas(model):
    plant = model.build(billboards=2, impostor_view=32)
    assert len(plant.levels) == 2 and plant.levels[1].billboards
    assert plant.impostor.color is None and plant.impostor.billboard_atlas.shape == (32, 128, 4)


def test_wind_is_the_commands_skin_and_animation(model, tmp_path):
    st = stats("--wind", "6", "--wind-seconds", "2", out=tmp_path / "wind.glb")
    w = model.mesh(wind=6, wind_seconds=2).wind
    assert len(w) == int(st["wind joints"]) and w.nkeys == int(st["wind keys"])
    js, acc = glb(tmp_path / "wind.glb")
    prim = js["meshes"][0]["primitives"][0]
    np.testing.assert_array_equal(acc(prim["attributes"]["JOINTS_0"])[:, :2], w.skin_joints)
    np.testing.assert_array_equal(acc(prim["attributes"]["WEIGHTS_0"])[:, :2], w.skin_weights)
    assert (w.skin_weights.astype(int).sum(1) == 255).all()
    skin = js["skins"][0]
    # every joint node at its stem's base (translations from the parent joint), parents first
    heads = np.zeros((len(w), 3))
    for j, node in enumerate(skin["joints"]):
        parent = w.joints["parent"][j]
        heads[j] = np.array(js["nodes"][node].get("translation", [0, 0, 0])) + (heads[parent] if parent >= 0 else 0)
    np.testing.assert_allclose(heads, w.heads, atol=1e-5)
    anim = js["animations"][0]
    for ch in anim["channels"]:
        j = skin["joints"].index(ch["target"]["node"])
        s = anim["samplers"][ch["sampler"]]
        np.testing.assert_allclose(acc(s["input"])[:, 0], w.times, rtol=1e-6)
        np.testing.assert_array_equal(acc(s["output"]), w.rotations[j])
    np.testing.assert_allclose(np.linalg.norm(w.rotations, axis=2), 1, atol=1e-5)
    np.testing.assert_array_equal(w.rotations[:, 0], w.rotations[:, -1])  # it loops


def test_every_level_is_skinned_but_the_billboards(model, tmp_path):
    stats("--lod", "3", "--billboards", "2", "--wind", "6", out=tmp_path / "wl.glb")
    js, acc = glb(tmp_path / "wl.glb")
    levels = model.build(lod=3, billboards=2, wind=6).levels
    nodes = {n["name"]: n for n in js["nodes"] if "mesh" in n}
    for lv in levels:
        skin = lv.skin()
        node = nodes[f"{model.name}_LOD{lv.level}"]
        assert (skin is None) == lv.billboards == ("skin" not in node)
        if skin is not None:
            prim = js["meshes"][node["mesh"]]["primitives"][0]
            np.testing.assert_array_equal(acc(prim["attributes"]["JOINTS_0"])[:, :2], skin[0])
            np.testing.assert_array_equal(acc(prim["attributes"]["WEIGHTS_0"])[:, :2], skin[1])


def test_save_writes_the_commands_file(model, tmp_path):
    # levels skinned to one set of joints: the same bytes as the command's
    subprocess.run([CLI, "mesh", MODEL, "--lod", "2", "--wind", "6", "--wind-dir", "0,1", "-o",
                    str(tmp_path / "cli.glb")], check=True)
    model.build(lod=2, wind=6, wind_dir=(0, 1)).save(tmp_path / "py.glb")
    assert (tmp_path / "py.glb").read_bytes() == (tmp_path / "cli.glb").read_bytes()


@pytest.mark.parametrize("kw,err", [({"lod": 9}, ValueError), ({"billboards": 5}, ValueError),
                                    ({"wind": -1}, ValueError), ({"wind": "6"}, TypeError),
                                    ({"lod": 2, "until": "skeleton"}, ValueError)])
def test_bad_realtime_options_are_refused(model, kw, err):
    with pytest.raises(err):
        model.build(**kw)


def test_without_options_there_is_nothing_realtime(model):
    plant = model.build()
    assert plant.levels == [] and plant.wind is None and plant.impostor is None


def test_leaf_sets_are_the_commands_instances(tmp_path):
    # as many instances as the command places, and each prototype the copied leaf: the leaves'
    # triangles of the copied mesh are the prototypes' times their instances
    oak = os.path.join(ROOT, "examples", "curvetree", "bezier_oak.syl")

    def st(leaves):
        r = subprocess.run([CLI, "mesh", oak, "--leaves", leaves, "--stats", "-o", str(tmp_path / f"{leaves}.glb")],
                           capture_output=True, text=True, check=True)
        return {k.strip(): v.strip() for k, _, v in (line.partition(":") for line in r.stderr.splitlines())}
    inst, copied = st("instanced"), st("mesh")
    plant = sylva.load(oak).model.build(leaves="instanced")
    sets = plant.leaf_sets()
    assert sum(len(s) for s in sets) == int(inst["leaf instances"])
    assert sum(len(s) * len(s.proto.triangles) for s in sets) == int(copied["triangles"]) - int(inst["triangles"])
    for s in sets:
        np.testing.assert_allclose(np.linalg.norm(s.rotations, axis=1), 1, atol=1e-5)
        assert s.proto.vertices[:, 2].ptp() == 0 and s.proto.vertices[:, 0].min() >= 0  # flat, from its base
    org = plant.skeleton.organs  # each leaf's size is its instance's scale, in every axis
    sizes = np.sort(org["size"][org["kind"] == sylva.ORGAN_KINDS.index("leaf")])
    scales = np.sort(np.concatenate([s.scales for s in sets]), axis=0)
    np.testing.assert_array_equal(scales, np.repeat(sizes[:, None], 3, 1))


def test_level_leaf_sets_are_the_glbs(tmp_path):
    # every level's leaves as the .glb of `--lod 2 --leaves instanced --wind` has them: per
    # LODk node, per joint (the writer splits a set by the joint its leaves follow, _stemN),
    # at the translations the file stores relative to the joint's stem base
    bush = os.path.join(ROOT, "examples", "hybrid", "shade_bush.syl")
    out = tmp_path / "lv.glb"
    subprocess.run([CLI, "mesh", bush, "--lod", "2", "--leaves", "instanced", "--wind", "6", "--wind-seconds", "2",
                    "-o", str(out)], check=True, capture_output=True)
    js, accessor = glb(out)
    nodes = js["nodes"]
    want = {}

    def walk(i, level):
        ext = nodes[i].get("extensions", {}).get("EXT_mesh_gpu_instancing")
        if ext:
            stem = int(nodes[i]["name"].rsplit("_stem", 1)[1])
            want[level, stem] = want.get((level, stem), 0) + len(accessor(ext["attributes"]["TRANSLATION"]))
        for c in nodes[i].get("children", []):
            walk(c, level)
    for i, n in enumerate(nodes):
        if n.get("name", "").rsplit("_LOD", 1)[-1].isdigit():
            walk(i, int(n["name"].rsplit("_LOD", 1)[1]))
    plant = sylva.load(bush).model.build(leaves="instanced", lod=2, wind=6, wind_seconds=2)
    stem_of = plant.wind.joints["stem"]
    got = {}
    for lv in plant.levels:
        for s in lv.leaf_sets():
            assert s.joints is not None and len(s.joints) == len(s) and s.nodes is not None
            for j, c in zip(*np.unique(s.joints, return_counts=True)):
                got[lv.level, int(stem_of[j])] = got.get((lv.level, int(stem_of[j])), 0) + int(c)
    assert {k for k, _ in got} == {0, 1, 2} and got == want
    # without wind: no joints, and a level's leaves have no nodes
    plain = sylva.load(bush).model.build(leaves="instanced", lod=2)
    assert [sum(len(s) for s in lv.leaf_sets()) for lv in plain.levels] == \
        [sum(c for (k, _), c in want.items() if k == lv) for lv in range(3)]
    assert all(s.joints is None for lv in plain.levels for s in lv.leaf_sets())


def test_mesh_edges_are_the_sides_once():
    # the add-on's edges (sylva._core.mesh_edges): every triangle side once, as numpy's unique
    # finds them, and loop 3t + i's edge joins corners i and i + 1 of triangle t
    from sylva import _core
    mesh = sylva.load(os.path.join(ROOT, "examples", "abop", "fig1_25_bush3d.syl")).model.mesh()
    tris = mesh.triangles
    edges, loop_edge = (np.asarray(a) for a in _core.mesh_edges(tris, len(mesh.vertices)))
    a, b = tris.ravel().astype(np.int64), tris[:, [1, 2, 0]].ravel().astype(np.int64)
    pairs = np.stack([np.minimum(a, b), np.maximum(a, b)], axis=1)
    assert len(edges) == len(np.unique(pairs, axis=0)) and (edges[:, 0] < edges[:, 1]).all()
    np.testing.assert_array_equal(edges[loop_edge], pairs)
    with pytest.raises(ValueError):
        _core.mesh_edges(tris, int(tris.max()))


def test_instance_quads_centre_side_and_heading():
    # the add-on's leaf faces (sylva._core.instance_quads): each square centred on its leaf,
    # its side the leaf's size, its first edge along the leaf's R x and its normal along R z
    from sylva import _core
    s = sylva.load(os.path.join(ROOT, "examples", "curvetree", "bezier_oak.syl")).model.build(
        leaves="instanced", until="skeleton").leaf_sets()[0]
    q = np.asarray(_core.instance_quads(s.translations, s.rotations, s.scales)).reshape(-1, 4, 3).astype(np.float64)
    np.testing.assert_allclose(q.mean(axis=1), s.translations, atol=1e-5)
    edge = q[:, 1] - q[:, 0]
    np.testing.assert_allclose(np.linalg.norm(edge, axis=1), s.scales[:, 0], rtol=1e-4)
    x, y, z, w = s.rotations.T.astype(np.float64)
    rx = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], axis=1)
    rz = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], axis=1)
    assert (np.einsum("ij,ij->i", edge / np.linalg.norm(edge, axis=1)[:, None], rx) > 0.9999).all()
    normal = np.cross(edge, q[:, 2] - q[:, 1])
    assert (np.einsum("ij,ij->i", normal / np.linalg.norm(normal, axis=1)[:, None], rz) > 0.9999).all()

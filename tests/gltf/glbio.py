"""Reading a glTF binary for the test readers (tests/gltf/wind.py, leaves.py, tests/lod/check.py)."""
import json, struct


def read_glb(path, fail):
    """The JSON chunk (parsed) and the BIN chunk of a .glb; fail(message) when it is not one."""
    b = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", b, 0)
    if magic != 0x46546C67 or version != 2 or length != len(b):
        fail(f"{path}: not a glTF 2.0 binary")
    jlen, _ = struct.unpack_from("<II", b, 12)
    js = json.loads(b[20:20 + jlen])
    at = 20 + jlen
    blen, _ = struct.unpack_from("<II", b, at)
    return js, b[at + 8:at + 8 + blen]


def triangles(idx, mode):
    """A primitive's indices (flat) as triangles, by glTF's rule for its mode: 4 a list,
    5 a strip whose triangle i is (v_i, v_i+1+i%2, v_i+2-i%2), its joins (triangles
    without area) dropped; None for another mode."""
    if mode == 4:
        return [tuple(idx[k:k + 3]) for k in range(0, len(idx), 3)]
    if mode != 5:
        return None
    tris = [(idx[i], idx[i + 1 + i % 2], idx[i + 2 - i % 2]) for i in range(len(idx) - 2)]
    return [t for t in tris if len(set(t)) == 3]

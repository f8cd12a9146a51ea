"""Reading a glTF binary for the test readers (tests/gltf/wind.py, tests/lod/check.py)."""
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

"""The species shipped with Sylva: the examples' model files (`make blender-addon` copies
examples/ and their gallery pictures into the add-on as library/), each by its name
("weberpenn/quaking_aspen") with its picture from docs/gallery as the enum's preview icon;
and the presets of Blender's own Sapling add-on, as sapling/NAME."""
from __future__ import annotations

import os

_HERE = os.path.dirname(os.path.abspath(__file__))
FOLDERS = ("weberpenn", "sot", "pafco", "strands", "curvetree", "hybrid", "picek", "seeds", "abop", "scenes",
           "ecosystem")
EXTS = (".syl", ".xml", ".cfg")


def _roots() -> tuple[str, str]:
    """(models, pictures): inside the installed add-on, or the repository's when it is run
    from a clone (blender/sylva_blender beside examples/ and docs/gallery)."""
    lib = os.path.join(_HERE, "library")
    if os.path.isdir(lib):
        return lib, os.path.join(lib, "gallery")
    repo = os.path.dirname(os.path.dirname(_HERE))
    return os.path.join(repo, "examples"), os.path.join(repo, "docs", "gallery")


def sapling_presets() -> str | None:
    """The folder of the Sapling add-on's presets in the running Blender (Python dictionaries
    Sylva reads as Weber–Penn trees, docs/arbaro.md#saplings-presets), if it has one."""
    try:
        import addon_utils
    except ImportError:  # outside Blender
        return None
    for root in addon_utils.paths():
        d = os.path.join(root, "add_curve_sapling", "presets")
        if os.path.isdir(d):
            return d
    return None


_species: list[tuple[str, str]] = []  # the list of species, read once a session (free() forgets it)


def species() -> list[tuple[str, str]]:
    """(name, path) of every model file of the library, folder by folder, names sorted, then
    Sapling's presets as sapling/NAME. Read once: the library is the installed add-on's folder
    (a scan took a third of the operator's time on a small tree)."""
    if _species:
        return _species
    models, _ = _roots()
    out = []
    for folder in FOLDERS:
        d = os.path.join(models, folder)
        if not os.path.isdir(d):
            continue
        for f in sorted(os.listdir(d)):
            stem, ext = os.path.splitext(f)
            if ext in EXTS:
                out.append((f"{folder}/{stem}", os.path.join(d, f)))
    sap = sapling_presets()
    if sap:
        out += [(f"sapling/{f[:-3]}", os.path.join(sap, f)) for f in sorted(os.listdir(sap)) if f.endswith(".py")]
    _species[:] = out
    return _species


def path(name: str) -> str:
    """The file of a species; KeyError names the way names are written."""
    for n, p in species():
        if n == name:
            return p
    raise KeyError(f"the library has no species {name!r} (its names: folder/stem, as weberpenn/quaking_aspen)")


def picture(name: str) -> str | None:
    _, pics = _roots()
    folder, _, stem = name.rpartition("/")
    for f in (f"{folder}_{stem}.png", f"{stem}.png"):  # the gallery's names: pafco_oak beside sot's oak
        if os.path.isfile(os.path.join(pics, f)):
            return os.path.join(pics, f)
    return None


NONE = "NONE"  # no species: the operator's File
_previews = None
_items: list = []  # Blender keeps no reference to a dynamic enum's strings: this list does


def enum_items(self, context):
    """The items of a species enum, each with its gallery picture (loaded once)."""
    global _previews
    if _items:
        return _items
    import bpy.utils.previews
    if _previews is None:
        _previews = bpy.utils.previews.new()
    _items.append((NONE, "None", "a model file instead (File)", 0, 0))
    for i, (name, p) in enumerate(species(), 1):
        pic = picture(name)
        icon = 0
        if pic:
            icon = (_previews.get(name) or _previews.load(name, pic, "IMAGE")).icon_id
        _items.append((name, name, p, icon, i))
    return _items


def free() -> None:
    global _previews
    if _previews is not None:
        import bpy.utils.previews
        bpy.utils.previews.remove(_previews)
        _previews = None
    _items.clear()
    _species.clear()

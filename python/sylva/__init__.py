"""Sylva from Python: compile plant models, derive their strings, build skeletons and meshes,
render pictures, and read every result as numpy arrays (docs/python.md).

    >>> import sylva
    >>> plant = sylva.load("examples/abop/fig1_24e_plant.syl").model
    >>> s = plant.derive(5)
    >>> len(s), s.counts()["F"]
    >>> tree = plant.build(angle=30)          # skeleton and mesh, --set angle=30
    >>> tree.mesh.vertices.shape, tree.skeleton.positions[:3]
    >>> tree.mesh.save("plant.glb")
"""
from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Iterable, Iterator, Mapping

import numpy as np

from . import _core, _view
from .errors import CompileError, LimitError, SylvaError

__all__ = ["load", "compile", "compare", "File", "Model", "Extern", "String", "Module", "Plant", "Skeleton", "Mesh",
           "Level", "Wind", "Impostor", "LeafSet", "Queries",
           "Picture", "Param", "Ecosystem", "Snapshot", "CompileError", "LimitError", "SylvaError", "__version__"]
__version__ = _core.VERSION

_core._set_errors(CompileError, LimitError)

VIEWS = {"iso": 0, "front": 1, "side": 2, "top": 3, "auto": 4}
LEAVES = {"copied": 0, "cards": 1, "instanced": 2, "instanced-cards": 3, "clusters": 4}
_UNTIL = {"mesh": 0, "skeleton": 1, "string": 2}
# Keyword arguments of the building calls; every other keyword is a model parameter (--set).
_OPTIONS = {"seed", "threads", "max_modules", "max_memory", "scene", "leaves", "sides", "age", "one_sided",
            "optimize", "functions", *(_REALTIME := ("lod", "impostor", "billboards", "impostor_grid", "impostor_view",
                                                     "wind", "wind_dir", "wind_seconds", "wind_levels"))}


def load(path: str | os.PathLike, **overrides) -> "File":
    """Read a model file (.syl, Arbaro .xml, ...). Keyword arguments are --set values for
    every model of it. Raises CompileError (with .path, .line, .col) for a wrong model."""
    path = os.fspath(path)
    return File(path, None, overrides)


def compile(text: str, name: str = "<text>", **overrides) -> "File":  # noqa: A001 (as sylva compile)
    """Compile model source text; name is the path its messages give."""
    if not isinstance(text, str):
        raise TypeError(f"compile() takes the model's text as str, not {type(text).__name__}")
    return File(name, text.encode("utf-8"), overrides)


def _pairs(overrides: Mapping[str, object]) -> list[tuple[str, float]]:
    out = []
    for k, v in overrides.items():
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
            raise TypeError(f"parameter {k} takes a number, not {type(v).__name__}")
        out.append((k, float(v)))
    return out


class File:
    """A model file: its models by name (`file["Birch"]`, `file.model` for the first)."""

    def __init__(self, path: str, text: bytes | None, overrides: Mapping[str, object]):
        self.path = path
        self._text = text
        self._overrides = dict(overrides)
        # Compiling the first model checks the whole file (and the --set names) now.
        self._first, self.warnings = _core.compile(path, text, None, _pairs(self._overrides))
        self.models = _core.models(path, text) or [self._first.info()["name"]]
        self._cache: dict[str, Model] = {}

    def __getitem__(self, name: str) -> "Model":
        if not isinstance(name, str):
            raise TypeError(f"models are named by str, not {type(name).__name__}")
        if name not in self.models:
            close = [m for m in self.models if m.lower() == name.lower()]
            hint = f"; did you mean {close[0]}?" if close else ""
            raise KeyError(f"{self.path} has no model {name!r} (it has {', '.join(self.models)}){hint}")
        if name not in self._cache:
            self._cache[name] = Model(self, name)
        return self._cache[name]

    def __iter__(self) -> Iterator["Model"]:
        return (self[n] for n in self.models)

    def __len__(self) -> int:
        return len(self.models)

    @property
    def model(self) -> "Model":
        """The first model (the one `sylva FILE` builds)."""
        return self[self._first.info()["name"]] if self._first.info()["name"] in self.models else self[self.models[0]]

    def _compile(self, name: str, overrides: Mapping[str, object]):
        merged = {**self._overrides, **overrides}
        prog, _ = _core.compile(self.path, self._text, name, _pairs(merged))
        return prog

    def __repr__(self) -> str:
        return f"<sylva.File {self.path!r}: {', '.join(self.models)}>"


@dataclass(frozen=True)
class Extern:
    """A function the model declares `extern name(a, b)`: Python binds it (functions=)."""
    name: str
    nparams: int
    has_default: bool


@dataclass(frozen=True)
class Param:
    """One parameter of a model, as `sylva describe` lists it."""
    name: str
    type: str
    min: float | None
    max: float | None
    default: object
    value: object
    unit: str
    doc: str
    values: list | None = None
    aliases: tuple = ()


class Model:
    """One model of a file. Every call takes --set overrides as keyword arguments
    (`model.derive(7, angle=30)`), checked as `sylva --set` checks them."""

    def __init__(self, file: File, name: str):
        self.file = file
        self.name = name
        self._program = file._compile(name, {})
        info = self._program.info()
        self.kind = info["kind"]  # the block's keyword, from the library's table of kinds
        self.kind_name = info["kind_name"]  # "weber block"
        # what the kind does, asked of the library (no list of kinds here)
        self.has_string, self.has_steps, self.is_plant = info["has_string"], info["has_steps"], info["is_plant"]
        # every capability of the kind by the library's name (lang/kind_flags.def): caps.ages,
        # caps.not_a_plant, caps.takes_terrain, ...
        self.caps = SimpleNamespace(**info["caps"])
        self.symbols = info["symbols"]
        self.steps = info["steps"]
        self.seed = info["seed"]
        self.externs = {n: Extern(n, k, d) for n, k, d in self._program.externs()}

    def _prog(self, overrides: Mapping[str, object], functions=None):
        """The program for one call; with functions, a fresh one whose externs they answer
        (bindings belong to the call, not to a program other threads may derive)."""
        if functions is None:
            missing = [e for e in self.externs.values() if not e.has_default]
            if missing:
                raise ValueError(f"model {self.name} calls extern {_sig(missing[0])}, which has no default: "
                                 f"bind it with functions={{{missing[0].name!r}: ...}}")
            return self._program if not overrides else self.file._compile(self.name, overrides)
        if not isinstance(functions, Mapping):
            raise TypeError(f"functions is a dict of name: function, not {type(functions).__name__}")
        for name, fn in functions.items():
            if not isinstance(name, str):
                raise TypeError(f"functions' names are str, not {type(name).__name__}")
            if name not in self.externs:
                have = ", ".join(_sig(e) for e in self.externs.values()) or "none"
                raise ValueError(f"model {self.name} declares no extern {name!r} (its externs: {have})")
            if not callable(fn):
                raise TypeError(f"functions[{name!r}] is not callable ({type(fn).__name__})")
        missing = [e for e in self.externs.values() if not e.has_default and e.name not in functions]
        if missing:
            raise ValueError(f"model {self.name} calls extern {_sig(missing[0])}, which has no default: "
                             f"bind it too")
        prog = self.file._compile(self.name, overrides)
        for name, fn in functions.items():
            prog.bind(name, fn)
        return prog

    @property
    def params(self) -> dict[str, Param]:
        """Every parameter with its range, default, unit and meaning (the directive schema)."""
        text = self._program.describe()
        if text is None:
            raise NotImplementedError("this build of libsylva has no sylva_describe_json")
        for m in json.loads(text)["models"]:
            if m["name"] == self.name:
                return {p["name"]: Param(p["name"], p["type"], p.get("min"), p.get("max"), p.get("default"),
                                         p.get("value"), p.get("unit", ""), p.get("doc", ""), p.get("values"),
                                         tuple(p.get("aliases") or ())) for p in m["params"]}
        return {}

    def setting(self, name: str) -> float:
        """An lsystem setting: angle, step, width, derive, widthfactor, lod."""
        return self._program.setting(name)

    def derive(self, steps: int | None = None, *, seed: int | None = None, threads: int = 0,
               max_modules: int = 0, max_memory: int = 0, environment=None, functions=None,
               **overrides) -> "String":
        """Derive the module string (`sylva derive`); steps None: the model's `derive`.
        environment: a function(step, queries) that answers the ?E modules after every step
        (see Queries); None: the stand-alone environment of `sylva derive`.
        functions: {name: function} for the model's `extern` declarations, called with floats
        for every evaluation (one thread unless threads says more).
        Ctrl-C stops it between steps with KeyboardInterrupt."""
        if not self.has_string:
            raise ValueError(f"{self.name} is a {self.kind} model: it has no string; use build()")
        if environment is not None and not callable(environment):
            raise TypeError("environment is a function(step, queries)")
        prog = self._prog(overrides, functions)
        if functions and not threads:
            threads = 1  # the calls take the GIL in turn: more threads only wait for it
        env = None if environment is None else _environment(environment)
        s = prog.derive(-1 if steps is None else _count("steps", steps), seed, threads, max_modules, max_memory,
                        env)
        return String(s, self.symbols)

    def build(self, steps: int | None = None, *, until: str = "mesh", **kw) -> "Plant":
        """Build the plant as `sylva mesh` does: skeleton and mesh (until="skeleton" stops
        earlier). steps: derivation steps, or years of a grown tree.
        The real-time options of `sylva mesh` (docs/cli.md) give .levels, .impostor and .wind:
        lod=N levels of detail LOD0..LODN, impostor=True the octahedral atlas and crossed
        billboards as the last level (billboards=K: 2 to 4 quads, impostor_grid, impostor_view),
        wind=SPEED (m/s) the sway's joints and keys (wind_dir=(x, z), wind_seconds,
        wind_levels). With any of them the mesh is made as `sylva mesh` makes it for a .glb
        (one_sided=True, optimize=True) unless those say otherwise."""
        opts = {k: kw.pop(k) for k in list(kw) if k in _OPTIONS}
        rt = _realtime({k: opts.pop(k) for k in _REALTIME if k in opts})
        if rt:
            opts.setdefault("one_sided", True)
            opts.setdefault("optimize", True)
        if until not in _UNTIL:
            raise ValueError(f"until is one of {', '.join(_UNTIL)}, not {until!r}")
        leaves = opts.pop("leaves", "copied")
        if leaves not in LEAVES:
            raise ValueError(f"leaves is one of {', '.join(LEAVES)}, not {leaves!r}")
        functions = opts.pop("functions", None)
        prog = self._prog(kw, functions)
        if functions and not opts.get("threads"):
            opts["threads"] = 1
        core = prog.build(until=_UNTIL[until], steps=-1 if steps is None else _count("steps", steps),
                          seed=opts.get("seed"), threads=opts.get("threads", 0),
                          max_modules=opts.get("max_modules", 0), max_memory=opts.get("max_memory", 0),
                          scene=bool(opts.get("scene", False)), leaves=LEAVES[leaves], sides=opts.get("sides", 0),
                          age=float(opts.get("age", 0.0)), one_sided=bool(opts.get("one_sided", False)),
                          optimize=bool(opts.get("optimize", False)), **rt)
        plant = Plant(core, self.name)
        plant._leaves = leaves
        return plant

    def save(self, path: str | os.PathLike, steps: int | None = None, **kw) -> "Plant":
        """Build and write a mesh file as `sylva mesh -o PATH` does (.glb, .obj or .ply; the
        same bytes): for glTF, leaves made once and drawn double-sided; triangles without area
        dropped. Returns the plant."""
        path = os.fspath(path)
        plant = self.build(steps, one_sided=path.lower().endswith(".glb"), optimize=True, **kw)
        plant.mesh.save(path)
        return plant

    def run(self, years: int | None = None, *, seed: int | None = None, snapshots=None, threads: int = 0,
            max_plants: int = 0, tiles: tuple[int, int] = (1, 1), **overrides) -> "Ecosystem":
        """Run an ecosystem block as `sylva ecosystem` does: its years (None: the block's),
        with snapshots of every plant at the given years (None: the block's). Ctrl-C stops it
        at the end of a year with KeyboardInterrupt."""
        if self.is_plant:  # the library refuses any other kind that is not one (syl_ecosystem_load)
            raise ValueError(f"{self.name} is a {self.kind} model, not an ecosystem block")
        tx, tz = tiles
        core = self._prog(overrides).ecosystem(
            years=0 if years is None else _count("years", years), seed=seed, threads=threads,
            max_plants=_count("max_plants", max_plants), tiles_x=_count("tiles", tx), tiles_z=_count("tiles", tz),
            snapshots=None if snapshots is None else [_count("a snapshot year", y) for y in snapshots])
        return Ecosystem(core, self.name)

    def skeleton(self, steps: int | None = None, **kw) -> "Skeleton":
        return self.build(steps, until="skeleton", **kw).skeleton

    def mesh(self, steps: int | None = None, **kw) -> "Mesh":
        return self.build(steps, **kw).mesh

    def render(self, width: int = 512, height: int = 512, *, view: str = "auto", steps: int | None = None,
               **kw) -> "Picture":
        return self.build(steps, **kw).render(width, height, view=view)

    def _repr_png_(self):
        return self.render(384, 384)._repr_png_()

    def interact(self, steps: int | None = None, *, view: str = "picture", size: int = 384, **kw):
        """A slider for each numeric parameter of the model (ipywidgets, Debian's
        python3-ipywidgets); moving one rebuilds the plant with it as an override and shows it:
        view="picture" its picture (fast), "3d" the 3D view. Keyword arguments are the builds'
        (seed=, overrides that stay). Returns the panel, with .sliders by name, .plant (the
        last build) and .overrides (the sliders' values)."""
        size = _count("size", size)
        if view not in ("picture", "3d"):
            raise ValueError(f"view is 'picture' or '3d', not {view!r}")
        if not self.is_plant:
            raise ValueError(f"{self.name} is {'an' if self.kind_name[0] in 'aeiou' else 'a'} {self.kind_name}: "
                             "it has no plant to rebuild")
        try:
            import ipywidgets as widgets
            from IPython.display import clear_output, display
        except ImportError as e:
            raise ImportError("interact() needs ipywidgets (Debian: python3-ipywidgets)") from e
        sliders = {}
        for p in self.params.values():
            v = p.value
            if p.type not in ("number", "integer") or p.name in ("seed", "maxdepth") or p.name in kw \
                    or (steps is not None and p.name in ("derive", "years")) \
                    or isinstance(v, bool) or not isinstance(v, (int, float)):
                continue
            lo, hi = _slider_range(p)
            if p.type == "integer":
                s = widgets.IntSlider(value=int(v), min=int(lo), max=int(hi), step=1)
            else:
                s = widgets.FloatSlider(value=float(v), min=lo, max=hi, step=(hi - lo) / 100 or 0.01)
            s.description, s.continuous_update = p.name, False
            sliders[p.name] = s
        out = widgets.Output()
        panel = widgets.VBox(list(sliders.values()) + [out])
        panel.sliders, panel.plant, panel.overrides = sliders, None, {}

        def update(_=None):
            panel.overrides = {n: s.value for n, s in sliders.items()}
            panel.plant = self.build(steps, **{**kw, **panel.overrides})
            with out:
                clear_output(wait=True)
                display(panel.plant.render(size, size) if view == "picture" else panel.plant)

        for s in sliders.values():
            s.observe(update, names="value")
        update()
        return panel

    def _repr_mimebundle_(self, include=None, exclude=None):
        """In a notebook: the built plant in the 3D view of `sylva view` (an ecosystem block:
        its last snapshot), with a picture for frontends without HTML."""
        if not self.is_plant:  # the one such kind runs (lang/kinds.def: KF_NOT_A_PLANT)
            run = self.run()
            return run.snapshot(max(run._snaps))._repr_mimebundle_() if run._snaps else None
        return self.build()._repr_mimebundle_()

    def __repr__(self) -> str:
        return f"<sylva.Model {self.name} ({self.kind}) of {self.file.path!r}>"


class Queries:
    """The ?E modules of one step, as an environment function receives them: .positions and
    .headings (k, 3) float32 where the turtle stands at each; .params (k, n) float64, each
    row the module's parameters (its first says what is asked, docs/language.md §19), which
    the function overwrites with its answers; .nparams (k,) how many of a row's entries are
    the module's; .tips (k,) bool, whether it stands at the end of the segment just drawn;
    .ends (m, 3) every segment end drawn this step."""

    __slots__ = ("step", "positions", "headings", "params", "nparams", "tips", "ends")

    def __len__(self) -> int:
        return len(self.params)


def _environment(fn):
    def call(step, pos, hd, par, na, tip, ends):
        q = Queries()
        q.step = step
        q.positions, q.headings = np.asarray(pos), np.asarray(hd)
        q.params, q.nparams = np.asarray(par), np.asarray(na)
        q.tips, q.ends = np.asarray(tip).astype(bool), np.asarray(ends)
        fn(step, q)
    return call


def _realtime(o: dict) -> dict:
    """The real-time keyword arguments of build() as _core.Program.build takes them."""
    out = {}
    for k in ("lod", "billboards", "impostor_grid", "impostor_view", "wind_levels"):
        if k in o:
            out[k] = _count(k, o[k])
    if o.get("impostor"):
        out["impostor"] = True
    for k in ("wind", "wind_seconds"):
        if k in o and o[k] is not None:
            if isinstance(o[k], bool) or not isinstance(o[k], (int, float, np.integer, np.floating)):
                raise TypeError(f"{k} is a number, not {type(o[k]).__name__}")
            if not o[k] >= 0:
                raise ValueError(f"{k} is not negative ({o[k]})")
            out[k] = float(o[k])
    if o.get("wind_dir") is not None:
        x, z = (float(c) for c in o["wind_dir"])
        out["wind_dx"], out["wind_dz"] = x, z
    return {k: v for k, v in out.items() if v}


def _slider_range(p: "Param") -> tuple[float, float]:
    """Around the parameter's value, within its range: [0, 2v] for a positive value; a step
    count (derive, years) only two more, which is already a lot of growth."""
    v = float(p.value)
    span = abs(v) if v else 1.0
    lo, hi = v - span, v + span
    if p.name in ("derive", "years"):
        lo, hi = 0.0, v + 2
    if p.min is not None:
        lo = max(lo, float(p.min))
    if p.max is not None:
        hi = min(hi, float(p.max))
    return lo, max(hi, lo)


def _sig(e: Extern) -> str:
    return f"{e.name}/{e.nparams}"


def _count(what: str, v) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
        raise TypeError(f"{what} is a whole number, not {type(v).__name__}")
    if v < 0:
        raise ValueError(f"{what} is not negative ({v})")
    return int(v)


@dataclass(frozen=True)
class Module:
    name: str
    params: tuple


class String:
    """A derived string: len(), modules by index and slice, parameters per module name as numpy
    arrays (`s.params("F")`: one row per F), counts per name, and its text."""

    def __init__(self, core, symbols: list[str]):
        self._core = core
        self.symbols = symbols
        self._ids = {n: i for i, n in enumerate(symbols)}

    def __len__(self) -> int:
        return len(self._core)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        if not isinstance(i, (int, np.integer)) or isinstance(i, bool):
            raise TypeError(f"modules are indexed by int or slice, not {type(i).__name__}")
        sym, par = self._core.module(int(i))
        return Module(self.symbols[sym], par)

    def __iter__(self) -> Iterator[Module]:
        return (self[i] for i in range(len(self)))

    @property
    def ids(self) -> np.ndarray:
        """Every module's symbol id (int32), an index into .symbols."""
        return np.asarray(self._core.symbols())

    def counts(self) -> dict[str, int]:
        c = np.bincount(self.ids, minlength=len(self.symbols))
        return {n: int(c[i]) for i, n in enumerate(self.symbols) if c[i]}

    def params(self, name: str, nparams: int | None = None) -> np.ndarray:
        """The parameters of every `name` module, one row each, in string order (float64).
        Modules of one name with different parameter counts: say which count with nparams."""
        if name not in self._ids:
            raise KeyError(f"no module {name!r} in this model (it has {' '.join(self.symbols)})")
        return np.asarray(self._core.gather(self._ids[name], -1 if nparams is None else _count("nparams", nparams)))

    @property
    def text(self) -> str:
        return self._core.text()

    @property
    def rewritten(self) -> int:
        return self._core.stats()["rewritten"]

    @property
    def seconds(self) -> float:
        """The derivation's wall time."""
        return self._core.stats()["seconds"]

    @property
    def cpu_seconds(self) -> float:
        """The derivation's processor time (every thread's), which a busy machine does not inflate."""
        return self._core.stats()["cpu_seconds"]

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"<sylva.String of {len(self)} modules>"


def _dtype(layout: dict, fields: dict) -> np.dtype:
    names = [n for n in fields if n in layout]
    return np.dtype({"names": names, "formats": [fields[n] for n in names], "offsets": [layout[n] for n in names],
                     "itemsize": layout["itemsize"]})


NODE_DTYPE = _dtype(_core.LAYOUT["node"], {"pos": ("<f4", 3), "h": ("<f4", 3), "l": ("<f4", 3), "u": ("<f4", 3),
                                           "radius": "<f4", "parent": "<i4", "axis": "<i4", "order": "<u2",
                                           "kind": "u1", "material": "u1", "flags": "u1", "module": "<u4"})
ORGAN_DTYPE = _dtype(_core.LAYOUT["organ"], {"pos": ("<f4", 3), "h": ("<f4", 3), "l": ("<f4", 3),
                                             "u": ("<f4", 3), "size": "<f4", "node": "<i4", "kind": "u1",
                                             "material": "u1", "module": "<u4"})
ORGAN_KINDS = tuple(_core.ORGAN_KINDS)


class Skeleton:
    """A plant's skeleton as numpy views of Sylva's own records (no copy): .nodes and .organs
    are structured arrays; positions, parent, radius, order and kind are their columns."""

    def __init__(self, plant: "Plant"):
        self._plant = plant
        self.nodes = np.frombuffer(plant._core.nodes(), dtype=NODE_DTYPE)
        self.organs = np.frombuffer(plant._core.organs(), dtype=ORGAN_DTYPE)

    positions = property(lambda self: self.nodes["pos"])
    parent = property(lambda self: self.nodes["parent"])
    radius = property(lambda self: self.nodes["radius"])
    order = property(lambda self: self.nodes["order"])
    kind = property(lambda self: self.nodes["kind"])

    def __len__(self) -> int:
        return len(self.nodes)

    def csv(self) -> str:
        """As `sylva skeleton` writes it."""
        return self._plant._core.skeleton_csv()

    def _segments(self):
        n = self.nodes
        child = np.flatnonzero(n["parent"] >= 0)
        return n["pos"][n["parent"][child]], n["pos"][child], n["order"][child]

    def picture(self, size: int = 384) -> "Picture":
        """The skeleton's segments seen from the front, coloured by branching order."""
        return _view.lines_png(*self._segments(), size=_count("size", size)).view(Picture)

    def _repr_png_(self) -> bytes:
        return self.picture()._repr_png_()

    def _repr_mimebundle_(self, include=None, exclude=None):
        return _view.bundle({"csv": self.csv()}, self._repr_png_(), f"{self._plant.name}: {len(self)} nodes")

    def __repr__(self) -> str:
        return f"<sylva.Skeleton: {len(self.nodes)} nodes, {len(self.organs)} organs>"


class Mesh:
    """A mesh as numpy views (no copy): vertices (n, 3), normals (n, 3), uvs (n, 2) float32 and
    triangles (m, 3) uint32; groups say which triangles have which material."""

    def __init__(self, plant: "Plant", arrays: dict | None = None):
        self._plant = plant
        a = arrays or plant._core.mesh_arrays()
        self.vertices = np.asarray(a["positions"])
        self.normals = np.asarray(a["normals"])
        self.uvs = np.asarray(a["uvs"])
        self.triangles = np.asarray(a["triangles"])
        self.groups = a["groups"]

    def save(self, path: str | os.PathLike) -> None:
        """Write .glb, .obj or .ply (by the extension) through the writers of `sylva mesh`;
        a plant built with lod= or wind= writes its levels and sway into a .glb."""
        self._plant._core.write(os.fspath(path))

    levels = property(lambda self: self._plant.levels, doc="the plant's levels of detail (Plant.levels)")
    wind = property(lambda self: self._plant.wind, doc="the plant's wind animation (Plant.wind)")
    impostor = property(lambda self: self._plant.impostor, doc="the plant's impostor (Plant.impostor)")

    def _repr_mimebundle_(self, include=None, exclude=None):
        return self._plant._repr_mimebundle_()

    def __repr__(self) -> str:
        return f"<sylva.Mesh: {len(self.vertices)} vertices, {len(self.triangles)} triangles>"


@dataclass(frozen=True)
class Level:
    """One level of detail (`sylva mesh --lod`): LODk's mesh and how it was made (docs/mesh.md):
    stems of order <= max_order and at least min_radius thick, leaf_keep of the leaves
    enlarged by leaf_scale; shown above coverage of the screen's height; billboards: the
    impostor's crossed quads (textured with Impostor.billboard_atlas)."""
    level: int
    mesh: "Mesh"
    max_order: int
    min_radius: float
    leaf_keep: float
    leaf_scale: float
    cluster_leaves: float
    coverage: float
    error: float
    billboards: bool
    _plant: "Plant" = None

    def leaf_sets(self) -> "list[LeafSet]":
        """This level's leaves as instance sets, as the .glb places them under LODk (a plant
        built with leaves='instanced' or 'instanced-cards'; LOD0's are Plant.leaf_sets())."""
        if self.level == 0:
            return self._plant.leaf_sets(cards=self._plant._leaves == "instanced-cards")
        return [LeafSet(self._plant, d) for d in self._plant._core.leaf_sets(level=self.level)]

    def skin(self) -> "tuple[np.ndarray, np.ndarray] | None":
        """With wind: each vertex's two joints and weights (bytes summing to 255) of this
        level's mesh, as the .glb skins it to the one set of joints; None for the billboards."""
        s = self._plant._core.skin(self.level)
        return None if s is None else tuple(np.asarray(a) for a in s)

    @property
    def triangles(self) -> int:
        return len(self.mesh.triangles)


class Impostor:
    """The plant baked into atlases (`sylva mesh --impostor`): .color and .normal the
    grid x grid octahedral atlas (size x size RGBA; None with billboards= alone),
    .billboard_atlas the crossed billboards' texture (view x 2·billboards·view RGBA), the
    bounding sphere (centre, radius) every view frames."""

    def __init__(self, d: dict):
        def rgba(b, w=None):
            if b is None:
                return None
            a = np.asarray(b)
            return a.reshape(a.shape[0], -1, 4).view(Picture)
        self.grid, self.view, self.size = d["grid"], d["view"], d["size"]
        self.color, self.normal = rgba(d["color"]), rgba(d["normal"])
        self.billboard_atlas = rgba(d["bb_color"])
        self.centre, self.radius, self.billboards = d["centre"], d["radius"], d["billboards"]

    def __repr__(self) -> str:
        return f"<sylva.Impostor {self.grid}x{self.grid} views of {self.view} px, {self.billboards} billboards>"


WIND_STEM_DTYPE = _dtype(_core.LAYOUT["wind_stem"], {"joint": "<i4", "parent": "<i4", "base": ("<f4", 3),
                                                     "dir": ("<f4", 3), "length": "<f4", "radius": "<f4",
                                                     "parent_radius": "<f4", "phase": "<f4", "stiffness": "<f4",
                                                     "order": "<u2"})
WIND_JOINT_DTYPE = _dtype(_core.LAYOUT["wind_joint"], {"stem": "<i4", "parent": "<i4", "amplitude": "<f4",
                                                       "frequency": "<f4", "blend_start": "<f4",
                                                       "blend_length": "<f4"})


class Wind:
    """The sway of `sylva mesh --wind` (docs/mesh.md#wind): a joint per stem of the first
    levels, parents first (.joints: stem, parent, amplitude, frequency, blend; .stems: base,
    dir, length, radius, phase, ...), each joint's rotation at every key as unit quaternions
    x, y, z, w in its parent's frame, which has no rest rotation (.rotations (joints, keys, 4)),
    at .times (the last key is the first: the loop), and each vertex's two joints and weights
    (.skin_joints, .skin_weights bytes summing to 255) as the .glb skins the mesh. Y is up.
    .heads: each joint's pivot, its stem's base."""

    def __init__(self, d: dict, skin):
        self.stems = np.frombuffer(d["stems"], dtype=WIND_STEM_DTYPE)
        self.joints = np.frombuffer(d["joints"], dtype=WIND_JOINT_DTYPE)
        self.seconds, self.nkeys = d["seconds"], d["nkeys"]
        self.rotations = np.asarray(d["rot"]).reshape(len(self.joints), self.nkeys, 4)
        k = np.arange(self.nkeys)
        self.times = np.where(k == self.nkeys - 1, self.seconds, self.seconds * k / max(self.nkeys - 1, 1))
        self.skin_joints, self.skin_weights = (np.asarray(a) for a in skin)

    @property
    def heads(self) -> np.ndarray:
        return self.stems["base"][self.joints["stem"]]

    def __len__(self) -> int:
        return len(self.joints)

    def __repr__(self) -> str:
        return f"<sylva.Wind: {len(self)} joints, {self.nkeys} keys over {self.seconds:g} s>"


class LeafSet:
    """The leaves of one material as instances of one prototype leaf (`sylva mesh --leaves
    instanced`, EXT_mesh_gpu_instancing): .proto the leaf of size 1 the mesher makes (the
    model's own outline; at the origin along +x, across +y, facing +z; one-sided), and per
    leaf .translations (n, 3), .rotations (n, 4) unit quaternions x, y, z, w, .scales (n, 3)
    and .nodes (its skeleton node; None for a level's leaves built without wind), and with
    wind .joints (the wind joint each leaf follows, the one the .glb puts it under; else None):
    a vertex p of the prototype is at T + R (S p). Y is up."""

    def __init__(self, plant: "Plant", d: dict):
        self.name = d["name"]
        self.proto = Mesh(plant, d["proto"])
        self.translations, self.rotations = np.asarray(d["t"]), np.asarray(d["r"])
        self.scales = np.asarray(d["s"])
        self.nodes = None if d["node"] is None else np.asarray(d["node"])
        self.joints = None if d.get("joint") is None else np.asarray(d["joint"])

    def __len__(self) -> int:
        return len(self.translations)

    def __repr__(self) -> str:
        return f"<sylva.LeafSet {self.name}: {len(self)} leaves of {len(self.proto.triangles)} triangles>"


class Picture(np.ndarray):
    """An (H, W, 4) uint8 RGBA picture; notebooks show it (_repr_png_)."""

    def _repr_png_(self) -> bytes:
        return _png(np.asarray(self))


def _png(rgba: np.ndarray) -> bytes:
    """PNG bytes of an RGBA array, by the library's encoder."""
    h, w, _ = rgba.shape
    return _core.png_rgba(np.ascontiguousarray(rgba, np.uint8).tobytes(), w, h)


class Plant:
    """What a build made: .skeleton and .mesh (numpy views), counts and timings in .info,
    pictures by .render(), compare's figures by .metrics()."""

    def __init__(self, core, name: str):
        self._core = core
        self.name = name
        self.info = core.info()
        self._leaves = "copied"  # the build's leaves= (Level.leaf_sets)

    @property
    def skeleton(self) -> Skeleton:
        return Skeleton(self)

    @property
    def mesh(self) -> Mesh:
        return Mesh(self)

    @property
    def levels(self) -> list[Level]:
        """The levels of detail of lod= (or impostor=, billboards=), LOD0 first; [] without."""
        return [Level(d["level"], Mesh(self, d["mesh"]), d["max_order"], d["min_radius"], d["leaf_keep"],
                      d["leaf_scale"], d["cluster_leaves"], d["coverage"], d["error"], d["billboards"], self)
                for d in self._core.levels()]

    def leaf_sets(self, cards: bool = False) -> list[LeafSet]:
        """The leaves as instances, one set a leaf material, as `sylva mesh --leaves instanced`
        (cards: instanced-cards) places them; the plant's mesh is unchanged."""
        return [LeafSet(self, d) for d in self._core.leaf_sets(cards=bool(cards))]

    @property
    def impostor(self) -> "Impostor | None":
        d = self._core.impostor()
        return None if d is None else Impostor(d)

    @property
    def wind(self) -> "Wind | None":
        d = self._core.wind()
        return None if d is None else Wind(d, self._core.skin(0))

    def render(self, width: int = 512, height: int = 512, *, view: str = "auto", samples: int = 0,
               transparent: bool = False, threads: int = 0) -> Picture:
        if view not in VIEWS:
            raise ValueError(f"view is one of {', '.join(VIEWS)}, not {view!r}")
        buf = self._core.render(_count("width", width), _count("height", height), VIEWS[view],
                                _count("samples", samples), threads, transparent)
        return np.asarray(buf).view(Picture)

    def metrics(self, threads: int = 0) -> dict[str, float]:
        return self._core.metrics(threads=threads)

    def save(self, path: str | os.PathLike) -> None:
        self.mesh.save(path)

    def _repr_png_(self):
        return self.render(384, 384)._repr_png_()

    def _repr_mimebundle_(self, include=None, exclude=None):
        """The 3D view of `sylva view` with the plant's .glb inlined, and its picture."""
        if not self.info["triangles"]:
            return self.skeleton._repr_mimebundle_()
        i = self.info
        return _view.bundle(_view.glb_data(self._core), self._repr_png_(),
                            f"{self.name}: {i['nodes']} nodes, {i['triangles']} triangles")

    def __repr__(self) -> str:
        i = self.info
        return f"<sylva.Plant {self.name}: {i['nodes']} nodes, {i['triangles']} triangles>"


ECO_PLANT_DTYPE = _dtype(_core.LAYOUT["eco_plant"], {"id": "<u8", "x": "<f4", "z": "<f4", "height": "<f4",
                                                     "vigour": "<f4", "age": "<u2", "species": "u1", "state": "u1"})
_NSP = _core.LAYOUT["eco_max_species"]
ECO_YEAR_DTYPE = _dtype(_core.LAYOUT["eco_year"], {"year": "<i4", "count": ("<u4", _NSP), "cover": ("<f8", _NSP),
                                                   "mean_height": ("<f8", _NSP)})


def _table(columns: dict):
    """A pandas DataFrame when pandas is importable, else a numpy record array."""
    try:
        import pandas as pd
        return pd.DataFrame(columns)
    except ImportError:
        return np.rec.fromarrays(list(columns.values()), names=list(columns))


class Ecosystem:
    """An ecosystem run: iterate it for its yearly summaries; .years is every year as one table
    (year, species, count, cover, mean_height: `species.csv`), .snapshots[year] the plants of
    a snapshot (id, x, z, height, vigour, age, species, state), .terrain the factor maps as
    2-D arrays (rows along z, columns along x), .species the names."""

    def __init__(self, core, name: str):
        self._core = core
        self.name = name
        self.info = core.info()
        self.species = self.info["species"]
        self._years = np.frombuffer(core.years(), dtype=ECO_YEAR_DTYPE)
        self._snaps = {y: np.frombuffer(b, dtype=ECO_PLANT_DTYPE) for y, b in core.snapshots().items()}

    def __iter__(self):
        for r in self._years:
            yield {"year": int(r["year"]),
                   "count": {n: int(r["count"][i]) for i, n in enumerate(self.species)},
                   "cover": {n: float(r["cover"][i]) for i, n in enumerate(self.species)},
                   "mean_height": {n: float(r["mean_height"][i]) for i, n in enumerate(self.species)}}

    def __len__(self) -> int:
        return len(self._years)

    @property
    def years(self):
        k = len(self.species)
        y = self._years
        return _table({"year": np.repeat(y["year"], k), "species": np.tile(np.array(self.species), len(y)),
                       "count": y["count"][:, :k].reshape(-1), "cover": y["cover"][:, :k].reshape(-1),
                       "mean_height": y["mean_height"][:, :k].reshape(-1)})

    @property
    def snapshots(self) -> dict:
        names = np.array(self.species)
        return {year: _table({"id": p["id"], "x": p["x"], "z": p["z"], "height": p["height"], "vigour": p["vigour"],
                              "age": p["age"], "species": names[p["species"]] if len(p) else names[:0],
                              "state": p["state"]})
                for year, p in sorted(self._snaps.items())}

    def plants(self, year: int) -> np.ndarray:
        """A snapshot's plants as a structured array (a view of the run's own records)."""
        return self._snaps[year]

    def snapshot(self, year: int) -> "Snapshot":
        """A snapshot's plants on the terrain; a notebook draws it in 3D."""
        if year not in self._snaps:
            raise KeyError(f"no snapshot of year {year!r} (there are {sorted(self._snaps)})")
        return Snapshot(self, year)

    @property
    def terrain(self) -> dict:
        return {k: np.asarray(v) for k, v in self._core.terrain().items()}

    def __repr__(self) -> str:
        return f"<sylva.Ecosystem {self.name}: {len(self)} years, snapshots {sorted(self._snaps)}>"


class Snapshot:
    """One year's plants of an ecosystem run on its terrain: .plants (a table), .year; shown in
    a notebook as a 3D view (every plant a cone as tall as it is, coloured by species)."""

    MAX_SIDE = 160  # terrain cells a side in the view (a larger DEM is sampled)

    def __init__(self, run: Ecosystem, year: int):
        self.run, self.year = run, year
        self.plants = run.snapshots[year]

    def _cells(self):
        info, p = self.run.info, self.run._snaps[self.year]
        cx = (p["x"] - info["x0"]) / info["cell"]
        cz = (p["z"] - info["z0"]) / info["cell"]
        return cx, cz, p

    def picture(self, size: int = 384) -> "Picture":
        """The snapshot from above: altitude in greys, the plants as dots of their species' colour."""
        alt = self.run.terrain["altitude"]
        cx, cz, p = self._cells()
        return _view.map_png(alt, np.stack([cx, cz], 1), p["species"].astype(np.int64),
                             size=_count("size", size)).view(Picture)

    def _repr_png_(self) -> bytes:
        return self.picture()._repr_png_()

    def _repr_mimebundle_(self, include=None, exclude=None):
        info = self.run.info
        alt = self.run.terrain["altitude"]
        nz, nx = alt.shape
        k = max(1, -(-max(nx, nz) // self.MAX_SIDE))
        sub = alt[::k, ::k]
        cx, cz, p = self._cells()
        iz = np.clip(np.rint(cz).astype(np.int64), 0, nz - 1)
        ix = np.clip(np.rint(cx).astype(np.int64), 0, nx - 1)
        y = alt[iz, ix]
        data = {"terrain": {"nx": int(sub.shape[1]), "nz": int(sub.shape[0]), "cell": float(info["cell"] * k),
                            "x0": float(info["x0"]), "z0": float(info["z0"]),
                            "heights": np.round(sub.astype(np.float64), 3).ravel().tolist()},
                "plants": np.round(np.stack([p["x"], y, p["z"], p["height"], p["species"]], 1).astype(np.float64),
                                   3).tolist(),
                "colours": list(_view.SPECIES_COLOURS)}
        return _view.bundle(data, self._repr_png_(), f"{self.run.name}, year {self.year}: {len(p)} plants")

    def __repr__(self) -> str:
        return f"<sylva.Snapshot {self.run.name} year {self.year}: {len(self.run._snaps[self.year])} plants>"


def compare(*models: Model, seeds: Iterable[int] = (1,), steps: int | None = None, **overrides):
    """Compare's figures for each model and seed, one row each (`sylva compare`): a pandas
    DataFrame when pandas is importable, else a numpy record array."""
    rows = []
    for m in models:
        for seed in seeds:
            plant = m.build(steps, seed=seed, **overrides)
            rows.append({"model": m.name, "seed": seed, **plant.metrics()})
    keys = list(dict.fromkeys(k for r in rows for k in r))
    try:
        import pandas as pd
        return pd.DataFrame(rows, columns=keys)
    except ImportError:
        formats = ["U64" if k == "model" else "i8" if k == "seed" else "f8" for k in keys]
        return np.rec.fromrecords([tuple(r.get(k, np.nan) for k in keys) for r in rows], names=keys,
                                  formats=formats)

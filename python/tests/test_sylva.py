"""The Python package against the `sylva` command's own outputs, hand derivations and
invariants (docs/python.md). SYLVA names the command (default: build/sylva of the checkout)."""
import gc
import os
import re
import subprocess
import threading
import time
import _thread

import numpy as np
import pytest

import sylva

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("SYLVA", os.path.join(ROOT, "build", "sylva"))


def ex(*p):
    return os.path.join(ROOT, "examples", *p)


def cli(*args):
    r = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r


# ---- strings ----

@pytest.mark.parametrize("path,steps,seed", [
    (ex("abop", "fig1_24e_plant.syl"), 4, None),
    (ex("abop", "fig1_27_stochastic.syl"), 4, 7),
    (ex("abop", "fig2_06_monopodial.syl"), 6, None),
])
def test_derived_string_is_the_commands(path, steps, seed):
    args = ["derive", path, "-n", str(steps)] + (["--seed", str(seed)] if seed is not None else [])
    s = sylva.load(path).model.derive(steps, seed=seed)
    assert s.text.strip() == cli(*args).stdout.strip()
    assert len(s) == sum(s.counts().values())


def test_parameters_by_name_hand_derived():
    # A(x) -> F(x) A(2x): after 3 steps F(1) F(2) F(4) A(8)
    f = sylva.compile("lsystem P {\n derive 3\n axiom A(1)\n A(x) -> F(x) A(x*2)\n}\n")
    s = f["P"].derive()
    assert len(s) == 4
    np.testing.assert_array_equal(s.params("F"), [[1.0], [2.0], [4.0]])
    np.testing.assert_array_equal(s.params("A"), [[8.0]])
    assert s[3] == sylva.Module("A", (8.0,))
    assert [m.name for m in s[0:3]] == ["F", "F", "F"]
    assert s[-1].params == (8.0,)
    assert s.counts() == {"F": 3, "A": 1}
    np.testing.assert_array_equal(s.ids, [s.symbols.index(n) for n in "FFFA"])
    with pytest.raises(IndexError):
        s[4]
    with pytest.raises(KeyError):
        s.params("Q")


def test_mixed_parameter_counts_need_nparams():
    s = sylva.compile("lsystem P {\n derive 1\n axiom A\n A -> F F(2) F(3,4)\n}\n")["P"].derive()
    with pytest.raises(ValueError, match="nparams"):
        s.params("F")
    np.testing.assert_array_equal(s.params("F", nparams=2), [[3.0, 4.0]])
    assert s.params("F", nparams=0).shape == (1, 0)


def test_overrides_are_checked_as_set_is():
    m = sylva.load(ex("abop", "fig1_24e_plant.syl")).model
    a = m.build(3, until="skeleton")
    b = m.build(3, until="skeleton", angle=40.0)
    assert len(a.skeleton) == len(b.skeleton)
    assert not np.allclose(a.skeleton.positions, b.skeleton.positions)
    with pytest.raises(ValueError, match="did you mean 'angle'"):
        m.derive(3, anglee=3)
    with pytest.raises(TypeError):
        m.derive(3, angle="wide")
    with pytest.raises(TypeError):
        m.derive("3")
    with pytest.raises(ValueError):
        m.derive(-1)


# ---- every kind, against the command ----

KINDS = [
    (ex("abop", "fig1_25_bush3d.syl"), "lsystem"),
    (ex("sot", "birch.syl"), "grow"),
    (ex("weberpenn", "lombardy_poplar.syl"), "weber"),
    (ex("strands", "holton_fir.syl"), "strands"),
    (ex("curvetree", "bezier_oak.syl"), "curvetree"),
]


def test_a_kind_is_its_keyword_from_the_library():
    # the keyword comes from the library's table of kinds (src/lang/kinds.def): a kind added
    # there is named here without a list in Python (pafco was "pafco block" when one was kept)
    pafco = sylva.load(ex("pafco", "birch.cfg")).model
    assert (pafco.kind, pafco.kind_name) == ("pafco", "pafco block")
    assert (pafco.has_string, pafco.has_steps, pafco.is_plant) == (False, False, True)
    eco = next(m for m in sylva.load(ex("ecosystem", "meadow.syl")) if m.kind == "ecosystem")
    assert not eco.is_plant and not eco.has_string
    with pytest.raises(ValueError, match="is an ecosystem block: it has no plant to rebuild"):
        eco.interact()
    lsys, grow = sylva.load(ex("abop", "fig1_25_bush3d.syl")).model, sylva.load(ex("sot", "birch.syl")).model
    assert lsys.has_string and lsys.has_steps and grow.has_steps and not grow.has_string


def test_caps_follow_the_row_of_the_kind():
    # Model.caps names every capability of the library's list, src/lang/kind_flags.def, read
    # here from the source (so a name added there is here without a list in Python), and a
    # kind's true ones are the KF_ flags of its row in src/lang/kinds.def
    src = os.path.join(ROOT, "src", "lang")
    flags = re.findall(r'^SYL_KIND_FLAG\((\w+),\s*"(\w+)"', open(os.path.join(src, "kind_flags.def")).read(), re.M)
    rows = re.findall(r'^SYL_KIND\(\w+,\s*"(\w+)",\s*"[^"]*",\s*([^,]*),', open(os.path.join(src, "kinds.def")).read(), re.M)
    name = dict(flags)
    row = {kw: {name[f] for f in re.findall(r"KF_(\w+)", fl)} for kw, fl in rows}
    models = [sylva.load(path).model for path, _ in KINDS] + [sylva.load(ex("pafco", "birch.cfg")).model]
    models.append(next(m for m in sylva.load(ex("ecosystem", "meadow.syl")) if not m.is_plant))
    assert {m.kind for m in models} == set(row) - {"scene"}
    for m in models:
        assert list(vars(m.caps)) == [n for _, n in flags]
        assert {n for n, v in vars(m.caps).items() if v} == row[m.kind], m.kind
        assert m.is_plant == (not m.caps.not_a_plant)


@pytest.mark.parametrize("path,kind", KINDS)
def test_every_kind_writes_the_commands_glb(path, kind, tmp_path):
    m = sylva.load(path).model
    assert m.kind == kind
    mine, theirs = tmp_path / "py.glb", tmp_path / "cli.glb"
    plant = m.save(mine)
    cli("mesh", path, "-o", str(theirs))
    assert mine.read_bytes() == theirs.read_bytes()
    stats = cli("mesh", path, "-o", str(tmp_path / "s.glb"), "--stats").stderr
    figures = dict(line.split(": ", 1) for line in stats.splitlines() if ": " in line)
    assert plant.info["nodes"] == int(figures["nodes"])
    assert plant.info["triangles"] == int(figures["triangles"])
    assert len(plant.mesh.triangles) == plant.info["triangles"]


@pytest.mark.parametrize("path,kind", KINDS)
def test_skeleton_arrays_are_the_commands_csv(path, kind):
    sk = sylva.load(path).model.skeleton()
    assert sk.csv() == cli("skeleton", path).stdout
    rows = [r.split(",") for r in sk.csv().splitlines()[1:]]
    nodes = rows[: len(sk)]
    np.testing.assert_allclose(sk.positions, [[float(r[2]), float(r[3]), float(r[4])] for r in nodes], atol=1e-4)
    np.testing.assert_array_equal(sk.parent, [int(r[1]) for r in nodes])
    assert (sk.parent < np.arange(len(sk))).all()  # a parent precedes its child


def test_ecosystem_is_not_a_plant():
    path = ex("ecosystem", "succession.syl")
    f = sylva.load(path)
    kinds = {m.kind for m in f}
    assert "ecosystem" in kinds
    eco = next(m for m in f if m.kind == "ecosystem")
    with pytest.raises(ValueError):
        eco.build()


# ---- arrays: views of Sylva's memory ----

def test_mesh_arrays_are_read_only_views_that_keep_the_plant():
    plant = sylva.load(ex("abop", "fig1_24e_plant.syl")).model.build(3)
    v = plant.mesh.vertices
    t = plant.mesh.triangles
    assert v.dtype == np.float32 and v.shape[1] == 3 and not v.flags.writeable
    assert t.dtype == np.uint32 and t.max() < len(v)
    n = np.linalg.norm(plant.mesh.normals, axis=1)
    np.testing.assert_allclose(n, 1, atol=1e-3)
    del plant
    gc.collect()
    assert np.isfinite(v).all() and t.max() < len(v)  # the views still hold the mesh


def test_skeleton_columns_hand_derived():
    # F F [+F]: a trunk of two unit segments and a branch of order 1 at 90 degrees
    sk = sylva.compile("lsystem P {\n derive 0\n angle 90\n axiom F F [+F]\n}\n")["P"].skeleton()
    assert len(sk) == 4
    np.testing.assert_allclose(sk.positions[:3], [[0, 0, 0], [0, 1, 0], [0, 2, 0]], atol=1e-6)
    assert list(sk.parent) == [-1, 0, 1, 2]
    assert list(sk.order) == [0, 0, 0, 1]
    np.testing.assert_allclose(np.linalg.norm(sk.positions[3] - sk.positions[2]), 1, atol=1e-6)
    assert abs(sk.positions[3][1] - 2) < 1e-6  # the branch is horizontal


def test_render_is_rgba_with_the_plant_in_it():
    plant = sylva.load(ex("abop", "fig1_25_bush3d.syl")).model.build()
    pic = plant.render(96, 64)
    assert pic.shape == (64, 96, 4) and pic.dtype == np.uint8
    assert (pic[..., 3] == 255).all()
    cut = plant.render(96, 64, transparent=True)
    covered = (cut[..., 3] > 0).mean()
    assert 0.02 < covered < 0.9
    png = pic._repr_png_()
    assert png.startswith(b"\x89PNG\r\n\x1a\n")


def test_compare_table_against_the_command():
    import json
    birch = sylva.load(ex("sot", "birch.syl")).model
    t = sylva.compare(birch, seeds=[1, 2])
    assert list(t["seed"]) == [1, 2]
    for row, seed in enumerate([1, 2]):
        out = json.loads(cli("compare", ex("sot", "birch.syl"), "--seed", str(seed), "--json").stdout)
        values = out["models"][0]["values"]  # printed with 6 significant digits
        assert set(values) <= set(t.columns if hasattr(t, "columns") else t.dtype.names)
        for key, v in values.items():
            assert abs(float(t[key][row]) - v) <= 1e-5 * max(1.0, abs(v)), key


# ---- errors ----

def test_compile_error_has_where_and_caret():
    with pytest.raises(sylva.CompileError) as e:
        sylva.compile("lsystem A {\n axiom F\n F -> F[+F\n}\n", name="broken.syl")
    err = e.value
    assert err.path == "broken.syl" and err.line == 3 and err.col >= 1
    assert "^" in str(err) and "F -> F[+F" in str(err)
    assert err.status == 1


def test_limit_error_names_the_limit():
    m = sylva.load(ex("abop", "fig1_24e_plant.syl")).model
    with pytest.raises(sylva.LimitError, match="max-modules|modules"):
        m.derive(7, max_modules=1000)


def test_missing_file_is_an_oserror(tmp_path):
    with pytest.raises((OSError, sylva.CompileError)):
        sylva.load(tmp_path / "nothing.syl")


def test_wrong_argument_types():
    with pytest.raises(TypeError):
        sylva.compile(b"lsystem A { axiom F }")
    m = sylva.compile("lsystem A {\n axiom F\n}\n")["A"]
    with pytest.raises(ValueError):
        m.build(leaves="fluffy")
    with pytest.raises(ValueError):
        m.build().render(view="sideways")
    with pytest.raises(KeyError, match="did you mean A"):
        m.file["a"]


# ---- threads, the GIL and Ctrl-C ----

def test_threads_at_once_give_the_same_strings():
    m = sylva.load(ex("abop", "fig1_27_stochastic.syl")).model
    want = m.derive(5, seed=3).text
    got = [None] * 6

    def work(i):
        got[i] = m.derive(5, seed=3).text

    ts = [threading.Thread(target=work, args=(i,)) for i in range(6)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert got == [want] * 6


def test_ctrl_c_interrupts_a_derivation():
    # one module more a step: 200,000 steps rewrite 2e10 modules, far longer than the
    # interrupt's delay even on a busy machine, and stay below the default --max-work (1e11)
    # however the derivation projects the steps to come (a million steps could hit the limit
    # before the interrupt on a loaded machine)
    m = sylva.compile("lsystem L {\n axiom A\n A -> A B\n}\n")["L"]
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        m.derive(200_000)
    timer.cancel()
    assert time.monotonic() - t0 < 30


def _rss_kb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") // 1024


def test_no_leak_over_many_calls():
    import tracemalloc
    m = sylva.load(ex("abop", "fig1_24e_plant.syl")).model
    for _ in range(20):  # warm up allocators
        m.build(3).mesh.vertices.sum()
    tracemalloc.start()
    rss0 = _rss_kb()
    snap0 = tracemalloc.take_snapshot()
    for _ in range(200):
        p = m.build(3)
        p.mesh.vertices.sum()
        p.skeleton.positions.sum()
        m.derive(4).params("F")
    gc.collect()
    grown = sum(s.size_diff for s in tracemalloc.take_snapshot().compare_to(snap0, "filename"))
    tracemalloc.stop()
    assert grown < 200_000, grown  # Python objects
    assert _rss_kb() - rss0 < 20_000  # C memory: 200 plants of about 1 MB each are freed


# ---- Python as the environment of an open L-system ----

PROBE = """lsystem Probe {
  derive 2
  angle 30
  axiom F(2) [ &(120) A ?E(2, 0) ] [ &(100) /(90) F(1) A ?E(2, 0) ] [ A ?E(2, 0) ] [ &(170) F(0.5) A ?E(2, 0) ] ?P(0, 0, 0)
  A -> F(0.5) A
}
"""


def ground_distance(step, q):
    """?E(2, d): how far ahead along the heading the ground plane y = 0 is (1e9: never)."""
    asked = q.params[:, 0] == 2
    hy = q.headings[:, 1].astype(np.float64)
    y = q.positions[:, 1].astype(np.float64)
    down = hy < 0
    q.params[asked, 1] = np.where(down, y / np.where(down, -hy, 1), 1e9)[asked]


def test_python_environment_answers_as_the_stand_alone_one(tmp_path):
    # alone on the ground with no obstacle, the stand-alone environment's obstacle distance is
    # the ground plane's: the same question answered in numpy gives the same string
    path = tmp_path / "probe.syl"
    path.write_text(PROBE)
    m = sylva.load(path).model
    seen = []

    def env(step, q):
        seen.append((step, len(q), q.nparams.tolist(), bool(q.tips.any()), len(q.ends)))
        ground_distance(step, q)

    s = m.derive(environment=env)
    assert s.text.strip() == cli("derive", str(path)).stdout.strip()
    assert [st for st, *_ in seen] == [0, 1, 2]          # after the axiom and every step
    assert all(k == 4 and na == [2, 2, 2, 2] for _, k, na, _, _ in seen)
    assert s.text.rstrip().endswith("?P(0,2,0)")  # the turtle fills ?P: after the branches, at the trunk top


def test_environment_exceptions_reach_the_caller():
    m = sylva.compile(PROBE)["Probe"]

    def broken(step, q):
        raise ZeroDivisionError("the model of the world failed")

    with pytest.raises(ZeroDivisionError, match="the world"):
        m.derive(environment=broken)
    with pytest.raises(TypeError):
        m.derive(environment=42)


# ---- ecosystems ----

def test_ecosystem_run_is_the_commands(tmp_path):
    import csv
    path = ex("ecosystem", "meadow.syl")
    eco = next(m for m in sylva.load(path) if m.kind == "ecosystem")
    run = eco.run(12, snapshots=[5, 12], threads=1)
    cli("ecosystem", path, "--years", "12", "--snapshots", "5,12", "-o", str(tmp_path), "-j", "1",
        "--size", "64x36", "--samples", "1")
    rows = list(csv.DictReader(open(tmp_path / "species.csv")))
    years = run.years
    assert len(years["year"]) == len(rows)
    for i, r in enumerate(rows):
        assert int(years["year"][i]) == int(r["year"]) and years["species"][i] == r["species"]
        assert int(years["count"][i]) == int(r["count"])
        assert abs(float(years["mean_height"][i]) - float(r["mean_height"])) < 0.0006
    summaries = list(run)
    assert [s["year"] for s in summaries] == list(range(1, 13))
    assert summaries[-1]["count"] == {r["species"]: int(r["count"]) for r in rows if r["year"] == "12"}
    for year in (5, 12):
        table = run.snapshots[year]
        theirs = list(csv.DictReader(open(tmp_path / f"plants-{year}.csv")))
        assert len(table["id"]) == len(theirs) == sum(summaries[year - 1]["count"].values())
        mine = sorted(zip((f"{i:016x}" for i in table["id"]), table["species"]))
        assert mine == sorted((r["id"], r["species"]) for r in theirs)


def test_ecosystem_terrain_factors_are_arrays():
    eco = next(m for m in sylva.load(ex("ecosystem", "meadow.syl")) if m.kind == "ecosystem")
    t = eco.run(1, threads=1).terrain
    alt, slope = t["altitude"], t["slope"]
    assert alt.ndim == 2 and alt.shape == slope.shape and alt.dtype == np.float32
    assert (slope >= 0).all() and (slope < 90).all()
    # Horn's slope from the altitude grid by central differences, inside the border
    info = eco.run(1, threads=1).info
    gz, gx = np.gradient(alt.astype(np.float64), info["cell"])
    horn = np.degrees(np.arctan(np.hypot(gx, gz)))[2:-2, 2:-2]
    assert np.abs(horn - slope[2:-2, 2:-2]).mean() < 0.5


def test_plants_are_not_ecosystems():
    with pytest.raises(ValueError, match="not an ecosystem"):
        sylva.load(ex("abop", "fig1_24e_plant.syl")).model.run()

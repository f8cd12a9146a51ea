"""Python functions called from a rule's expressions (`extern` declarations, docs/python.md):
against closed forms and the `sylva` command's default bodies; and the other query modules
(?P ?H ?L ?U) under a Python environment, against the turtle's hand-derived frame."""
import os
import subprocess

import numpy as np
import pytest

import sylva

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("SYLVA", os.path.join(ROOT, "build", "sylva"))

AFFINE = """lsystem Affine {
  extern f(x)
  derive 10
  axiom A(0)
  A(x) -> A(f(x))
}
"""


@pytest.mark.parametrize("n", [0, 1, 7, 20])
def test_affine_map_is_its_closed_form(n):
    # x' = 2x + 1 from 0: x_n = 2^n - 1
    s = sylva.compile(AFFINE).model.derive(n, functions={"f": lambda x: 2 * x + 1})
    np.testing.assert_array_equal(s.params("A"), [[2.0 ** n - 1]])


def test_every_evaluation_calls_with_its_arguments():
    # B(k) -> B(k) B(k+1) doubles the Bs; each step g is called once per B with its k
    m = sylva.compile("""lsystem Calls {
  extern g(k, step)
  derive 4
  axiom B(0)
  B(k) -> B(g(k, 0)) B(k + 1)
}
""").model
    calls = []

    def g(k, zero):
        calls.append(k)
        assert isinstance(k, float) and zero == 0.0
        return k

    s = m.derive(functions={"g": g})
    assert len(s) == 16 and len(calls) == 1 + 2 + 4 + 8
    # B(k) keeps k, its sibling adds 1: after 4 steps the ks are the popcounts of 0..15
    np.testing.assert_array_equal(s.params("B")[:, 0], [bin(i).count("1") for i in range(16)])


def test_a_default_body_is_the_commands_and_a_binding_replaces_it(tmp_path):
    text = """fn sq(x) = x * x
extern dist(x, y) = sqrt(sq(x) + sq(y))
lsystem D {
  derive 3
  axiom P(3, 4)
  P(a, b) : dist(a, b) < 100 -> P(dist(a, b), b * 2)
}
"""
    path = tmp_path / "d.syl"
    path.write_text(text)
    m = sylva.load(path).model
    assert m.externs == {"dist": sylva.Extern("dist", 2, True)}
    cmd = subprocess.run([CLI, "derive", str(path)], capture_output=True, text=True, check=True).stdout
    assert m.derive().text.strip() == cmd.strip()
    # bound to the Manhattan distance: 3+4 = 7, 7+8 = 15, 15+16 = 31
    s = m.derive(functions={"dist": lambda x, y: abs(x) + abs(y)})
    np.testing.assert_array_equal(s.params("P"), [[31.0, 32.0]])


def test_conditions_call_it_too_and_build_uses_it():
    m = sylva.compile("""lsystem Grow {
  extern grows(i)
  derive 5
  axiom A(0)
  A(i) : grows(i) -> F(1) A(i + 1)
  A(i) -> A(i + 1)
}
""").model
    even = {"grows": lambda i: i % 2 == 0}
    s = m.derive(functions=even)
    assert s.counts()["F"] == 3  # i = 0, 2, 4
    plant = m.build(functions=even)
    assert plant.info["modules"] == len(s)


def test_errors_of_the_function_are_the_callers():
    m = sylva.compile(AFFINE).model
    with pytest.raises(ZeroDivisionError):
        m.derive(functions={"f": lambda x: 1 / (x - x)})
    with pytest.raises(TypeError, match="extern 'f' returned str"):
        m.derive(functions={"f": lambda x: "two"})
    with pytest.raises(TypeError):  # the wrong arity is Python's own TypeError
        m.derive(functions={"f": lambda x, y: x})
    with pytest.raises(sylva.CompileError, match="not a finite number"):
        m.derive(functions={"f": lambda x: float("nan")})
    # and a later call is clean again
    np.testing.assert_array_equal(m.derive(3, functions={"f": lambda x: x + 2}).params("A"), [[6.0]])


def test_bindings_are_checked():
    m = sylva.compile(AFFINE).model
    with pytest.raises(ValueError, match="no default"):
        m.derive()
    with pytest.raises(ValueError, match="declares no extern 'h'"):
        m.derive(functions={"f": abs, "h": abs})
    with pytest.raises(TypeError):
        m.derive(functions={"f": 3})
    with pytest.raises(TypeError):
        m.derive(functions=[abs])
    with pytest.raises(TypeError):
        m.derive(functions={1: abs})


# ---- ?P ?H ?L ?U under a Python environment ----

FRAME = """lsystem Frame {
  derive 1
  angle 90
  axiom F(2) ?P(0, 0, 0) ?H(0, 0, 0) +(90) F(3) ?P(0, 0, 0) ?H(0, 0, 0) ?L(0, 0, 0) ?U(0, 0, 0) ?E(2, 0)
}
"""


def test_turtle_queries_are_filled_under_a_python_environment(tmp_path):
    path = tmp_path / "frame.syl"
    path.write_text(FRAME)
    m = sylva.load(path).model
    seen = []

    def env(step, q):
        seen.append(q.positions.copy())
        q.params[:, 1] = 7

    s = m.derive(environment=env)
    cmd = subprocess.run([CLI, "derive", str(path)], capture_output=True, text=True, check=True).stdout
    by = {}
    for mod in s:
        by.setdefault(mod.name, []).append(np.array(mod.params))
    # F(2) up the y axis; + turns about U (toward L): then F(3) along the new heading
    np.testing.assert_allclose(by["?P"][0], [0, 2, 0], atol=1e-6)
    np.testing.assert_allclose(by["?H"][0], [0, 1, 0], atol=1e-6)
    h = by["?H"][1]
    np.testing.assert_allclose(np.abs(h), [1, 0, 0], atol=1e-6)  # horizontal after a quarter turn
    np.testing.assert_allclose(by["?P"][1], np.array([0, 2, 0]) + 3 * h, atol=1e-5)
    l_, u = by["?L"][0], by["?U"][0]
    np.testing.assert_allclose([h @ l_, h @ u, l_ @ u], [0, 0, 0], atol=1e-6)  # an orthonormal frame
    np.testing.assert_allclose(np.cross(h, l_), u, atol=1e-6)
    np.testing.assert_allclose(seen[0][0], by["?P"][1], atol=1e-5)  # the ?E stands where ?P says
    assert s[len(s) - 1] == sylva.Module("?E", (2.0, 7.0))
    # the turtle's answers are the command's (its ?E answer aside)
    assert s.text.split("?E")[0] == cmd.split("?E")[0]

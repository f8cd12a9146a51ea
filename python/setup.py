"""Build the sylva package: a CPython extension over libsylva (docs/python.md).

It links ../build/libsylva-nompi.a, the library without MPI (its objects are position-independent),
brought up to date here by `make python-lib`, so `pip install ./python` works from a fresh clone once
`make deps` has installed the Debian packages. Nothing is fetched from a package index."""
import os
import re
import runpy
import shutil
import subprocess

from setuptools import Extension, setup

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
LIB = os.path.join(ROOT, "build", "libsylva-nompi.a")


def pkg_config(flag):
    return subprocess.check_output(["pkg-config", flag, "cglm", "libpng", "libxml-2.0"], text=True).split()


def version():
    with open(os.path.join(ROOT, "include", "sylva", "sylva.h"), encoding="utf-8") as f:
        return re.search(r'#define SYLVA_VERSION "([^"]+)"', f.read()).group(1)


def copy_web():
    """The notebook view's assets (sylva/_view.py's SOURCES: web/scene.js, web/notebook.js and
    three.js, which `make deps` installs in web/node_modules) into the package, as sylva/_web."""
    sources = runpy.run_path(os.path.join(HERE, "sylva", "_view.py"))["SOURCES"]
    three = "node_modules/three/"
    files = list(sources.values()) + [three + "package.json", three + "LICENSE"]
    missing = [rel for rel in files if not os.path.exists(os.path.join(ROOT, "web", rel))]
    if missing:  # the package still works; notebooks then show pictures, not the 3D view
        print(f"sylva: no {missing[0]} in web/ (make deps installs three.js): the notebook view is left out")
        return []
    for rel in files:
        dst = os.path.join(HERE, "sylva", "_web", rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copyfile(os.path.join(ROOT, "web", rel), dst)
    return ["_web/" + rel for rel in files]


# make decides whether the library is up to date with its sources.
subprocess.check_call(["make", "-C", ROOT, "--no-print-directory", "python-lib"])

core = Extension(
    "sylva._core",
    sources=["sylva/_core.c"],
    include_dirs=[os.path.join(ROOT, "include")],
    extra_compile_args=["-std=c11", "-D_GNU_SOURCE", "-Wall", "-Wextra", "-Werror", "-Wno-missing-field-initializers",
                        "-Wno-cast-function-type", "-Wno-unused-parameter"],
    extra_objects=[LIB],
    extra_link_args=pkg_config("--libs") + ["-lembree3", "-lmeshoptimizer", "-lm", "-pthread"],
    depends=[LIB],
)

setup(
    name="sylva",
    version=version(),
    description="Plants from grammar files: L-systems, grown trees, Weber-Penn, strands, ecosystems",
    packages=["sylva"],
    package_data={"sylva": ["py.typed"] + copy_web()},
    ext_modules=[core],
    install_requires=["numpy"],
    python_requires=">=3.11",
)

#!/bin/sh
# Install the Debian packages Sylva needs, if any are missing (as root), or say how; then the
# glTF validator the tests use (npm ci from tests/gltf/package-lock.json). gdal-bin is the
# terrain tests' oracle (gdaldem); ffmpeg encodes `sylva animate`'s videos.
PKGS="flex bison pkg-config g++ libcglm-dev libembree-dev libxml2-dev libpng-dev libcmocka-dev libmeshoptimizer-dev clang libclang-rt-dev pngquant python3 gdal-bin ffmpeg libopenmpi-dev openmpi-bin"
# The Python package (docs/python.md): its build, a venv with Debian's numpy, pytest, and the
# notebooks executed by nbclient (matplotlib draws their plots).
PKGS="$PKGS python3-dev python3-venv python3-numpy python3-pytest python3-nbclient python3-nbformat python3-ipykernel python3-matplotlib"
# The Blender add-on's tests (docs/blender.md): Debian's Blender 3.4 runs the add-on headless.
# It is large (about 165 packages, 150 MB to download, 560 MB installed: 1-3 minutes of a
# fresh CI machine's apt time).
PKGS="$PKGS blender"
PKGS="$PKGS libmicrohttpd-dev"  # sylva view's web server (the CLI only)
# sylva view's browser tests (tests/run-view) and the notebook view's (tests/run-python, which
# writes the notebook's HTML with jupyter-nbconvert): Debian's chromium, headless.
PKGS="$PKGS chromium jupyter-nbconvert"
PKGS="$PKGS python3-ipywidgets"  # model.interact(): the parameters as sliders in a notebook (docs/python.md)
PKGS="$PKGS python3-pandas"  # the Python package's tables as DataFrames, against its record arrays (python/tests/test_tables.py)
# node and npm for the glTF validator, from Debian unless a node is installed already
# (one from elsewhere, such as NodeSource's, brings its own npm).
command -v node >/dev/null 2>&1 || PKGS="$PKGS nodejs npm"
PKGS="$PKGS strace"  # tests/cases/trust.test: a model, and libxml2, open no file they should not (traced)
PKGS="$PKGS python3-pil"  # tools/make-textures: the example bark and leaf images
PKGS="$PKGS lld"  # links the programs of a tree (the Makefile uses it when found): 2-3 times faster than GNU ld
# One dpkg-query for them all (one a package took about 1.5 s of CPU; make test asks twice).
installed=" "$(dpkg-query -W -f='${Package} ${Status}\n' $PKGS 2>/dev/null | awk '/ ok installed$/ {printf "%s ", $1}')
missing=""
for p in $PKGS; do
    case "$installed" in *" $p "*) ;; *) missing="$missing $p" ;; esac
done
gltf_validator() {
    [ -f tests/gltf/node_modules/gltf-validator/package.json ] && return 0
    command -v npm >/dev/null 2>&1 || return 0
    echo "sylva: installing the glTF validator into tests/gltf/node_modules (npm ci)"
    npm ci --prefix tests/gltf --no-audit --no-fund >/dev/null 2>&1 ||
        echo "sylva: npm ci --prefix tests/gltf failed; tests/run-gltf will try again" >&2
    return 0
}
# three.js for sylva view's page (web/), and puppeteer-core for its browser tests (tests/view/),
# from their package-lock.json files.
npm_folder() {
    [ -f "$1/node_modules/$2/package.json" ] && return 0
    command -v npm >/dev/null 2>&1 || return 0
    echo "sylva: installing $2 into $1/node_modules (npm ci)"
    npm ci --prefix "$1" --no-audit --no-fund >/dev/null 2>&1 ||
        echo "sylva: npm ci --prefix $1 failed" >&2
    return 0
}
npm_all() { gltf_validator; npm_folder web three; npm_folder tests/view puppeteer-core; }
cd "$(dirname "$0")/.." || exit 1
[ -z "$missing" ] && { npm_all; exit 0; }
if [ "$(id -u)" = 0 ]; then
    echo "sylva: installing$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q >/dev/null && apt-get install -y -q --no-install-recommends $missing >/dev/null || {
        echo "sylva: apt-get install failed for:$missing" >&2; exit 1; }
else
    echo "sylva: missing Debian packages; run as root:" >&2
    echo "  apt-get update && apt-get install -y$missing" >&2
    exit 1
fi
npm_all

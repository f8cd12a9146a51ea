#!/bin/sh
# Install the Debian packages Sylva needs, if any are missing (as root), or say how; then the
# glTF validator the tests use (npm ci from tests/gltf/package-lock.json). gdal-bin is the
# terrain tests' oracle (gdaldem); ffmpeg encodes `sylva animate`'s videos.
PKGS="flex bison pkg-config g++ libcglm-dev libembree-dev libxml2-dev libpng-dev libcmocka-dev libmeshoptimizer-dev clang libclang-rt-dev pngquant python3 gdal-bin ffmpeg libopenmpi-dev openmpi-bin"
# node and npm for the glTF validator, from Debian unless a node is installed already
# (one from elsewhere, such as NodeSource's, brings its own npm).
command -v node >/dev/null 2>&1 || PKGS="$PKGS nodejs npm"
PKGS="$PKGS strace"  # tests/cases/trust.test: a model, and libxml2, open no file they should not (traced)
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q "ok installed" || missing="$missing $p"
done
gltf_validator() {
    [ -f tests/gltf/node_modules/gltf-validator/package.json ] && return 0
    command -v npm >/dev/null 2>&1 || return 0
    echo "sylva: installing the glTF validator into tests/gltf/node_modules (npm ci)"
    npm ci --prefix tests/gltf --no-audit --no-fund >/dev/null 2>&1 ||
        echo "sylva: npm ci --prefix tests/gltf failed; tests/run-gltf will try again" >&2
    return 0
}
cd "$(dirname "$0")/.." || exit 1
[ -z "$missing" ] && { gltf_validator; exit 0; }
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
gltf_validator

#!/bin/sh
# Install the Debian packages Sylva needs, if any are missing (as root), or say how.
PKGS="flex bison pkg-config g++ libcglm-dev libembree-dev libxml2-dev libpng-dev libcmocka-dev clang libclang-rt-dev pngquant"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q "ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
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

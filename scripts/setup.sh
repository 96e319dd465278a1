#!/usr/bin/env bash
# Install what BirdsEye needs to run and to be tested, and nothing twice:
#   1. Debian packages (QGIS 3.22 and its Python bindings, Xvfb for the desktop test), only when one is
#      missing — `apt-get` runs only then, so a ready machine needs no root and no network;
#   2. .venv, made from Debian's /usr/bin/python3 with --system-site-packages (QGIS's bindings, GDAL
#      and pyproj come from Debian), and the pinned requirements, re-installed only when
#      requirements*.txt or constraints.txt change (their hash is kept in .venv/.requirements.sha256).
#   3. .venv-qt6, a plain venv with PyQt6 only (requirements-qt6.txt), in which `make lint` checks that
#      every Qt name the plugin spells exists in PyQt6 (QGIS 4) — this machine has no QGIS 4;
#   4. the link build/pluginpath/birdseye -> this tree, for QGIS_PLUGINPATH.
# Quiet when everything is already there. Called by `make setup`, `make test` and `make demo`.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"

debian_packages=(
    qgis python3-qgis qgis-providers  # QGIS 3.22 desktop, qgis_process and the Python bindings
    python3-venv python3-pyproj python3-numpy  # the venv's base; numpy 1.x that GDAL was built with
    xvfb xauth fonts-dejavu-core  # headless X server and a font for the desktop test
    proj-data gdal-bin  # PROJ's EGM96 geoid grid (heights); gdaltransform, PROJ's command line the height tests check against
    pyqt5-dev-tools qttools5-dev-tools  # pylupdate5 and lrelease for `make translations`
)
system_python=/usr/bin/python3
venv="${BIRDSEYE_VENV_DIR:-$repo/.venv}"
stamp="$venv/.requirements.sha256"
qt6_venv="${BIRDSEYE_QT6_VENV_DIR:-$repo/.venv-qt6}"
qt6_stamp="$qt6_venv/.requirements.sha256"
requirement_files=(requirements.txt requirements-test.txt requirements-dev.txt requirements-train.txt constraints.txt)

say() { echo "setup: $*"; }

missing_packages() {  # one dpkg-query for all of them: quick when nothing is missing
    local installed
    installed="$(dpkg-query -W -f='${Package} ${db:Status-Status}\n' "${debian_packages[@]}" 2>/dev/null || true)"
    local pkg
    for pkg in "${debian_packages[@]}"; do
        grep -qx "$pkg installed" <<<"$installed" || echo "$pkg"
    done
}

install_debian_packages() {
    local missing
    mapfile -t missing < <(missing_packages)
    ((${#missing[@]})) || return 0
    say "installing Debian packages: ${missing[*]}"
    local sudo=()
    if ((EUID != 0)); then
        command -v sudo >/dev/null || {
            echo "setup: run as root, or install: apt-get install --no-install-recommends ${missing[*]}" >&2
            exit 1
        }
        sudo=(sudo)
    fi
    "${sudo[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

python_version() { "$1" -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null; }

venv_is_usable() {  # exists, sees Debian's packages, and matches the Python QGIS embeds
    [[ -x "$venv/bin/python" ]] &&
        grep -qx 'include-system-site-packages = true' "$venv/pyvenv.cfg" 2>/dev/null &&
        [[ "$(python_version "$venv/bin/python")" == "$(python_version "$system_python")" ]]
}

make_venv() {
    venv_is_usable && return 0
    say "creating $venv from $system_python (with Debian's site packages)"
    rm -rf "$venv"
    "$system_python" -m venv --system-site-packages "$venv"
}

install_requirements() {
    local wanted
    wanted="$(cat "${requirement_files[@]}" | sha256sum | cut -d' ' -f1)"
    [[ -f "$stamp" && "$(cat "$stamp")" == "$wanted" ]] && return 0
    say "installing Python packages (requirements-dev.txt, requirements-train.txt, constraints.txt) into $venv"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
        -c constraints.txt -r requirements-dev.txt -r requirements-train.txt
    echo "$wanted" >"$stamp"
}

install_qt6_checker() {  # PyQt6 from PyPI, apart from QGIS's PyQt5 so neither sees the other
    local wanted
    wanted="$(sha256sum requirements-qt6.txt | cut -d' ' -f1)"
    [[ -f "$qt6_stamp" && "$(cat "$qt6_stamp")" == "$wanted" ]] && return 0
    say "creating $qt6_venv with PyQt6 (requirements-qt6.txt) for the Qt 6 check"
    rm -rf "$qt6_venv"
    "$system_python" -m venv "$qt6_venv"
    "$qt6_venv/bin/python" -m pip install --quiet --disable-pip-version-check -r requirements-qt6.txt
    echo "$wanted" >"$qt6_stamp"
}

link_plugin() {  # QGIS_PLUGINPATH=build/pluginpath finds this tree as the plugin "birdseye"
    mkdir -p build/pluginpath
    [[ -L build/pluginpath/birdseye ]] || ln -sfn "$repo" build/pluginpath/birdseye
}

install_debian_packages
make_venv
install_requirements
install_qt6_checker
link_plugin

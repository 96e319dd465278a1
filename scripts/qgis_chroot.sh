#!/usr/bin/env bash
# Run the QGIS test suites (or any command) on another Debian release's QGIS, in a chroot:
#
#   scripts/qgis_chroot.sh trixie                  # Debian 13, QGIS 3.40 LTR: make test-integration
#   scripts/qgis_chroot.sh sid                     # Debian unstable, the latest QGIS
#   scripts/qgis_chroot.sh trixie /opt/birdseye-venv/bin/pytest -q tests/gui/test_review_dock.py
#   scripts/qgis_chroot.sh trixie bash             # a shell there, in this working tree
#
# The host keeps running QGIS 3.22 (Debian 12); users run newer QGIS, Python and numpy, and a chroot
# is the cheapest way to run those on the same machine (root needed, no container runtime).
#   - build/chroots/<suite>: made once by debootstrap from the Debian archive this machine's apt
#     sources name (never a fixed host: CI machines use their own mirror), with QGIS installed; made
#     again when this script changes (it holds the package list);
#   - this working tree and ../shared (the tests read it) are bind-mounted at the same paths as on
#     the host, so build/pluginpath/birdseye and every absolute path the tests compute stay valid;
#   - the venv lives in the chroot (/opt/birdseye-venv), never in the tree: the host's .venv belongs to
#     the host's Python. It is refilled when requirements.txt or requirements-test.txt change; torch
#     and the lint tools stay out (the training and unit suites run on the host);
#   - pytest-qgis keeps its QGIS profile in the tree's .qgis-settings, which the host's runs use: the
#     chroot mounts one of its own there, so no QGIS reads settings another release wrote;
#   - every mount is undone on exit, and a lock serialises runs for the same suite.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
shared="$(cd "$repo/.." && pwd)/shared"
suite="${1:?usage: scripts/qgis_chroot.sh <debian suite, e.g. trixie or sid> [command ...]}"
shift
root="$repo/build/chroots/$suite"
stamp="$root/.birdseye-chroot.sha256"
venv=/opt/birdseye-venv
venv_stamp="$root$venv/.requirements.sha256"
requirement_files=(requirements.txt requirements-test.txt)

debian_packages=(
    qgis python3-qgis qgis-providers  # the desktop, qgis_process and the Python bindings
    python3-venv python3-pyproj python3-numpy  # the venv's base: QGIS's Python sees these too
    python3-pip  # what Install dependencies… runs in QGIS's own Python (tests/e2e/test_package.py)
    # QGIS's Python has scipy on Windows, macOS and Debian 13 (through python3-matplotlib), and the
    # package test's bare profile starts from that; Debian unstable's QGIS no longer pulls it in.
    python3-scipy
    xvfb xauth fonts-dejavu-core  # headless X server and a font for the desktop tests
    proj-data gdal-bin  # PROJ's EGM96 geoid grid (heights); gdaltransform, PROJ's command line the height tests check against
    pyqt5-dev-tools qttools5-dev-tools  # pylupdate5 and lrelease (tests/e2e/test_package.py)
    make ca-certificates  # the package test runs `make package`; pip needs the CA bundle
)

say() { echo "qgis_chroot[$suite]: $*" >&2; }

((EUID == 0)) || { say "needs root (debootstrap, chroot, mount)"; exit 1; }
[[ "$suite" =~ ^[a-z]+$ ]] || { say "'$suite' is not a Debian suite name"; exit 1; }

# The URI of the host's own Debian release in its apt sources (one-line or deb822 format).
debian_archive() {
    local codename
    codename="$(. /etc/os-release && echo "$VERSION_CODENAME")"
    shopt -s nullglob
    local lists=(/etc/apt/sources.list /etc/apt/sources.list.d/*.list) sources=(/etc/apt/sources.list.d/*.sources)
    shopt -u nullglob
    {
        ((${#lists[@]})) && awk -v c="$codename" '$1 == "deb" {
            n = 2; if ($2 ~ /^\[/) { while ($n !~ /\]$/) n++; n++ }
            if ($(n + 1) == c) print $n }' "${lists[@]}" 2>/dev/null
        ((${#sources[@]})) && awk -v c="$codename" '
            function flush() { if (uri != "" && (" " suites " ") ~ (" " c " ")) print uri; uri = ""; suites = "" }
            /^[ \t]*$/ { flush(); next }
            $1 == "URIs:" { uri = $2 }
            $1 == "Suites:" { $1 = ""; suites = $0 }
            END { flush() }' "${sources[@]}"
    } | head -n1
}

# Mount points inside the chroot, deepest first (a stale run's too, e.g. after kill -9).
mounts_inside() {
    awk -v r="$root/" 'index($2, r) == 1 { print $2 }' /proc/self/mounts | sort -r
}

unmount_all() {
    local point
    while read -r point; do
        [[ -n "$point" ]] || continue
        umount "$point" 2>/dev/null || umount -l "$point"
    done < <(mounts_inside)
}

mount_all() {
    mount -t proc proc "$root/proc"
    mount -t sysfs sys "$root/sys"
    mount --bind /dev "$root/dev"
    mount --bind /dev/pts "$root/dev/pts"
    mount -t tmpfs -o mode=1777 shm "$root/dev/shm"
    mkdir -p "$root$repo"
    mount --bind "$repo" "$root$repo"
    if [[ -d "$shared" ]]; then
        mkdir -p "$root$shared"
        mount --bind "$shared" "$root$shared"
    fi
    mkdir -p "$repo/.qgis-settings" "$root/var/lib/birdseye/qgis-settings"
    mount --bind "$root/var/lib/birdseye/qgis-settings" "$root$repo/.qgis-settings"
}

# The venv stays off PATH: QGIS's embedded Python looks for python3 on PATH to find its prefix, and
# would take the venv's packages for its own (the package test needs a bare QGIS Python). There is no
# display: without QT_QPA_PLATFORM, pytest-qgis's application aborts (the desktop tests start Xvfb).
in_chroot() {
    env -i HOME=/root LANG=C.UTF-8 PATH=/usr/sbin:/usr/bin:/sbin:/bin QT_QPA_PLATFORM=offscreen \
        DEBIAN_FRONTEND=noninteractive PIP_DISABLE_PIP_VERSION_CHECK=1 ${CI:+CI="$CI"} \
        ${TERM:+TERM="$TERM"} BIRDSEYE_VENV="$venv" chroot "$root" "$@"
}

build_chroot() {
    local archive wanted="$1"
    archive="${BIRDSEYE_DEBIAN_ARCHIVE:-$(debian_archive)}"
    [[ -n "$archive" ]] || { say "no Debian archive in /etc/apt/sources*; set BIRDSEYE_DEBIAN_ARCHIVE"; exit 1; }
    command -v debootstrap >/dev/null || {
        say "installing debootstrap"
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap
    }
    # rm -rf must never reach the working tree through a bind mount left by a killed run.
    [[ -z "$(mounts_inside)" ]] || { say "still mounted under $root:"; mounts_inside >&2; exit 1; }
    rm -rf --one-file-system "$root"
    mkdir -p "$root"
    local started=$SECONDS
    say "debootstrap $suite from $archive"
    debootstrap --variant=minbase "$suite" "$root" "$archive" >"$root.debootstrap.log" 2>&1 || {
        tail -n 30 "$root.debootstrap.log" >&2; exit 1
    }
    say "debootstrap took $((SECONDS - started)) s"
    echo "deb $archive $suite main" >"$root/etc/apt/sources.list"
    # A mirror frozen in time serves Release files past their Valid-Until (unstable's lasts a week).
    echo 'Acquire::Check-Valid-Until "false";' >"$root/etc/apt/apt.conf.d/99birdseye-frozen-archive"
    printf '#!/bin/sh\nexit 101\n' >"$root/usr/sbin/policy-rc.d"  # no daemons start inside
    chmod +x "$root/usr/sbin/policy-rc.d"
    # The host may reach the network through a proxy that signs with its own CA.
    if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
        mkdir -p "$root/usr/local/share/ca-certificates"
        cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
    fi
    started=$SECONDS
    mount_all
    in_chroot apt-get update -qq
    in_chroot apt-get install -y -qq --no-install-recommends "${debian_packages[@]}" >"$root.apt.log" 2>&1 || {
        tail -n 30 "$root.apt.log" >&2; exit 1
    }
    in_chroot update-ca-certificates >/dev/null
    in_chroot apt-get clean
    unmount_all
    say "installing QGIS took $((SECONDS - started)) s: $(in_chroot dpkg-query -W -f='${Package} ${Version}' qgis)"
    echo "$wanted" >"$stamp"
}

fill_venv() {
    local wanted
    wanted="$(cd "$repo" && cat "${requirement_files[@]}" | sha256sum | cut -d' ' -f1)"
    [[ -f "$venv_stamp" && "$(cat "$venv_stamp")" == "$wanted" ]] && return 0
    local started=$SECONDS
    say "installing requirements.txt and requirements-test.txt into $venv"
    in_chroot rm -rf "$venv"
    in_chroot /usr/bin/python3 -m venv --system-site-packages "$venv"
    in_chroot bash -c "cd '$repo' && $venv/bin/pip install --quiet --only-binary=:all: -r requirements-test.txt"
    echo "$wanted" >"$venv_stamp"
    say "the venv took $((SECONDS - started)) s"
}

main() {
    mkdir -p "$repo/build/chroots"
    exec 9>"$root.lock"
    flock 9
    unmount_all
    trap unmount_all EXIT
    trap 'exit 130' INT TERM

    local wanted_root
    wanted_root="$(sha256sum "${BASH_SOURCE[0]}" | cut -d' ' -f1)"
    [[ -f "$stamp" && "$(cat "$stamp")" == "$wanted_root" ]] || build_chroot "$wanted_root"
    mount_all
    fill_venv

    local command=("$@")
    ((${#command[@]})) || command=(make --no-print-directory test-integration VENV="$venv")
    in_chroot bash -c 'cd "$1" && shift && exec "$@"' bash "$repo" "${command[@]}"
}

# On one line with its exit: bash reads a script as it runs, and a run must not read an edited copy.
main "$@"; exit

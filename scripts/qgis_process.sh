#!/usr/bin/env bash
# Run QGIS's command-line Processing executor with the BirdsEye plugin loaded.
#
#   scripts/qgis_process.sh list                         # every algorithm, BirdsEye's under "birdseye"
#   scripts/qgis_process.sh help birdseye:simulatecampaign
#   scripts/qgis_process.sh run birdseye:simulatecampaign -- SEED=1 OUTPUT_FOLDER=/tmp/campaign
#
# qgis_process (QGIS 3.22) loads a Python plugin only when the plugin is on QGIS_PLUGINPATH *and*
# enabled in the active profile (QGIS3.ini, [PythonPlugins] birdseye=true). This wrapper
#   - points QGIS_PLUGINPATH at build/pluginpath, where birdseye -> this working tree (the same link
#     the tests use), or at $BIRDSEYE_PLUGIN_PATH when set (e.g. a folder holding an unzipped release);
#   - uses its own settings folder, build/qgis-process (or $BIRDSEYE_QGIS_CONFIG), through
#     QGIS_CUSTOM_CONFIG_PATH, so your desktop profile is never read or changed, and enables the
#     plugin in that folder's default profile;
#   - calls /usr/bin/qgis_process.bin directly: Debian's /usr/bin/qgis_process wrapper may add
#     options from /etc/default/qgis that this version rejects;
#   - puts the venv's packages (.venv, or $BIRDSEYE_VENV; set it empty for none) on PYTHONPATH: QGIS
#     embeds Debian's python3, which lacks the pip-installed packages some algorithms need;
#   - runs headless (QT_QPA_PLATFORM=offscreen).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
qgis_process_bin="${QGIS_PROCESS_BIN:-/usr/bin/qgis_process.bin}"

if [[ -n "${BIRDSEYE_PLUGIN_PATH:-}" ]]; then
    plugin_path="$BIRDSEYE_PLUGIN_PATH"
else
    plugin_path="$repo/build/pluginpath"
    mkdir -p "$plugin_path"
    [[ -L "$plugin_path/birdseye" ]] || ln -sfn "$repo" "$plugin_path/birdseye"
fi
config_dir="${BIRDSEYE_QGIS_CONFIG:-$repo/build/qgis-process}"
ini="$config_dir/profiles/default/QGIS/QGIS3.ini"

# Enable the plugin in the profile, keeping whatever else QGIS wrote there.
mkdir -p "$(dirname "$ini")"
if [[ ! -f "$ini" ]]; then
    printf '[PythonPlugins]\nbirdseye=true\n' >"$ini"
elif ! grep -qx 'birdseye=true' "$ini"; then
    if grep -q '^birdseye=' "$ini"; then
        sed -i 's/^birdseye=.*/birdseye=true/' "$ini"
    elif grep -qx '\[PythonPlugins\]' "$ini"; then
        sed -i '/^\[PythonPlugins\]$/a birdseye=true' "$ini"
    else
        printf '\n[PythonPlugins]\nbirdseye=true\n' >>"$ini"
    fi
fi

if [[ ! -x "$qgis_process_bin" ]]; then
    echo "qgis_process.sh: $qgis_process_bin not found; run 'make setup' (installs Debian's qgis)." >&2
    exit 127
fi

venv="${BIRDSEYE_VENV-$repo/.venv}"
if [[ -n "$venv" ]]; then
    for site_packages in "$venv"/lib/python3*/site-packages; do
        if [[ -d "$site_packages" ]]; then
            export PYTHONPATH="$site_packages${PYTHONPATH:+:$PYTHONPATH}"
        fi
    done
fi
export QGIS_PLUGINPATH="$plugin_path${QGIS_PLUGINPATH:+:$QGIS_PLUGINPATH}"
export QGIS_CUSTOM_CONFIG_PATH="$config_dir"
export QT_QPA_PLATFORM=offscreen
if [[ -z "${XDG_RUNTIME_DIR:-}" ]]; then  # silences Qt's "XDG_RUNTIME_DIR not set" warning
    export XDG_RUNTIME_DIR="$config_dir/runtime"
    mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
fi
exec "$qgis_process_bin" "$@"

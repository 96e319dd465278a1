#!/usr/bin/env bash
# Refresh tests/data/deepness: the files of the Deepness QGIS plugin (Apache-2.0) that
# tests/unit/detect/test_deepness_interop.py imports, copied unchanged from a Deepness checkout at one
# commit, with Deepness's LICENSE and a SOURCE.md listing each file's git blob id (the test checks them).
#   scripts/deepness_snapshot.sh /path/to/qgis-plugin-deepness [commit]
# (git clone https://github.com/PUTvision/qgis-plugin-deepness first; CI never fetches it.)
set -euo pipefail
src="$(cd "$1" && pwd)"
commit="$(git -C "$src" rev-parse "${2:-HEAD}")"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/tests/data/deepness"
files=(
    src/deepness/__init__.py
    src/deepness/common/__init__.py
    src/deepness/common/lazy_package_loader.py
    src/deepness/common/processing_parameters/__init__.py
    src/deepness/common/processing_parameters/standardization_parameters.py
    src/deepness/processing/__init__.py
    src/deepness/processing/models/__init__.py
    src/deepness/processing/models/model_base.py
    src/deepness/processing/models/preprocessing_utils.py
    src/deepness/processing/models/regressor.py
    src/deepness/processing/models/segmentor.py
)
rm -rf "$out"
mkdir -p "$out"
git -C "$src" show "$commit:LICENSE" > "$out/LICENSE"
{
    echo "# Deepness files used by the interoperability test"
    echo
    echo "Test data, not code the plugin runs: unchanged copies of the files of the Deepness QGIS plugin"
    echo "(https://github.com/PUTvision/qgis-plugin-deepness, Apache License 2.0, see LICENSE here) that"
    echo "\`tests/unit/detect/test_deepness_interop.py\` imports, so that test checks BirdsEye's models against"
    echo "Deepness's own model classes where only package registries are reachable (CI). Refresh with"
    echo "\`scripts/deepness_snapshot.sh\`; run the test against another checkout with \`DEEPNESS_SRC=<checkout>\`."
    echo
    echo "commit: $commit ($(git -C "$src" log -1 --format=%cs "$commit"))"
    echo
    echo "| git blob id | file |"
    echo "|---|---|"
    for f in "${files[@]}"; do
        mkdir -p "$out/$(dirname "$f")"
        git -C "$src" show "$commit:$f" > "$out/$f"
        echo "| $(git -C "$src" rev-parse "$commit:$f") | $f |"
    done
} > "$out/SOURCE.md"
echo "tests/data/deepness: ${#files[@]} files from $commit"

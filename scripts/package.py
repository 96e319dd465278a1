"""Build the plugin zip a user installs with QGIS's "Install from ZIP", build/birdseye.<version>.zip, and
the plugin repository file beside it, build/plugins.xml, that a user adds in QGIS's Plugin Manager.

The zip holds one top folder, ``birdseye/`` (the name QGIS installs the plugin under), with only what
the plugin needs at run time: the files and folders in :data:`INCLUDED` (the bundled ONNX model and
the ranges of ``requirements.txt`` included) and the compiled translations ``i18n/*.qm``. Tests,
benchmarks, scripts, the venv, build output, caches and hidden files stay out. The zip is then checked
as plugins.qgis.org's upload validator checks it (:func:`repository_problems`); any problem fails the
build.

``plugins.xml`` describes the zip in the format QGIS's plugin installer reads from a plugin repository
(``python/pyplugin_installer/installer_data.py``, ``Repositories.xmlDownloaded``; the elements
plugins.qgis.org writes): one ``<pyqgis_plugin name=… version=…>`` whose elements come from
metadata.txt, ``file_name`` the zip's name and ``download_url`` where the zip is fetched from:
``--base-url`` + the zip's name, or, without it, the zip's own ``file://`` URL (a repository on this
machine or a shared folder mounted at the same path). QGIS takes the plugin's id from ``file_name``, up
to the first dot, which is why the zip is named ``birdseye.<version>.zip`` (plugins.qgis.org's own
naming), not ``birdseye-<version>.zip``. The file is checked against metadata.txt and the zip
(:func:`repository_file_problems`). Runs with Debian's python3 (no QGIS needed).

    /usr/bin/python3 scripts/package.py [--out build] [--base-url https://example.org/qgis/]
"""
from __future__ import annotations

import argparse
import configparser
import io
import os
import re
import sys
import xml.etree.ElementTree as ET
import zipfile
from datetime import datetime, timezone
from pathlib import Path
from urllib.parse import urljoin, urlparse

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_FOLDER = "birdseye"
REPOSITORY_FILE = "plugins.xml"
# requirements.txt: the ranges BirdsEye › Install dependencies… installs from (birdseye_qgis/dependencies.py)
INCLUDED = ["__init__.py", "metadata.txt", "LICENSE", "README.md", "requirements.txt",
            "birdseye_qgis", "processing", "models", "resources"]
INCLUDED_PATTERNS = ["i18n/*.qm"]  # translations the plugin loads; the .ts sources stay in the repository
EXCLUDED_DIR_NAMES = {"__pycache__", ".pytest_cache", ".hypothesis", ".mypy_cache", ".ruff_cache"}
EXCLUDED_SUFFIXES = {".pyc", ".pyo", ".orig", ".rej", ".swp"}

# plugins.qgis.org's upload validator (QGIS-Django, plugins/validator.py): its size limit, the metadata
# it requires, the folders it refuses anywhere in the zip.
MAX_UPLOAD_BYTES = 25_000_000
REQUIRED_METADATA = ("name", "description", "version", "qgisMinimumVersion", "author", "email", "about",
                     "tracker", "repository")
URL_METADATA = ("tracker", "repository", "homepage")
FORBIDDEN_DIRS = ("__MACOSX", ".git", "__pycache__")


def read_metadata(text: str) -> configparser.SectionProxy:
    """The ``[general]`` section of a metadata.txt, keys case-sensitive (``qgisMinimumVersion``)."""
    parser = configparser.ConfigParser(interpolation=None)
    parser.optionxform = str
    parser.read_string(text)
    return parser["general"]


def plugin_metadata(root: Path = REPO_ROOT) -> configparser.SectionProxy:
    return read_metadata((root / "metadata.txt").read_text(encoding="utf-8"))


def plugin_version(root: Path = REPO_ROOT) -> str:
    return plugin_metadata(root)["version"]


def archive_name(version: str) -> str:
    """``birdseye.<version>.zip``: QGIS's installer takes a repository plugin's id from its file name up to
    the first dot, so the name must start with the plugin folder and a dot."""
    return f"{PLUGIN_FOLDER}.{version}.zip"


def packaged_files(root: Path = REPO_ROOT) -> list[Path]:
    """Every file the zip holds, relative to ``root``, sorted."""
    files = []
    for name in INCLUDED:
        path = root / name
        if not path.exists():
            sys.exit(f"package: {path} is missing")
        candidates = [path] if path.is_file() else sorted(p for p in path.rglob("*") if p.is_file())
        for candidate in candidates:
            relative = candidate.relative_to(root)
            if any(part.startswith(".") or part in EXCLUDED_DIR_NAMES for part in relative.parts):
                continue
            if candidate.suffix in EXCLUDED_SUFFIXES:
                continue
            files.append(relative)
    for pattern in INCLUDED_PATTERNS:
        files += [p.relative_to(root) for p in root.glob(pattern) if p.is_file()]
    return sorted(files)


def build(out_dir: Path, root: Path = REPO_ROOT) -> Path:
    out_dir.mkdir(parents=True, exist_ok=True)
    archive = out_dir / archive_name(plugin_version(root))
    tmp = archive.with_suffix(".zip.part")
    with zipfile.ZipFile(tmp, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for relative in packaged_files(root):
            zf.write(root / relative, f"{PLUGIN_FOLDER}/{relative.as_posix()}")
    tmp.replace(archive)  # never leave a half-written zip under the final name
    return archive


def repository_problems(archive: Path, new_plugin: bool = True) -> list[str]:
    """What plugins.qgis.org's upload validator would refuse in ``archive`` (empty: it passes).

    The same checks, in the same terms: size, member paths, forbidden folders and .pyc files, a sound
    zip, one top folder with a valid (PEP 8 for a new plugin) name holding ``__init__.py``,
    ``metadata.txt`` with a ``[general]`` section and every required key, the icon it names, a
    LICENSE, an author without slashes and well-formed tracker/repository/homepage URLs (the site
    also fetches those URLs; that needs the network and is left to the upload) — and one trap of
    QGIS's own installer, an empty ``plugin_dependencies``.
    """
    problems = []
    size = archive.stat().st_size
    if size > MAX_UPLOAD_BYTES:
        problems.append(f"the zip is {size / 1e6:.1f} MB; plugins.qgis.org accepts at most "
                        f"{MAX_UPLOAD_BYTES / 1e6:g} MB")
    try:
        zf = zipfile.ZipFile(archive)
    except zipfile.BadZipFile:
        return problems + ["the file cannot be unzipped"]
    with zf:
        names = zf.namelist()
        for name in names:
            parts = name.split("/")
            if ".." in name or name.startswith("/"):
                problems.append(f"{name}: member paths must not contain '..' or start with '/'")
            if ".pyc" in name:
                problems.append(f"{name}: .pyc files are refused")
            for forbidden in FORBIDDEN_DIRS:
                if forbidden in parts[:-1] or (forbidden == parts[-1] and name.endswith("/")):
                    problems.append(f"{name}: a '{forbidden}' folder is refused")
        bad = zf.testzip()
        if bad:
            problems.append(f"{bad}: bad CRC, the zip is damaged")
        tops = sorted({name.split("/")[0] for name in names})
        if not names or "/" not in names[0]:
            return problems + ["the zip holds no top folder (it must hold <plugin folder>/__init__.py …)"]
        if len(tops) > 1:
            problems.append(f"the zip holds several top folders ({', '.join(tops)}); it must hold exactly one")
        package = names[0].split("/")[0]
        if new_plugin and not re.match(r"^[a-z_][a-z0-9_]*$", package):
            problems.append(f"top folder '{package}': a new plugin's folder must be PEP 8 (lowercase, digits, _)")
        if not re.match(r"^[A-Za-z][A-Za-z0-9-_]+$", package):
            problems.append(f"top folder '{package}': only ASCII letters, digits, '-' and '_', starting with a letter")
        for required in ("__init__.py", "metadata.txt", "LICENSE"):
            if f"{package}/{required}" not in names:
                problems.append(f"{package}/{required} is missing")
        if f"{package}/metadata.txt" not in names:
            return problems
        parser = configparser.ConfigParser(interpolation=None)
        parser.optionxform = str  # keys are case-sensitive (qgisMinimumVersion)
        try:
            parser.read_file(io.StringIO(zf.read(f"{package}/metadata.txt").decode("utf-8")))
        except (configparser.Error, UnicodeDecodeError) as exc:
            return problems + [f"metadata.txt cannot be parsed: {exc}"]
        if not parser.has_section("general"):
            return problems + ["metadata.txt has no [general] section"]
        general = parser["general"]
        missing = [key for key in REQUIRED_METADATA if not general.get(key, "").strip()]
        if missing:
            problems.append(f"metadata.txt lacks {', '.join(missing)}")
        icon = general.get("icon", "").strip()
        if icon and f"{package}/{icon.removeprefix('./')}" not in names:
            problems.append(f"metadata.txt names the icon {icon}, which is not in the zip")
        if "/" in general.get("author", ""):
            problems.append("metadata.txt: the author must not contain '/'")
        if "plugin_dependencies" in general and not general["plugin_dependencies"].strip():
            # Not the site's rule but QGIS's installer: it splits the empty value into one dependency
            # named "" and greets every Install from ZIP with a dialog asking to install it.
            problems.append("metadata.txt: plugin_dependencies is empty; leave the key out")
        for key in URL_METADATA:
            url = general.get(key, "").strip()
            if key in REQUIRED_METADATA or url:
                parsed = urlparse(url)
                if not (parsed.scheme and parsed.netloc):
                    problems.append(f"metadata.txt: {key} = '{url}' is not a URL")
    return problems


def download_url(archive: Path, base_url: str | None = None) -> str:
    """Where plugins.xml says the zip is: ``base_url`` + its name, else its own ``file://`` URL."""
    if not base_url:
        return archive.resolve().as_uri()
    return urljoin(base_url if base_url.endswith("/") else base_url + "/", archive.name)


def _flag(value: str) -> str:
    return "True" if value.strip().lower() in ("true", "yes", "1") else "False"


def plugins_xml(archive: Path, url: str, now: datetime | None = None) -> str:
    """The plugin repository file for ``archive``, from the metadata.txt inside it.

    The elements and their spelling are those QGIS's installer reads (``installer_data.py``:
    ``pyqgis_plugin`` with the attributes ``name`` and ``version``; ``file_name``, ``download_url``,
    ``qgis_minimum_version``, ``qgis_maximum_version``, ``experimental``, ``deprecated``, ``description``,
    ``about``, ``author_name``, ``author_email``, ``homepage``, ``tracker``, ``repository``, ``tags``,
    ``category``, ``changelog``, ``create_date``, ``update_date``), in the order plugins.qgis.org writes
    them; ``uploaded_by``, ``server`` and ``supports_qt6`` are written for people and other tools (QGIS
    3.22–3.40 do not read them). ``now`` (UTC) dates the file; default: ``SOURCE_DATE_EPOCH`` if set,
    else the current time.
    """
    with zipfile.ZipFile(archive) as zf:
        general = read_metadata(zf.read(f"{PLUGIN_FOLDER}/metadata.txt").decode("utf-8"))
    if now is None:
        epoch = os.environ.get("SOURCE_DATE_EPOCH")
        now = datetime.fromtimestamp(int(epoch), timezone.utc) if epoch else datetime.now(timezone.utc)
    stamp = now.replace(microsecond=0).isoformat()
    minimum = general["qgisMinimumVersion"].strip()
    root = ET.Element("plugins")
    plugin = ET.SubElement(root, "pyqgis_plugin", name=general["name"].strip(), version=general["version"].strip())
    fields = [
        ("description", general.get("description", "")),
        ("about", general.get("about", "")),
        ("version", general["version"]),
        ("trusted", "False"),
        ("qgis_minimum_version", minimum),
        # QGIS's own default for a missing maximum: the minimum's major version .99
        ("qgis_maximum_version", general.get("qgisMaximumVersion", "").strip() or f"{minimum.split('.')[0]}.99"),
        ("homepage", general.get("homepage", "")),
        ("file_name", archive.name),
        ("icon", ""),  # a relative path would be taken from the web server's root: the installed plugin's icon is used
        ("author_name", general.get("author", "")),
        ("author_email", general.get("email", "")),
        ("download_url", url),
        ("uploaded_by", general.get("author", "")),
        ("create_date", stamp),
        ("update_date", stamp),
        ("experimental", _flag(general.get("experimental", "False"))),
        ("deprecated", _flag(general.get("deprecated", "False"))),
        ("tracker", general.get("tracker", "")),
        ("repository", general.get("repository", "")),
        ("tags", general.get("tags", "")),
        ("category", general.get("category", "")),
        ("changelog", general.get("changelog", "")),
        ("server", _flag(general.get("server", "False"))),
        ("supports_qt6", _flag(general.get("supportsQt6", "False"))),
    ]
    for tag, text in fields:
        ET.SubElement(plugin, tag).text = text.strip()
    ET.indent(root)
    return "<?xml version='1.0' encoding='UTF-8'?>\n" + ET.tostring(root, encoding="unicode") + "\n"


def write_repository_file(archive: Path, base_url: str | None = None) -> Path:
    """``plugins.xml`` beside ``archive`` (written under a temporary name, then renamed)."""
    path = archive.parent / REPOSITORY_FILE
    tmp = path.with_suffix(".xml.part")
    tmp.write_text(plugins_xml(archive, download_url(archive, base_url)), encoding="utf-8")
    tmp.replace(path)
    return path


def repository_file_problems(path: Path, archive: Path) -> list[str]:
    """Where ``plugins.xml`` disagrees with the zip it describes (empty: it matches): one plugin, named and
    versioned as the zip's metadata.txt, with its QGIS range, the zip's file name, an id (the file name up
    to the first dot, as QGIS's installer takes it) equal to the zip's top folder, and a download URL that
    ends with the zip's name."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        return [f"{path.name} is not well-formed XML: {exc}"]
    plugins = root.findall("pyqgis_plugin")
    if root.tag != "plugins" or len(plugins) != 1:
        return [f"{path.name} must hold <plugins> with exactly one <pyqgis_plugin>"]
    plugin = plugins[0]
    with zipfile.ZipFile(archive) as zf:
        general = read_metadata(zf.read(f"{PLUGIN_FOLDER}/metadata.txt").decode("utf-8"))
        top = zf.namelist()[0].split("/")[0]
    expected = {"@name": general["name"], "@version": general["version"], "version": general["version"],
                "qgis_minimum_version": general["qgisMinimumVersion"],
                "qgis_maximum_version": general.get("qgisMaximumVersion", ""),
                "experimental": _flag(general.get("experimental", "False")), "file_name": archive.name}
    problems = []
    for key, want in expected.items():
        got = plugin.get(key[1:]) if key.startswith("@") else plugin.findtext(key)
        if (got or "").strip() != want.strip():
            problems.append(f"{path.name}: {key.lstrip('@')} is '{got}', the zip says '{want.strip()}'")
    file_name = (plugin.findtext("file_name") or "").strip()
    if file_name.partition(".")[0] != top:
        problems.append(f"{path.name}: QGIS would install '{file_name}' as plugin '{file_name.partition('.')[0]}', "
                        f"but the zip's folder is '{top}'")
    url = (plugin.findtext("download_url") or "").strip()
    if not url.split("?")[0].endswith("/" + archive.name) or not urlparse(url).scheme:
        problems.append(f"{path.name}: download_url '{url}' is not a full URL of {archive.name}")
    return problems


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO_ROOT / "build", help="output folder")
    parser.add_argument("--base-url", default=os.environ.get("PLUGIN_BASE_URL") or None,
                        help="the web (or file://) folder the zip will be served from, for plugins.xml's "
                             "download_url (default: $PLUGIN_BASE_URL, else the output folder as a file:// URL)")
    args = parser.parse_args()
    archive = build(args.out)
    with zipfile.ZipFile(archive) as zf:
        count = len(zf.namelist())
    print(f"{archive} ({count} files, {archive.stat().st_size / 1e6:.1f} MB of plugins.qgis.org's "
          f"{MAX_UPLOAD_BYTES / 1e6:g} MB)")
    problems = repository_problems(archive)
    if problems:
        sys.exit("package: plugins.qgis.org would refuse it:\n  - " + "\n  - ".join(problems))
    print("package: passes plugins.qgis.org's upload checks (size, paths, folders, metadata, icon, LICENSE)")
    repository = write_repository_file(archive, args.base_url)
    problems = repository_file_problems(repository, archive)
    if problems:
        sys.exit("package: the plugin repository file does not match the zip:\n  - " + "\n  - ".join(problems))
    url = ET.parse(repository).getroot().findtext("pyqgis_plugin/download_url")
    print(f"{repository}: plugin repository file, download_url {url}")


if __name__ == "__main__":
    main()

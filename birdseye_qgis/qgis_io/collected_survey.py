"""A field survey package as QField leaves it (docs/design.md#geotags): its GeoPackage, metadata, geotag and
visit layers, and the visits' decisions appended to the review's verdict log.

The package's contract (table and field names) is ``core/field/field_survey.py``; the rules that read its
geotags are those of any point layer (``core/field/geotags.layer_fields``), and its decisions are planned by
``core/review/field_decisions.py``.
"""
from __future__ import annotations

import sqlite3
from dataclasses import dataclass
from pathlib import Path

from qgis.core import QgsVectorLayer

from ..core.errors import InputError
from ..core.field.field_survey import GEOTAG_TABLE, META_REVIEW_LOG, META_TABLE, PACKAGE_GPKG, VISIT_TABLE
from ..core.review.actions import ACTION_VERDICT
from ..core.review.field_decisions import FieldDecisions, Visit, plan_field_decisions, read_visits
from . import layers
from .review_store import RowMeta, VerdictStore

#: The package's project files: the GeoPackage read is the one beside them.
PROJECT_SUFFIXES = (".qgz", ".qgs")
#: The visit table's fields a decision needs.
VISIT_FIELDS = ("visit_id", "unit_keys", "decision", "worker")


def package_geopackage(path) -> Path | None:
    """The GeoPackage to read for a file given as a field survey: a ``.gpkg`` itself, a package's project
    (``.qgz``, ``.qgs``) the :data:`PACKAGE_GPKG` beside it; None for any other file."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".gpkg":
        return path
    return path.with_name(PACKAGE_GPKG) if suffix in PROJECT_SUFFIXES else None


@dataclass(frozen=True)
class CollectedSurvey:
    """A field package's GeoPackage: its path, tables and metadata (``META_TABLE``'s key → value)."""

    gpkg: Path
    tables: tuple
    meta: dict

    def layer(self, table: str) -> QgsVectorLayer:
        """The package's table ``table`` as an OGR layer, named ``<GeoPackage file>|<table>``; refused when it
        cannot be opened."""
        layer = QgsVectorLayer(f"{self.gpkg}|layername={table}", f"{self.gpkg.name}|{table}", "ogr")
        if not layer.isValid():
            raise InputError("cannot be opened as a layer", source=layer.name())
        return layer

    @property
    def review_log(self) -> Path | None:
        """The verdict GeoPackage the visits came from (``META_REVIEW_LOG``; a relative path is taken from the
        package's folder), None when the package names none."""
        value = (self.meta.get(META_REVIEW_LOG) or "").strip()
        if not value:
            return None
        path = Path(value)
        return path if path.is_absolute() else self.gpkg.parent / path


def open_collected_survey(path) -> CollectedSurvey:
    """The field package whose GeoPackage is ``path`` (see :func:`package_geopackage`). A missing file, a file
    that is no GeoPackage, or a GeoPackage without the package's geotag and metadata tables is refused, naming
    the tables it has."""
    gpkg = Path(path)
    if not gpkg.is_file():
        raise InputError(f"not found: a field survey package keeps its data in {PACKAGE_GPKG} beside its project",
                         source=str(gpkg))
    try:
        # Read-only: the survey is the field worker's record, never changed by importing it.
        connection = sqlite3.connect(f"{gpkg.resolve().as_uri()}?mode=ro", uri=True)
        try:
            tables = tuple(r[0] for r in connection.execute("SELECT table_name FROM gpkg_contents ORDER BY table_name"))
            meta = ({str(k): "" if v is None else str(v) for k, v in
                     connection.execute(f'SELECT key, value FROM "{META_TABLE}"')} if META_TABLE in tables else {})
        finally:
            connection.close()
    except sqlite3.DatabaseError as exc:
        raise InputError(f"is not a GeoPackage ({exc}); give the field survey package's {PACKAGE_GPKG}, or a "
                         "geotag CSV or NMEA log", source=str(gpkg)) from exc
    missing = [t for t in (GEOTAG_TABLE, META_TABLE) if t not in tables]
    if missing:
        raise InputError(f"is a GeoPackage but not a BirdsEye field survey package: it has no table "
                         f"{' or '.join(repr(t) for t in missing)} (its tables: {', '.join(tables) or 'none'}); load "
                         "a table of it as a point layer and give it as the input layer instead", source=str(gpkg))
    return CollectedSurvey(gpkg, tables, meta)


def read_package_visits(survey: CollectedSurvey, transform_context=None) -> tuple[list[Visit], list[InputError]]:
    """The package's visits (``VISIT_TABLE``; none when the package has no such table) and the rows left out
    (:func:`core.review.field_decisions.read_visits`)."""
    if VISIT_TABLE not in survey.tables:
        return [], []
    layer = survey.layer(VISIT_TABLE)
    source = layer.name()
    names = layer.fields().names()
    wanted = [n for n in VISIT_FIELDS if n in names]
    cols = layers.read_point_layer(layer, transform_context, wanted, source)
    values = cols["attributes"]
    records = [{"row": int(row), "lat": lat, "lon": lon, **{n: values[n][i] for n in wanted}}
               for i, (row, lat, lon) in enumerate(zip(cols["row"], cols["lat"].tolist(), cols["lon"].tolist()))]
    return read_visits(records, source)


def append_field_decisions(log_path, visits) -> tuple[FieldDecisions, list[dict]]:
    """Append the decisions of ``visits`` to the verdict log in the GeoPackage ``log_path`` (which must exist) as
    :func:`core.review.field_decisions.plan_field_decisions` plans them, in one transaction: one action of the
    log, each row with its own reviewer and metadata. Returns the plan and the rows as stored."""
    store = VerdictStore(log_path, create=False)
    try:
        plan = plan_field_decisions(visits, store.rows())
        stored = store.append([v.row for v in plan.verdicts], ACTION_VERDICT,
                              [RowMeta(v.reviewer, v.input_digests, v.matching_parameters, v.postprocessing)
                               for v in plan.verdicts])
    finally:
        store.close()
    return plan, stored

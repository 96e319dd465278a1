"""The field survey package: what BirdsEye hands to QField and what it reads back (docs/design.md#field-survey).

A package is a folder QField opens (QFieldSync's "package for QField" layout): ``<name>.qgz`` and one
GeoPackage, :data:`PACKAGE_GPKG`, holding

* :data:`GEOTAG_TABLE` — the points the field worker records. ``label`` is a value map of the user's
  classes; the GNSS fields (:data:`GNSS_FIELDS`) take QField's position variables as default values, so
  QField fills them at capture from the receiver (external RTK over Bluetooth/NTRIP or the device's own);
  the accuracy requirement is a constraint on them (:func:`accuracy_requirement_expression`).
* :data:`VISIT_TABLE` — points to visit (a review's unresolved clusters, or any point layer): what the
  worker decides there (:data:`DECISIONS`), with the same GNSS fields, and the review units it settles.
* :data:`SURVEYED_TABLE` — geotags surveyed before, read-only, so the worker sees what is already recorded
  without their records mixing with the new ones Import geotags reads from :data:`GEOTAG_TABLE`.
* :data:`AREA_TABLE` — the field's boundary or its partitions; :data:`FOOTPRINT_TABLE` — frame footprints
  as an offline background when there is no orthomosaic (an orthomosaic is copied into the folder).
* :data:`META_TABLE` — key/value text: the package's classes, label radius, accuracy requirement, height
  reference and the review log it came from.

The height QField stores is whatever the receiver reports after QField's own corrections (its "use
orthometric altitude from device" and vertical grid shift settings), which no position variable reveals.
So the package names the height field by the reference the user declares for the receiver
(:data:`HEIGHT_FIELDS`): ``h_ellipsoid`` or ``h_msl``, and Import geotags reads it by that name.

This module holds only the contract (names, expressions, the reading of QField's words); writing the
package is ``qgis_io/field_package.py`` and reading it back is ``importgeotags``.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from ..scoring.verdicts import CONFIRMED, HARD_NEGATIVE, UNCERTAIN

#: The package's GeoPackage and its tables.
PACKAGE_GPKG = "birdseye_survey.gpkg"
GEOTAG_TABLE = "geotags"
VISIT_TABLE = "visits"
AREA_TABLE = "survey_area"
FOOTPRINT_TABLE = "frame_footprints"
SURVEYED_TABLE = "surveyed_before"
META_TABLE = "birdseye_package"

#: Package metadata keys (META_TABLE rows).
META_CLASSES = "classes"                  # JSON list of class names
META_LABEL_RADIUS_M = "label_radius_m"
META_MAX_H_ACC_M = "max_h_accuracy_m"
META_REQUIRE_FIXED = "require_rtk_fixed"  # "1" / "0"
META_HEIGHT_REFERENCE = "height_reference"
META_REVIEW_LOG = "review_log"            # the verdict GeoPackage the visits came from ("" when none)
META_CREATED_UTC = "created_utc"

#: Height references the user can declare for the receiver's altitude, and the field each fills.
HEIGHT_ELLIPSOIDAL, HEIGHT_ORTHOMETRIC = "ellipsoidal", "orthometric"
HEIGHT_FIELDS = {HEIGHT_ELLIPSOIDAL: "h_ellipsoid", HEIGHT_ORTHOMETRIC: "h_msl"}
#: QField's altitude: the Z of ``@position_coordinate`` (WGS84 lon, lat, altitude as QField corrected it).
ALTITUDE_EXPRESSION = "z(@position_coordinate)"


@dataclass(frozen=True)
class GnssField:
    """A field QField fills from the receiver: name, QGIS type (``double``, ``int``, ``text``,
    ``datetime``), default-value expression (applied on insert only) and alias shown in the form."""

    name: str
    kind: str
    expression: str
    alias: str


#: The GNSS fields of the geotag and visit tables. ``time_utc`` holds ``@position_timestamp`` (UTC, as the
#: receiver reports it); ``fix`` QField's translated quality description ("Fixed RTK", "Float RTK", …).
GNSS_FIELDS = (
    GnssField("fix", "text", "@position_quality_description", "Fix (from the receiver)"),
    GnssField("h_acc_m", "double", "@position_horizontal_accuracy", "Horizontal accuracy (m)"),
    GnssField("v_acc_m", "double", "@position_vertical_accuracy", "Vertical accuracy (m)"),
    GnssField("pdop", "double", "@position_pdop", "PDOP"),
    GnssField("hdop", "double", "@position_hdop", "HDOP"),
    GnssField("vdop", "double", "@position_vdop", "VDOP"),
    GnssField("n_sats", "int", "@position_number_of_used_satellites", "Satellites used"),
    GnssField("averaged", "int", "@position_averaged_count", "Positions averaged"),
    GnssField("source", "text", "@position_source_name", "Position source"),
    GnssField("time_utc", "datetime", "@position_timestamp", "Capture time (UTC)"),
)

#: What a worker decides at a point to visit (stored value → shown in QField's drop-down), as the review's
#: verdicts; NULL = not visited.
DECISIONS = {
    CONFIRMED: "Real target",
    HARD_NEGATIVE: "Not a target",
    UNCERTAIN: "Cannot tell",
}

#: The reviewer name written with the verdicts that come from the field (``field:<worker>``).
FIELD_REVIEWER_PREFIX = "field:"


def accuracy_requirement_expression(max_h_accuracy_m: float | None, require_fixed: bool) -> str:
    """The QGIS expression a geotag must satisfy (the ``h_acc_m`` field's constraint): an RTK fixed
    solution (QField's quality description read as :func:`fix_from_description` reads it) and/or a
    horizontal accuracy at most ``max_h_accuracy_m``. An empty string: no requirement."""
    parts = []
    if require_fixed:
        parts.append("(coalesce(\"fix\", '') ILIKE 'fixed rtk%' OR coalesce(\"fix\", '') ILIKE 'unknown (4)%')")
    if max_h_accuracy_m is not None:
        parts.append(f"coalesce(\"h_acc_m\", 1e9) <= {float(max_h_accuracy_m)!r}")
    return " AND ".join(parts)


#: QField's quality descriptions (QgsGpsInformation's words, English) as NMEA GGA fix qualities.
_QUALITY_WORDS = {
    "fixed rtk": 4, "float rtk": 5, "dgps": 2, "pps": 3, "autonomous": 1, "estimated": 6,
    "manual input mode": 7, "simulation mode": 8, "invalid": 0,
}
#: Some QField releases write "Unknown (<GGA code>)" for every quality (a switch without breaks).
_UNKNOWN_CODE = re.compile(r"unknown\s*\((\d)\)")
_IMU_SUFFIX = re.compile(r"\s*-\s*imu active\s*$")


def fix_from_description(text) -> int | None:
    """The NMEA GGA fix quality of QField's ``@position_quality_description`` ("Fixed RTK" → 4, "Float RTK" →
    5, "DGPS" → 2, "Autonomous" → 1, "Unknown (4)" → 4; a trailing " - IMU active" is ignored); None for a
    description it does not know (a translated one), 0 for an empty one."""
    if text is None:
        return 0
    word = _IMU_SUFFIX.sub("", " ".join(str(text).lower().split()))
    if word == "":
        return 0
    if word in _QUALITY_WORDS:
        return _QUALITY_WORDS[word]
    match = _UNKNOWN_CODE.fullmatch(word)
    return int(match.group(1)) if match else None

"""``birdseye:preparefieldsurvey`` through the registry: the package QField opens, its default values and
accuracy requirement under QField's position variables, a review's open clusters as points to visit, and bad
input.

QField fills a new feature's default values from an expression context holding its ``@position_*``
variables; :func:`position_context` builds such a context, so ``QgsVectorLayerUtils.createFeature`` gives what
QField would store.
"""
from __future__ import annotations

import json
import re
import zipfile
from pathlib import Path

import pytest
from qgis.core import (
    NULL,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsExpression,
    QgsExpressionContext,
    QgsExpressionContextScope,
    QgsExpressionContextUtils,
    QgsFeature,
    QgsFieldConstraints,
    QgsGeometry,
    QgsPoint,
    QgsPointXY,
    QgsProcessingException,
    QgsProject,
    QgsRasterLayer,
    QgsVectorLayer,
    QgsVectorLayerUtils,
)
from qgis.PyQt.QtCore import QDateTime, Qt
from registry import run

from birdseye.birdseye_qgis.core.field import field_survey as fs

SMALL = {"SEED": 4, "N_TARGETS": 3, "FIELD_WIDTH_M": 6.0, "FIELD_LENGTH_M": 4.0, "IMAGE_WIDTH": 160,
         "IMAGE_HEIGHT": 100, "FPS": 2.0, "N_MISSED": 1, "N_SPURIOUS": 1}
LON, LAT, ALT = 151.95, -27.55, 401.234
FIX_TIME = QDateTime.fromString("2026-11-28T08:30:15Z", Qt.DateFormat.ISODate)


@pytest.fixture(scope="module")
def campaign(birdseye_provider, tmp_path_factory):
    """A simulated campaign: its orthomosaic, imported geotags and frame layer."""
    folder = tmp_path_factory.mktemp("campaign")
    sim = run("simulatecampaign", {**SMALL, "OUTPUT_FOLDER": str(folder)})
    geotags = run("importgeotags", {"INPUT": sim["GEOTAGS"], "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    frames = run("importflightlog", {"POSE_LOG": sim["POSES"], "IMAGES": str(folder / "frames"),
                                     "CALIBRATION": sim["CALIBRATION"], "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    return {"ortho": sim["ORTHOMOSAIC"], "geotags": geotags, "frames": frames}


def area_layer(geotags):
    """Two partitions covering the geotags' extent (WGS84), with a ``partition`` field."""
    layer = QgsVectorLayer("Polygon?crs=EPSG:4326&field=partition:string", "partitions", "memory")
    extent = QgsCoordinateTransform(geotags.crs(), QgsCoordinateReferenceSystem("EPSG:4326"),
                                    QgsProject.instance()).transformBoundingBox(geotags.extent()).buffered(1e-4)
    middle = extent.center().x()
    feats = []
    for name, (x0, x1) in (("west", (extent.xMinimum(), middle)), ("east", (middle, extent.xMaximum()))):
        f = QgsFeature(layer.fields())
        f.setAttributes([name])
        y0, y1 = extent.yMinimum(), extent.yMaximum()
        f.setGeometry(QgsGeometry.fromPolygonXY([[QgsPointXY(x0, y0), QgsPointXY(x1, y0), QgsPointXY(x1, y1),
                                                  QgsPointXY(x0, y1)]]))
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    return layer


def visit_points(points, with_id=False):
    layer = QgsVectorLayer("Point?crs=EPSG:4326" + ("&field=id:string" if with_id else ""), "to check", "memory")
    feats = []
    for k, (lon, lat) in enumerate(points):
        f = QgsFeature(layer.fields())
        if with_id:
            f.setAttributes([f"p{k + 1}"])
        f.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(lon, lat)))
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    return layer


def package(folder, **params):
    return run("preparefieldsurvey", {"OUTPUT_FOLDER": str(folder), **params})


def opened(project_path) -> QgsProject:
    project = QgsProject()
    assert project.read(str(project_path))
    return project


def layer_named(project, name):
    (layer,) = project.mapLayersByName(name)
    return layer


def position_context(layer, fix="Fixed RTK", h_acc=0.012):
    """The context QField evaluates default values in: the layer's scopes and its position variables."""
    context = QgsExpressionContext(layer.createExpressionContext())
    scope = QgsExpressionContextScope("position")
    for name, value in {"position_quality_description": fix, "position_horizontal_accuracy": h_acc,
                        "position_vertical_accuracy": 0.021, "position_pdop": 1.4, "position_hdop": 0.8,
                        "position_vdop": 1.1, "position_number_of_used_satellites": 23,
                        "position_averaged_count": 5, "position_source_name": "Reach RX",
                        "position_timestamp": FIX_TIME,
                        "position_coordinate": QgsGeometry(QgsPoint(LON, LAT, ALT)),
                        "user_full_name": "Ann Field"}.items():
        scope.setVariable(name, value)
    context.appendScope(scope)
    return context


def new_feature(layer, **position):
    return QgsVectorLayerUtils.createFeature(layer, QgsGeometry(QgsPoint(LON, LAT, ALT)), {},
                                             position_context(layer, **position))


def test_package_opens_in_a_fresh_project_with_relative_paths_and_the_orthomosaic_copied(campaign, tmp_path):
    geotags = campaign["geotags"]
    first = next(geotags.getFeatures())
    folder = tmp_path / "pkg"
    result = package(folder, PROJECT_NAME="north", CLASSES="burrow, nest , burrow", GEOTAGS=geotags,
                     VISIT_POINTS=visit_points([(first["lon"] + 1e-5, first["lat"])], with_id=True),
                     AREA=area_layer(geotags), FRAMES=campaign["frames"], BACKGROUND=campaign["ortho"])
    assert (result["VISIT_COUNT"], result["GEOTAG_COUNT"]) == (1, geotags.featureCount())
    assert Path(result["PROJECT"]) == folder / "north.qgz"
    written = sorted(p.name for p in folder.iterdir() if not p.name.endswith(".aux.xml"))  # GDAL's side files
    assert written == sorted(["north.qgz", fs.PACKAGE_GPKG, "north_orthomosaic.tif"])
    assert (folder / "north_orthomosaic.tif").read_bytes() == Path(campaign["ortho"]).read_bytes()

    with zipfile.ZipFile(folder / "north.qgz") as archive:
        xml = archive.read("north.qgs").decode("utf-8")
    sources = [s for s in re.findall(r"<datasource>([^<]*)</datasource>", xml) if s]
    assert len(sources) == 6 and all(s.startswith("./") for s in sources), sources

    project = opened(folder / "north.qgz")
    order = [node.layer().name() for node in project.layerTreeRoot().findLayers()]
    assert order == ["Geotags", "Points to visit", "Surveyed before", "Survey area", "Frame footprints", "Orthomosaic"]
    layers = {layer.name(): layer for layer in project.mapLayers().values()}
    assert all(layer.isValid() for layer in layers.values())
    assert isinstance(layers["Orthomosaic"], QgsRasterLayer)
    assert Path(layers["Orthomosaic"].source()) == folder / "north_orthomosaic.tif"
    assert [layers[n].readOnly() for n in ("Geotags", "Points to visit", "Surveyed before", "Survey area",
                                           "Frame footprints")] == [False, False, True, True, True]
    assert layers["Geotags"].customProperty("QFieldSync/action") == "offline"
    assert layers["Survey area"].customProperty("QFieldSync/action") == "copy"
    assert layers["Points to visit"].customProperty("QFieldSync/is_geometry_locked") in (True, "true")
    assert sorted(f["partition"] for f in layers["Survey area"].getFeatures()) == ["east", "west"]
    assert layers["Frame footprints"].featureCount() == campaign["frames"].featureCount()
    assert "frame_id" in layers["Frame footprints"].fields().names()
    visit = next(layers["Points to visit"].getFeatures())
    assert (visit["visit_id"], visit["origin"], visit["unit_keys"]) == ("p1", "layer:to check", "[]")
    assert visit["decision"] in (None, NULL)  # not visited

    assert project.crs().authid() == "EPSG:32756"  # the site's UTM zone
    # It opens on what the worker works on (the area, visits, geotags), not on the whole flight.
    opening = project.viewSettings().defaultViewExtent()
    work = QgsCoordinateTransform(layers["Survey area"].crs(), project.crs(), project).transformBoundingBox(
        layers["Survey area"].extent())
    assert opening.contains(work) and opening.width() <= work.width() + 2 * max(20.0, 0.1 * work.width()) + 1e-6
    assert "orthometric altitude from device" in project.metadata().abstract()
    scope = QgsExpressionContextUtils.projectScope(project)
    assert float(scope.variable("birdseye_label_radius_m")) == 0.05
    assert json.loads(scope.variable("birdseye_classes")) == ["burrow", "nest"]

    meta = QgsVectorLayer(f"{folder / fs.PACKAGE_GPKG}|layername={fs.META_TABLE}", "meta", "ogr")
    rows = {f["key"]: f["value"] for f in meta.getFeatures()}
    assert json.loads(rows[fs.META_CLASSES]) == ["burrow", "nest"]
    assert (rows[fs.META_LABEL_RADIUS_M], rows[fs.META_MAX_H_ACC_M], rows[fs.META_REQUIRE_FIXED],
            rows[fs.META_HEIGHT_REFERENCE], rows[fs.META_REVIEW_LOG]) == ("0.05", "0.05", "1", fs.HEIGHT_ORTHOMETRIC,
                                                                         "")


@pytest.mark.parametrize("height_reference, height_field", [(0, "h_msl"), (1, "h_ellipsoid")])
def test_default_values_fill_from_qfields_position_variables(birdseye_provider, tmp_path, height_reference,
                                                             height_field):
    result = package(tmp_path / "pkg", CLASSES="nest,burrow", LABEL_RADIUS_M=0.08, HEIGHT_REFERENCE=height_reference,
                     VISIT_POINTS=visit_points([(LON, LAT)]))
    project = opened(result["PROJECT"])
    assert project.crs().authid() == "EPSG:32756"
    expected = {"fix": "Fixed RTK", "h_acc_m": 0.012, "v_acc_m": 0.021, "pdop": 1.4, "hdop": 0.8, "vdop": 1.1,
                "n_sats": 23, "averaged": 5, "source": "Reach RX", "worker": "Ann Field"}
    geotags = layer_named(project, "Geotags")
    feature = new_feature(geotags)
    assert {field: feature[field] for field in expected} == pytest.approx(expected)
    assert feature["time_utc"] == FIX_TIME
    # A visit exists before the worker gets there: its fields fill on the edit that decides it (QField applies
    # apply-on-update defaults when the form is saved, in the same position context).
    visits = layer_named(project, "Points to visit")
    visit = next(visits.getFeatures())
    context = position_context(visits)

    def recorded():
        return {name: visits.defaultValue(visits.fields().indexOf(name), visit, context)
                for name in [*expected, "time_utc"]}

    assert all(value in (None, NULL) for value in recorded().values())  # not decided: nothing recorded
    visit["decision"] = "uncertain"
    assert recorded() == pytest.approx({**expected, "time_utc": FIX_TIME})
    for layer in (geotags, visits):
        assert all(layer.attributeDisplayName(layer.fields().indexOf(g.name)) == g.alias for g in fs.GNSS_FIELDS)
        assert all(layer.defaultValueDefinition(layer.fields().indexOf(g.name)).applyOnUpdate() == (layer is visits)
                   for g in fs.GNSS_FIELDS)
    assert feature[height_field] == pytest.approx(ALT)
    (other_height,) = set(fs.HEIGHT_FIELDS.values()) - {height_field}
    assert other_height not in geotags.fields().names()
    assert (feature["label"], feature["radius_m"]) == ("nest", pytest.approx(0.08))
    assert geotags.attributeDisplayName(geotags.fields().indexOf("radius_m")) == "Label radius (m)"
    assert geotags.editorWidgetSetup(geotags.fields().indexOf("label")).type() == "ValueMap"


@pytest.mark.parametrize("enforcement, strength", [
    (0, QgsFieldConstraints.ConstraintStrength.ConstraintStrengthSoft),
    (1, QgsFieldConstraints.ConstraintStrength.ConstraintStrengthHard)])
def test_accuracy_requirement_flags_a_float_point_and_passes_a_fixed_one(birdseye_provider, tmp_path, enforcement,
                                                                         strength):
    result = package(tmp_path / "pkg", ACCURACY_ENFORCEMENT=enforcement, MAX_H_ACCURACY_M=0.05)
    project = opened(result["PROJECT"])
    geotags = layer_named(project, "Geotags")
    index = geotags.fields().indexOf("h_acc_m")
    other = ({QgsFieldConstraints.ConstraintStrength.ConstraintStrengthSoft,
              QgsFieldConstraints.ConstraintStrength.ConstraintStrengthHard} - {strength}).pop()
    fails_rule = geotags.renderer().rootRule().children()[0]

    def judged(fix, h_acc):
        feature = new_feature(geotags, fix=fix, h_acc=h_acc)
        valid, _ = QgsVectorLayerUtils.validateAttribute(geotags, feature, index, strength)
        unchecked, _ = QgsVectorLayerUtils.validateAttribute(geotags, feature, index, other)
        assert unchecked  # the requirement has the one strength asked for
        context = position_context(geotags)
        context.setFeature(feature)
        red = bool(QgsExpression(fails_rule.filterExpression()).evaluate(context))
        assert red != valid  # the style shows what the constraint says
        return valid

    assert not judged("Float RTK", 0.08)
    assert not judged("Float RTK", 0.012)  # RTK fixed is required
    assert not judged("Fixed RTK", 0.08)   # and at most 5 cm
    assert judged("Fixed RTK", 0.012)
    assert judged("Unknown (4)", 0.012)    # what some QField releases write for a fixed solution
    description = geotags.fields().at(index).constraints().constraintDescription()
    assert "RTK fixed" in description and "5 cm" in description


def test_review_unresolved_clusters_become_visits_with_their_unit_keys(birdseye_provider, tmp_path):
    from test_cluster_algorithms import SITE, frame_layer, geotag_layer
    from test_review_loop import SPOTS, UNRESOLVED, scene

    det, verdicts = scene()
    result = package(tmp_path / "pkg", GEOTAGS=geotag_layer(), REVIEW=verdicts, REVIEW_DETECTIONS=[det],
                     REVIEW_FRAMES=[frame_layer()])
    assert (result["VISIT_COUNT"], result["GEOTAG_COUNT"]) == (3, 3)
    project = opened(result["PROJECT"])
    visits = layer_named(project, "Points to visit")
    found = {}
    for f in visits.getFeatures():
        point = f.geometry().asPoint()
        east, north, _ = SITE.from_geodetic(point.y(), point.x(), SITE.h0).reshape(3)
        spot = next(k for k, xy in SPOTS.items() if abs(xy[0] - east) < 0.05 and abs(xy[1] - north) < 0.05)
        found[spot] = (f["origin"], json.loads(f["unit_keys"]), f["question"])
        assert f["visit_id"].startswith("detections#")
    assert {k: v[0] for k, v in found.items()} == {k: f"review:{o}" for k, o in UNRESOLVED.items()}
    assert found["D"][1] == ["uD"] and found["E"][1] == ["uE"]
    # F was never judged: its decision goes to a unit at the visit point, the cluster's centroid.
    (f_key,) = found["F"][1]
    f_visit = next(f for f in visits.getFeatures() if json.loads(f["unit_keys"]) == [f_key]).geometry().asPoint()
    assert f_key == f"u{f_visit.y():+.7f}{f_visit.x():+.7f}"
    assert "uncertain" in found["D"][2]
    meta = QgsVectorLayer(f"{tmp_path / 'pkg' / fs.PACKAGE_GPKG}|layername={fs.META_TABLE}", "meta", "ogr")
    assert {f["key"]: f["value"] for f in meta.getFeatures()}[fs.META_REVIEW_LOG] == "", "a memory layer has no file"


def test_bad_input_is_refused_with_a_reason(birdseye_provider, tmp_path):
    from test_review_loop import scene

    det, verdicts = scene()
    with pytest.raises(QgsProcessingException, match="REVIEW needs GEOTAGS"):
        package(tmp_path / "a", REVIEW=verdicts, REVIEW_DETECTIONS=[det])
    with pytest.raises(QgsProcessingException, match="REVIEW_DETECTIONS is given without REVIEW"):
        package(tmp_path / "a", REVIEW_DETECTIONS=[det])
    with pytest.raises(QgsProcessingException, match="CLASSES: give at least one class"):
        package(tmp_path / "b", CLASSES=" , ")
    with pytest.raises(QgsProcessingException, match="PROJECT_NAME"):
        package(tmp_path / "c", PROJECT_NAME="../up")
    assert not any((tmp_path / name).exists() for name in "abc")

    first = package(tmp_path / "d")
    before = Path(first["PROJECT"]).read_bytes()
    # Another project name: the GeoPackage is the package's whichever the name, so it is refused too.
    for name in ("birdseye_survey", "other"):
        with pytest.raises(QgsProcessingException, match=f"already holds a field survey package.*{fs.PACKAGE_GPKG}"):
            package(tmp_path / "d", PROJECT_NAME=name)
    assert Path(first["PROJECT"]).read_bytes() == before


def test_a_cancelled_run_leaves_no_half_package(birdseye_provider, tmp_path):
    from birdseye.birdseye_qgis.core.errors import Cancelled
    from birdseye.birdseye_qgis.qgis_io import field_package

    settings = field_package.SurveySettings(("target",), 0.05, True, 0.05, False, fs.HEIGHT_ORTHOMETRIC)
    (tmp_path / "notes.txt").write_text("kept")
    with pytest.raises(Cancelled):
        field_package.write_package(tmp_path, "survey", settings, [], field_package.PackageSources(),
                                    QgsProject.instance().transformContext(), is_canceled=lambda: True)
    assert [p.name for p in tmp_path.iterdir()] == ["notes.txt"]
    assert field_package.write_package(tmp_path, "survey", settings, [], field_package.PackageSources(),
                                       QgsProject.instance().transformContext()).is_file()


@pytest.mark.parametrize("require_fixed, max_h_acc, float_close, fixed_far, description", [
    (False, 0.05, True, False, "Needs ≤ 5 cm horizontal accuracy"),
    (True, 0, False, True, "Needs RTK fixed"),
    (False, 0, True, True, None)])   # no requirement: no constraint, every point green
def test_each_part_of_the_requirement_can_be_left_out(birdseye_provider, tmp_path, require_fixed, max_h_acc,
                                                      float_close, fixed_far, description):
    result = package(tmp_path / "pkg", REQUIRE_RTK_FIXED=require_fixed, MAX_H_ACCURACY_M=max_h_acc)
    project = opened(result["PROJECT"])
    geotags = layer_named(project, "Geotags")
    index = geotags.fields().indexOf("h_acc_m")

    def valid(fix, h_acc):
        return QgsVectorLayerUtils.validateAttribute(geotags, new_feature(geotags, fix=fix, h_acc=h_acc), index)[0]

    assert (valid("Float RTK", 0.012), valid("Fixed RTK", 0.5)) == (float_close, fixed_far)
    constraints = geotags.fields().at(index).constraints()
    assert (constraints.constraintDescription() or None) == description
    assert len(geotags.renderer().rootRule().children()) == (1 if description is None else 2)


def test_a_package_with_only_an_orthomosaic_opens_on_it(campaign, tmp_path):
    project = opened(package(tmp_path / "pkg", BACKGROUND=campaign["ortho"])["PROJECT"])
    ortho = layer_named(project, "Orthomosaic")
    assert project.crs().authid() == "EPSG:32756"
    assert project.viewSettings().defaultViewExtent().contains(
        QgsCoordinateTransform(ortho.crs(), project.crs(), project).transformBoundingBox(ortho.extent()))

"""The QGIS enum values the plugin names, under the name each supported QGIS release has (3.22 … 4.x).

QGIS 3.30–3.36 moved these enums into ``Qgis`` (``QgsProcessing.TypeVectorPoint`` became
``Qgis.ProcessingSourceType.VectorPoint``, ``QgsWkbTypes.PointZ`` ``Qgis.WkbType.PointZ`` …) and
deprecated the old names; QGIS 4 still answers to them only through compatibility aliases that may go
during 4.x. QGIS 3.22 has only the old names. So each value is taken from the new enum where the
running QGIS has it and from the old one otherwise. ``scripts/check_qt6.py`` (``make lint``) refuses
the old names anywhere else in the plugin.
"""
from __future__ import annotations

from qgis.core import Qgis

if Qgis.QGIS_VERSION_INT >= 33600:
    SOURCE_VECTOR_POINT = Qgis.ProcessingSourceType.VectorPoint
    SOURCE_VECTOR_LINE = Qgis.ProcessingSourceType.VectorLine
    SOURCE_VECTOR_POLYGON = Qgis.ProcessingSourceType.VectorPolygon
    #: Any vector layer, with or without geometry (tables).
    SOURCE_VECTOR = Qgis.ProcessingSourceType.Vector
    SOURCE_FILE = Qgis.ProcessingSourceType.File
    NUMBER_DOUBLE = Qgis.ProcessingNumberParameterType.Double
    NUMBER_INTEGER = Qgis.ProcessingNumberParameterType.Integer
    FILE_BEHAVIOR_FILE = Qgis.ProcessingFileParameterBehavior.File
    FILE_BEHAVIOR_FOLDER = Qgis.ProcessingFileParameterBehavior.Folder
    PARAMETER_ADVANCED = Qgis.ProcessingParameterFlag.Advanced
    REQUEST_NO_GEOMETRY = Qgis.FeatureRequestFlag.NoGeometry
    CRS_WKT2_2019 = Qgis.CrsWktVariant.Wkt2_2019
else:
    from qgis.core import (
        QgsCoordinateReferenceSystem,
        QgsFeatureRequest,
        QgsProcessing,
        QgsProcessingParameterDefinition,
        QgsProcessingParameterFile,
        QgsProcessingParameterNumber,
    )

    SOURCE_VECTOR_POINT = QgsProcessing.TypeVectorPoint
    SOURCE_VECTOR_LINE = QgsProcessing.TypeVectorLine
    SOURCE_VECTOR_POLYGON = QgsProcessing.TypeVectorPolygon
    SOURCE_VECTOR = QgsProcessing.TypeVector
    SOURCE_FILE = QgsProcessing.TypeFile
    NUMBER_DOUBLE = QgsProcessingParameterNumber.Double
    NUMBER_INTEGER = QgsProcessingParameterNumber.Integer
    FILE_BEHAVIOR_FILE = QgsProcessingParameterFile.File
    FILE_BEHAVIOR_FOLDER = QgsProcessingParameterFile.Folder
    PARAMETER_ADVANCED = QgsProcessingParameterDefinition.FlagAdvanced
    REQUEST_NO_GEOMETRY = QgsFeatureRequest.NoGeometry
    CRS_WKT2_2019 = QgsCoordinateReferenceSystem.WKT2_2019

if Qgis.QGIS_VERSION_INT >= 33400:
    FILTER_VECTOR_LAYER = Qgis.LayerFilter.VectorLayer
    FILTER_POINT_LAYER = Qgis.LayerFilter.PointLayer
else:
    from qgis.core import QgsMapLayerProxyModel

    FILTER_VECTOR_LAYER = QgsMapLayerProxyModel.VectorLayer
    FILTER_POINT_LAYER = QgsMapLayerProxyModel.PointLayer

if Qgis.QGIS_VERSION_INT >= 33000:
    WKB_POINT = Qgis.WkbType.Point
    WKB_POINT_Z = Qgis.WkbType.PointZ
    WKB_LINE_STRING = Qgis.WkbType.LineString
    WKB_LINE_STRING_Z = Qgis.WkbType.LineStringZ
    WKB_POLYGON = Qgis.WkbType.Polygon
    WKB_POLYGON_Z = Qgis.WkbType.PolygonZ
    WKB_MULTI_POLYGON = Qgis.WkbType.MultiPolygon
    WKB_NO_GEOMETRY = Qgis.WkbType.NoGeometry
    GEOMETRY_POINT = Qgis.GeometryType.Point
    GEOMETRY_LINE = Qgis.GeometryType.Line
    GEOMETRY_POLYGON = Qgis.GeometryType.Polygon
    DISTANCE_METERS = Qgis.DistanceUnit.Meters
    LAYER_VECTOR = Qgis.LayerType.Vector
else:
    from qgis.core import QgsMapLayerType, QgsUnitTypes, QgsWkbTypes

    WKB_POINT = QgsWkbTypes.Point
    WKB_POINT_Z = QgsWkbTypes.PointZ
    WKB_LINE_STRING = QgsWkbTypes.LineString
    WKB_LINE_STRING_Z = QgsWkbTypes.LineStringZ
    WKB_POLYGON = QgsWkbTypes.Polygon
    WKB_POLYGON_Z = QgsWkbTypes.PolygonZ
    WKB_MULTI_POLYGON = QgsWkbTypes.MultiPolygon
    WKB_NO_GEOMETRY = QgsWkbTypes.NoGeometry
    GEOMETRY_POINT = QgsWkbTypes.PointGeometry
    GEOMETRY_LINE = QgsWkbTypes.LineGeometry
    GEOMETRY_POLYGON = QgsWkbTypes.PolygonGeometry
    DISTANCE_METERS = QgsUnitTypes.DistanceMeters
    LAYER_VECTOR = QgsMapLayerType.VectorLayer

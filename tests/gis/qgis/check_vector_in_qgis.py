#!/usr/bin/python3
"""Opens a talus vector layer (trajectories.gpkg) in QGIS as a user would and checks that it comes
up styled.

usage: check_vector_in_qgis.py CRS GPKG [FEATURES]

CRS is the expected layer CRS: an authority id (EPSG:31287), WKT, or 'local' for local metric
coordinates (no authority, not geographic, metres). The GeoPackage opens as a valid line layer with Z; the .qml beside it was applied (a
graduated renderer on max_energy_kj with exactly the style's classes and colours, every feature
inside a class, the style's field aliases); the CRS is the expected one; with FEATURES, the layer
has that many features. Prints one line per problem; exit 0 when none.
Runs on Debian's /usr/bin/python3 (python3-qgis).
"""
import os
import sys
import xml.etree.ElementTree as ET

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import (QgsApplication, QgsCoordinateReferenceSystem, QgsVectorLayer,  # noqa: E402
                       QgsUnitTypes, QgsWkbTypes)

ENERGY_FIELD = "max_energy_kj"


def style_of(qml_path):
    """(attribute, [(lower, upper, #rrggbb)], {field: alias}) of the style file."""
    root = ET.parse(qml_path).getroot()
    renderer = root.find("renderer-v2")
    colours = {}
    for symbol in renderer.iter("symbol"):
        props = {p.get("k"): p.get("v") for p in symbol.iter("prop")}
        r, g, b = (int(c) for c in props["line_color"].split(",")[:3])
        colours[symbol.get("name")] = f"#{r:02x}{g:02x}{b:02x}"
    ranges = [(float(r.get("lower")), float(r.get("upper")), colours[r.get("symbol")])
              for r in renderer.iter("range")]
    aliases = {a.get("field"): a.get("name") for a in root.iter("alias") if a.get("name")}
    return renderer.get("attr"), ranges, aliases


def problems_of(path, crs, features):
    name = os.path.basename(path)
    layer = QgsVectorLayer(path, name, "ogr")  # loads the .qml of the same base name by default
    if not layer.isValid():
        return [f"{name}: QGIS cannot open it"]
    problems = []
    qml = os.path.splitext(path)[0] + ".qml"
    if not os.path.exists(qml):
        return [f"{name}: no style {os.path.basename(qml)} beside it"]
    if layer.geometryType() != QgsWkbTypes.LineGeometry or not QgsWkbTypes.hasZ(layer.wkbType()):
        problems.append(f"{name}: geometry {QgsWkbTypes.displayString(layer.wkbType())}, not 3D lines")
    attribute, ranges, aliases = style_of(qml)
    renderer = layer.renderer()
    if renderer.type() != "graduatedSymbol":
        return problems + [f"{name}: renderer {renderer.type()}, not the style's graduatedSymbol"]
    if renderer.classAttribute() != attribute or attribute != ENERGY_FIELD:
        problems.append(f"{name}: classes on {renderer.classAttribute()} (style: {attribute}), not {ENERGY_FIELD}")
    shown = [(r.lowerValue(), r.upperValue(), r.symbol().color().name()) for r in renderer.ranges()]
    if shown != ranges:
        problems.append(f"{name}: classes {shown} are not the style's {ranges}")
    for feature in layer.getFeatures():
        value = feature[attribute]
        if renderer.rangeForValue(value) is None:
            problems.append(f"{name}: feature {feature.id()} ({attribute} {value}) is in no class")
    for field, alias in aliases.items():
        index = layer.fields().indexOf(field)
        if index < 0 or layer.attributeAlias(index) != alias:
            problems.append(f"{name}: field {field} has not the style's alias '{alias}'")
    if features is not None and layer.featureCount() != features:
        problems.append(f"{name}: {layer.featureCount()} features, expected {features}")
    if crs == "local":
        if layer.crs().authid() or layer.crs().isGeographic() or layer.crs().mapUnits() != QgsUnitTypes.DistanceMeters:
            problems.append(f"{name}: CRS {layer.crs().authid() or layer.crs().description()}, "
                            "expected local coordinates in metres")
    elif crs.startswith("EPSG:"):
        if layer.crs().authid() != crs:
            problems.append(f"{name}: CRS {layer.crs().authid()}, expected {crs}")
    elif layer.crs() != QgsCoordinateReferenceSystem.fromWkt(crs):
        problems.append(f"{name}: CRS {layer.crs().authid() or layer.crs().toWkt()} differs from the expected WKT")
    return problems


def main():
    if len(sys.argv) not in (3, 4):
        print(__doc__)
        return 2
    crs, path = sys.argv[1], sys.argv[2]
    features = int(sys.argv[3]) if len(sys.argv) == 4 else None
    app = QgsApplication([], False)
    app.initQgis()
    problems = problems_of(path, crs, features)
    app.exitQgis()
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

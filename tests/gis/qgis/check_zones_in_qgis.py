#!/usr/bin/python3
"""Opens a study's hazard_zones.gpkg in QGIS as a user would and checks that it comes up styled.

usage: check_zones_in_qgis.py CRS GPKG [MINIMUM_AREA_M2]

CRS is the expected layer CRS as an authority id (EPSG:31287). The GeoPackage opens as a valid
polygon layer; the .qml beside it was applied: a categorized renderer on `degree` with exactly the
style's categories, values, labels and fill colours; every feature's degree has a category and
its `name` is that category's degree name (the style's label starts with it); the CRS is the
expected one; residual hazard is hatched; no zone is smaller than MINIMUM_AREA_M2 (when given).
Prints one line per problem; exit 0 when none.
Runs on Debian's /usr/bin/python3 (python3-qgis).
"""
import os
import sys
import xml.etree.ElementTree as ET

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import QgsApplication, QgsVectorLayer, QgsWkbTypes  # noqa: E402
from qgis.PyQt.QtCore import Qt  # noqa: E402


def style_of(qml_path):
    """(attribute, [(value, label, #rrggbb)]) of the style file."""
    renderer = ET.parse(qml_path).getroot().find("renderer-v2")
    colours = {}
    for symbol in renderer.iter("symbol"):
        props = {p.get("k"): p.get("v") for p in symbol.iter("prop")}
        r, g, b = (int(c) for c in props["color"].split(",")[:3])
        colours[symbol.get("name")] = f"#{r:02x}{g:02x}{b:02x}"
    categories = [(c.get("value"), c.get("label"), colours[c.get("symbol")]) for c in renderer.iter("category")]
    return renderer.get("attr"), categories


def problems_of(path, crs, minimum_area):
    name = os.path.basename(path)
    layer = QgsVectorLayer(path, name, "ogr")
    if not layer.isValid():
        return [f"{name}: QGIS cannot open it"]
    qml = os.path.splitext(path)[0] + ".qml"
    if not os.path.exists(qml):
        return [f"{name}: no style {os.path.basename(qml)} beside it"]
    problems = []
    if layer.geometryType() != QgsWkbTypes.PolygonGeometry:
        problems.append(f"{name}: geometry {QgsWkbTypes.displayString(layer.wkbType())}, not polygons")
    attribute, categories = style_of(qml)
    renderer = layer.renderer()
    if renderer.type() != "categorizedSymbol":
        return problems + [f"{name}: renderer {renderer.type()}, not the style's categorizedSymbol"]
    if renderer.classAttribute() != "degree" or attribute != "degree":
        problems.append(f"{name}: categories on {renderer.classAttribute()} (style: {attribute}), not degree")
    shown = [(str(c.value()), c.label(), c.symbol().color().name()) for c in renderer.categories()]
    if shown != categories:
        problems.append(f"{name}: categories {shown} are not the style's {categories}")
    labels = {value: label for value, label, _ in categories}
    if layer.featureCount() == 0:
        problems.append(f"{name}: no zones")
    for feature in layer.getFeatures():
        value = str(feature["degree"])
        if value not in labels:
            problems.append(f"{name}: feature {feature.id()} (degree {value}) is in no category")
        elif not labels[value].startswith(str(feature["name"]) + " "):
            problems.append(f"{name}: feature {feature.id()} is named {feature['name']}, its category {labels[value]}")
    residual = [c for c in renderer.categories() if str(c.label()).startswith("residual")]
    for category in residual:
        if category.symbol().symbolLayer(0).brushStyle() == Qt.SolidPattern:
            problems.append(f"{name}: residual hazard is a solid fill, not hatched")
    if minimum_area > 0:
        small = [f.id() for f in layer.getFeatures() if f.geometry().area() < minimum_area - 1e-6]
        if small:
            problems.append(f"{name}: {len(small)} of {layer.featureCount()} zones are smaller than {minimum_area} m2")
    if layer.crs().authid() != crs:
        problems.append(f"{name}: CRS {layer.crs().authid()}, expected {crs}")
    return problems


def main():
    if len(sys.argv) not in (3, 4):
        print(__doc__)
        return 2
    app = QgsApplication([], False)
    app.initQgis()
    problems = problems_of(sys.argv[2], sys.argv[1], float(sys.argv[3]) if len(sys.argv) == 4 else 0.0)
    app.exitQgis()
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Opens talus layers in QGIS as a user would and checks that they come up styled.

usage: check_layer_in_qgis.py CRS LAYER DESCRIPTION [LAYER DESCRIPTION ...]

CRS is the expected layer CRS: an authority id (EPSG:31287) or WKT. For every LAYER (a .tif):
it opens as a valid raster layer; the .qml beside it was applied (a singleband pseudocolor
renderer with exactly the style's classes, 0 and nodata transparent); the band is named after
DESCRIPTION; the CRS is the expected one. Prints one line per problem; exit 0 when none.
Runs on Debian's /usr/bin/python3 (python3-qgis).
"""
import os
import sys
import xml.etree.ElementTree as ET

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import (QgsApplication, QgsColorRampShader, QgsCoordinateReferenceSystem,  # noqa: E402
                       QgsRasterLayer)

NODATA = -9999.0


def style_items(qml_path):
    """(value, #rrggbb, alpha) of the classes in the style file."""
    root = ET.parse(qml_path).getroot()
    return [(float(item.get("value")), item.get("color"), int(item.get("alpha")))
            for item in root.iter("item")]


def problems_of(path, description, crs):
    name = os.path.basename(path)
    layer = QgsRasterLayer(path, name, "gdal")  # loads NAME.qml beside it by default
    if not layer.isValid():
        return [f"{name}: QGIS cannot open it: {layer.error().summary()}"]
    problems = []
    renderer = layer.renderer()
    if renderer.type() != "singlebandpseudocolor":
        problems.append(f"{name}: renderer {renderer.type()}, not the style's singlebandpseudocolor")
        return problems
    ramp = renderer.shader().rasterShaderFunction()
    items = [(i.value, i.color.name(), i.color.alpha()) for i in ramp.colorRampItemList()]
    expected = style_items(os.path.splitext(path)[0] + ".qml")
    if items != expected:
        problems.append(f"{name}: colour classes {items} are not the style's {expected}")
    if ramp.colorRampType() != QgsColorRampShader.Discrete:
        problems.append(f"{name}: the classes are not discrete")
    ok, _, _, _, alpha = renderer.shader().shade(0.0)
    if not ok or alpha != 0:
        problems.append(f"{name}: 0 (never reached) is not transparent")
    if renderer.nodataColor().isValid():
        problems.append(f"{name}: nodata is drawn in {renderer.nodataColor().name()}")
    provider = layer.dataProvider()
    if not provider.sourceHasNoDataValue(1) or provider.sourceNoDataValue(1) != NODATA:
        problems.append(f"{name}: nodata is not {NODATA}")
    # QGIS 3.22 has no band-description call: the GDAL provider appends it to the band name.
    band_name = provider.generateBandName(1)
    if not band_name.endswith(": " + description):
        problems.append(f"{name}: band name '{band_name}' does not end with the description '{description}'")
    if crs.startswith("EPSG:"):
        if layer.crs().authid() != crs:
            problems.append(f"{name}: CRS {layer.crs().authid()}, expected {crs}")
    elif layer.crs() != QgsCoordinateReferenceSystem.fromWkt(crs):
        problems.append(f"{name}: CRS {layer.crs().authid() or layer.crs().toWkt()} differs from the expected WKT")
    return problems


def main():
    if len(sys.argv) < 4 or len(sys.argv) % 2 != 0:
        print(__doc__)
        return 2
    crs, pairs = sys.argv[1], sys.argv[2:]
    app = QgsApplication([], False)
    app.initQgis()
    problems = []
    for path, description in zip(pairs[::2], pairs[1::2]):
        problems += problems_of(path, description, crs)
    app.exitQgis()
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Opens talus layers in QGIS as a user would and checks that they come up styled.

usage: check_layer_in_qgis.py CRS LAYER DESCRIPTION [LAYER DESCRIPTION ...]

CRS is the expected layer CRS: an authority id (EPSG:31287) or WKT. For every LAYER (a .tif):
it opens as a valid raster layer; the .qml beside it was applied (a singleband pseudocolor
renderer with exactly the style's classes); cells of 0 (never reached) and nodata draw
transparent and reached cells draw in their class's colour at the style's opacity; the legend
lists only drawn classes (no transparent swatch, which a print layout draws as a black box) under
a heading that carries the band's unit; the band is named after DESCRIPTION; the .qmd beside it
gives QGIS a title and abstract; the CRS is the expected one. Prints one line per problem; exit 0
when none.
Runs on Debian's /usr/bin/python3 (python3-qgis).
"""
import os
import sys
import xml.etree.ElementTree as ET

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import (QgsApplication, QgsColorRampShader, QgsCoordinateReferenceSystem,  # noqa: E402
                       QgsLayerTreeLayer, QgsRasterLayer)
from qgis.PyQt.QtCore import Qt  # noqa: E402
from osgeo import gdal  # noqa: E402

NODATA = -9999.0


def style_items(qml_path):
    """(value, #rrggbb, alpha) of the classes in the style file: the colour ramp's items of a
    pseudocolor style, the palette entries of a paletted one (intensity.tif)."""
    root = ET.parse(qml_path).getroot()
    return [(float(item.get("value")), item.get("color"), int(item.get("alpha")))
            for item in list(root.iter("item")) + list(root.iter("paletteEntry"))]


def renderer_items(renderer):
    """(value, #rrggbb, alpha) of the classes QGIS applied; None for another renderer."""
    if renderer.type() == "singlebandpseudocolor":
        ramp = renderer.shader().rasterShaderFunction()
        if ramp.colorRampType() != QgsColorRampShader.Discrete:
            return None
        return [(i.value, i.color.name(), i.color.alpha()) for i in ramp.colorRampItemList()]
    if renderer.type() == "paletted":
        return [(float(c.value), c.color.name(), c.color.alpha()) for c in renderer.classes()]
    return None


def problems_of(path, description, crs):
    name = os.path.basename(path)
    layer = QgsRasterLayer(path, name, "gdal")  # loads NAME.qml beside it by default
    if not layer.isValid():
        return [f"{name}: QGIS cannot open it: {layer.error().summary()}"]
    problems = []
    renderer = layer.renderer()
    items = renderer_items(renderer)
    if items is None:
        problems.append(f"{name}: renderer {renderer.type()}, not the style's discrete pseudocolor or paletted one")
        return problems
    expected = style_items(os.path.splitext(path)[0] + ".qml")
    if items != expected:
        problems.append(f"{name}: colour classes {items} are not the style's {expected}")
    problems += drawing_problems(name, path, layer)
    problems += legend_problems(name, layer, items)
    layer.loadDefaultMetadata()  # QGIS reads the .qmd beside a layer it opens
    if not layer.metadata().title() or not layer.metadata().abstract():
        problems.append(f"{name}: no title or abstract in the metadata QGIS shows ({path[:-4]}.qmd)")
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


def drawing_problems(name, path, layer):
    """Draws the layer through its renderer and compares pixels with the band's values: 0 and
    nodata transparent, other cells opaque at the renderer's opacity."""
    dataset = gdal.Open(path)
    values = dataset.GetRasterBand(1).ReadAsArray()
    block = layer.renderer().block(1, layer.extent(), dataset.RasterXSize, dataset.RasterYSize)
    opacity = layer.renderer().opacity()
    problems, seen = [], set()
    for row in range(dataset.RasterYSize):
        for col in range(dataset.RasterXSize):
            value = float(values[row, col])
            kind = "nodata" if value == NODATA else "zero" if value == 0 else "reached"
            if kind in seen:
                continue
            alpha = (block.color(row, col) >> 24) & 0xFF
            expected = 0 if kind != "reached" else round(255 * opacity)
            if abs(alpha - expected) > 1:
                problems.append(f"{name}: a {kind} cell ({value:g}) draws with alpha {alpha}, expected {expected}")
            seen.add(kind)
    if opacity >= 1:
        problems.append(f"{name}: drawn fully opaque, hiding the terrain under it")
    return problems


def legend_problems(name, layer, items):
    """The legend QGIS builds for the layer: a heading with the unit, then one swatch per class."""
    tree_node = QgsLayerTreeLayer(layer)
    nodes = layer.legend().createLayerTreeModelLegendNodes(tree_node)
    texts = [node.data(Qt.DisplayRole) for node in nodes]
    del nodes, tree_node
    problems = []
    if any(alpha == 0 for _, _, alpha in items):
        problems.append(f"{name}: the legend holds a transparent class (printed as a black box)")
    dataset = gdal.Open(layer.source())  # kept while its band is read
    unit = dataset.GetRasterBand(1).GetUnitType()
    if unit and (not texts or f"({unit})" not in texts[0]):
        problems.append(f"{name}: the legend heading {texts[:1]} does not show the unit {unit}")
    if len(texts) != len(items) + 1:
        problems.append(f"{name}: legend {texts} is not a heading and the {len(items)} classes")
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

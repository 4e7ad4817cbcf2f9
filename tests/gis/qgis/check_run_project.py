#!/usr/bin/python3
"""Opens a run's project.qgz in QGIS and checks it and the quicklooks (issue 17, item 8).

usage: check_run_project.py OUT_DIR PROCESS LAYER [LAYER ...]

The project reads; every layer in it is valid; it holds each LAYER (a file stem) under its .qmd
title, the hillshade and the release, in the process's group; the hillshade lies at the bottom;
for PROCESS study (`talus study`), the group is Hazard, there is no release, each scenario of
OUT_DIR/study.json has a group named after it, and each process of its "region" a group of its
region layers, every one of them styled; the project's CRS is every layer's; a raster release
draws 0 transparent; the trajectories are off; particles, when written, are animated; the
project holds the print layout "Report" with its furniture, exported as quicklook/report.pdf;
quicklook/LAYER.png exists for each LAYER given and is not blank (it holds the layer's colours
and the hillshade's greys, not one flat colour). Prints one line per problem; exit 0 when none.
"""
import json
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ["GDAL_PAM_ENABLED"] = "NO"

from qgis.core import QgsApplication, QgsProject  # noqa: E402
from qgis.PyQt.QtGui import QImage  # noqa: E402

GROUP = {"rockfall": "Rock fall", "mudflow": "Mud flow", "study": "Hazard"}


def quicklook_problems(path):
    image = QImage(path)
    if image.isNull():
        return [f"{path}: not an image"]
    colours, white = set(), 0
    step = 7
    samples = 0
    for y in range(0, image.height(), step):
        for x in range(0, image.width(), step):
            rgb = image.pixel(x, y) & 0xFFFFFF
            colours.add(rgb)
            white += rgb == 0xFFFFFF
            samples += 1
    problems = []
    if len(colours) < 50:
        problems.append(f"{path}: only {len(colours)} colours: blank or flat")
    if white > 0.8 * samples:
        problems.append(f"{path}: {100 * white // samples} % white: the map is empty")
    return problems


def report_problems(project, out, process):
    """The report page (issue 38, item 2): a layout "Report" in the project with a map, a legend
    of the map's visible layers only (no hillshade, one entry each), a scale bar, a north arrow
    and a foot naming the CRS, the software and, for the sample scene, the terrain's credit; and
    quicklook/report.pdf beside the quicklooks."""
    problems = []
    if not os.path.exists(os.path.join(out, "quicklook", "report.pdf")):
        problems.append("no quicklook/report.pdf")
    layout = project.layoutManager().layoutByName("Report")
    if layout is None:
        return problems + ["no print layout 'Report' in the project"]
    kinds = {}
    for item in layout.items():
        kinds.setdefault(type(item).__name__, []).append(item)
    for needed in ("QgsLayoutItemMap", "QgsLayoutItemLegend", "QgsLayoutItemScaleBar", "QgsLayoutItemPicture"):
        if needed not in kinds:
            problems.append(f"the report page has no {needed[13:].lower()}")
    for legend in kinds.get("QgsLayoutItemLegend", []):
        names = [node.name() for node in legend.model().rootGroup().findLayers()]
        if any("hillshade" in name.lower() for name in names) or len(names) != len(set(names)):
            problems.append(f"the report's legend lists {names}: the map's layers once each, no hillshade")
    text = " ".join(item.text() for item in kinds.get("QgsLayoutItemLabel", []))
    for needed in ("CRS: ", "Talus "):
        if needed not in text:
            problems.append(f"the report page does not name '{needed.strip()}': {text!r}")
    sample = process != "study" and "sample_dem" in json.dumps(read_record(out).get("inputs", {}))
    if sample and "Land Tirol" not in text:
        problems.append(f"the report page of the sample scene lacks its terrain credit: {text!r}")
    return problems


def read_record(out):
    path = os.path.join(out, "run.json")
    if not os.path.exists(path):
        return {}
    with open(path, encoding="utf-8") as file:
        return json.load(file)


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    out, process, names = sys.argv[1], sys.argv[2], sys.argv[3:]
    app = QgsApplication([], False)
    app.initQgis()
    project = QgsProject.instance()
    problems = []
    if not project.read(os.path.join(out, "project.qgz")):
        problems.append(f"{out}/project.qgz: QGIS cannot read it: {project.error()}")
    layers = list(project.mapLayers().values())
    for layer in layers:
        if not layer.isValid():
            problems.append(f"project layer '{layer.name()}' ({layer.source()}) is not valid")
    by_file = {os.path.splitext(os.path.basename(layer.source().split("|")[0]))[0]: layer for layer in layers}
    group = project.layerTreeRoot().findGroup(GROUP[process])
    if group is None:
        problems.append(f"no group '{GROUP[process]}' in the project")
    for name in names:
        layer = by_file.get(name)
        if layer is None:
            problems.append(f"{name}: not in the project")
            continue
        layer.loadDefaultMetadata()
        if layer.name() != layer.metadata().title():
            problems.append(f"{name}: named '{layer.name()}', not its title '{layer.metadata().title()}'")
        if group is not None and group.findLayer(layer.id()) is None:
            problems.append(f"{name}: not in the group '{GROUP[process]}'")
        problems += quicklook_problems(os.path.join(out, "quicklook", name + ".png"))
    if process == "study":
        with open(os.path.join(out, "study.json"), encoding="utf-8") as file:
            study = json.load(file)
        scenarios = [s["name"] for s in study["scenarios"]]
        groups = [g.name() for g in project.layerTreeRoot().children() if g.nodeType() == 0]
        for name in scenarios:
            if not any(g.startswith(name + " (") for g in groups):
                problems.append(f"no group for the scenario {name} (groups: {groups})")
        # The region's layers (region/PROCESS/), each styled: its .qml gives it a renderer of its own.
        for merged, entry in study.get("region", {}).items():
            if not any(g.startswith("Region: ") and merged[:4] in g.replace(" ", "").lower() for g in groups):
                problems.append(f"no region group for {merged} (groups: {groups})")
            for name in entry["layers"]:
                path = os.path.join(out, entry["folder"], name + ".tif")
                found = [layer for layer in layers if os.path.abspath(layer.source()) == os.path.abspath(path)]
                if not found:
                    problems.append(f"{path}: not in the project")
                elif found[0].renderer() is None or found[0].renderer().type() == "singlebandgray":
                    problems.append(f"{path}: not styled (renderer {found[0].renderer() and found[0].renderer().type()})")
    for needed in ("hillshade",) if process == "study" else ("hillshade", "Release"):
        if not any(needed.lower() in (layer.name() + layer.source()).lower() for layer in layers):
            problems.append(f"no {needed} layer in the project")
    # One CRS: the project's is the layers' (also where --crs gave it), the hillshade's and the release's.
    if not project.crs().isValid():
        problems.append("the project has no CRS")
    for layer in layers:
        if layer.crs() != project.crs():
            problems.append(f"'{layer.name()}' is in {layer.crs().authid() or 'no CRS'}, the project in "
                            f"{project.crs().authid() or 'none'}")
    tree = project.layerTreeRoot()
    for layer in layers:
        node = tree.findLayer(layer.id())
        if layer.name() == "Release" and layer.type() == layer.RasterLayer:
            transparency = layer.renderer().rasterTransparency() if layer.renderer() else None
            zero_clear = transparency is not None and transparency.alphaValue(0.0) == 0
            if layer.renderer().type() == "singlebandgray" or not zero_clear:
                problems.append("the raster release is drawn opaque: 0 must be transparent")
        if layer.name().startswith("Trajectories") and node is not None and node.isVisible():
            problems.append("the trajectories are switched on: they belong off by default")
        if layer.name().startswith("Particles"):
            if not layer.temporalProperties().isActive():
                problems.append("the particles are not animated (temporal properties off)")
            if not project.timeSettings().temporalRange().begin().isValid():
                problems.append("the project has no time range for the temporal controller")
    problems += report_problems(project, out, process)
    bottom = project.layerTreeRoot().layerOrder()[-1] if layers else None
    if bottom is None or bottom.name() != "Hillshade":
        problems.append(f"the bottom layer is {bottom.name() if bottom else None}, not the hillshade")
    for problem in problems:
        print(problem)
    os._exit(1 if problems else 0)  # exitQgis after reading a project may crash in QGIS 3.22


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The QGIS project and quicklooks of a finished run (issue 17, item 8; docs/layers.md, "QGIS
project and quicklooks").

usage: run_project.py OUT_DIR PROCESS DEM [RELEASE]

PROCESS is rockfall, mudflow or study. Writes into OUT_DIR:
- project.qgz: every layer of the run styled (its .qml) under its title (its .qmd), grouped,
  over a hillshade of DEM in the layers' CRS, with the release layer (a raster release as a
  transparent-zero overlay), for rock fall the trajectories (switched off), and for a mud flow
  with snapshots the particles, animated by the temporal controller; the intensity, the
  release, the particles and the hillshade are switched on.
- quicklook/<layer>.png for the main layers: the layer over the hillshade, zoomed to the cells
  the process reached, with its legend, a scale bar and its title, drawn by QGIS's own layout
  renderer.
For a study (`talus study`, docs/study.md), OUT_DIR is the study's folder: the project holds the
hazard maps and zones (hazard/), the region's layers (region/PROCESS/: the envelope of each
process's scenarios), then one group per scenario of study.json (its intensity and main layers,
scenarios/NAME/), the detected sources (sources/) and the hillshade; the quicklook is
quicklook/hazard.png. Both are written under temporary names and renamed when complete. The talus program runs this
script on the staging folder of the run's set, before the commit, which OUT_DIR then is; it runs
on Debian's /usr/bin/python3 (python3-qgis).
"""
import json
import os
import shutil
import sys
import time

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ["GDAL_PAM_ENABLED"] = "NO"  # no .aux.xml beside the layers QGIS reads

from osgeo import gdal  # noqa: E402
from qgis.core import (QgsApplication, QgsBilinearRasterResampler, QgsColorRampShader,  # noqa: E402
                       QgsDateTimeRange, QgsLayoutExporter,
                       QgsLayoutItemLabel, QgsLayoutItemLegend, QgsLayoutItemMap, QgsLayoutItemPicture,
                       QgsLayoutItemScaleBar,
                       QgsLayoutPoint, QgsLayoutSize, QgsMapLayerLegendUtils, QgsPrintLayout, QgsProject,
                       QgsLegendRenderer, QgsLegendStyle, QgsRasterLayer, QgsRasterShader, QgsRasterTransparency,
                       QgsRectangle, QgsSingleBandPseudoColorRenderer, QgsUnitTypes, QgsVectorLayer,
                       QgsVectorLayerTemporalProperties)
from qgis.PyQt.QtGui import QColor, QFont  # noqa: E402

# The layers of each process by group, in the layer panel's order (top first); the first group's
# layers and the vectors are switched on.
GROUPS = {
    "rockfall": [("Intensity", ["intensity"]),
                 ("Energy and motion", ["energy_p95", "energy_max", "velocity_max", "jump_height_p95"]),
                 ("Probability and counts", ["reach_probability", "passages", "source_count", "deposits"]),
                 ("Energy losses", ["energy_loss_friction", "energy_loss_deformation"])],
    "mudflow": [("Intensity", ["intensity"]),
                ("Flow", ["flow_depth_max", "velocity_max", "pressure_max", "arrival_time"]),
                ("Deposit and erosion", ["deposit_depth", "erosion_depth"])],
}
PROCESS_WORDS = {"rockfall": "Rock fall", "mudflow": "Mud flow"}
QUICKLOOKS = {"rockfall": ["intensity", "energy_p95", "reach_probability", "velocity_max"],
              "mudflow": ["intensity", "flow_depth_max", "velocity_max", "arrival_time"]}

PAGE_MM = (297.0, 210.0)  # A4 landscape
MAP_MM = (10.0, 22.0, 180.0, 176.0)  # x, y, width, height
QUICKLOOK_DPI = 100


def title_of(layer, name):
    """The .qmd title QGIS read with the layer, else the file stem."""
    layer.loadDefaultMetadata()
    return layer.metadata().title() or name


def band_heading(path):
    """The band description with its unit, for the legend's heading (no "Band 1:" prefix)."""
    dataset = gdal.Open(path)  # kept while its band is read
    return dataset.GetRasterBand(1).GetDescription()


def layers_crs_wkt(paths):
    """The CRS (WKT) of the first of the run's layers at `paths` that has one: the run's CRS,
    also where `--crs` gave it to a DEM without one."""
    for path in paths:
        if os.path.exists(path):
            wkt = gdal.Open(path).GetProjection()
            if wkt:
                return wkt
    return ""


def hillshade(dem_path, path, crs_wkt):
    """GDAL's multidirectional hillshade of the DEM (Byte, as gdaldem writes it) at `path`, in
    the run's CRS, drawn grey with bilinear smoothing. QGIS's own hillshade renderer shades the
    cells it is given, so zoomed in it draws every cell edge as a line."""
    shaded = gdal.DEMProcessing(path, dem_path, "hillshade", format="GTiff", multiDirectional=True,
                                creationOptions=["COMPRESS=DEFLATE", "TILED=YES"])
    if shaded is None:
        raise RuntimeError(f"{dem_path}: GDAL could not shade the DEM")
    if crs_wkt:
        shaded.SetProjection(crs_wkt)  # the DEM's own, or the one --crs gave it
    shaded = None  # closes the file
    layer = QgsRasterLayer(path, "Hillshade", "gdal")
    if not layer.isValid():
        raise RuntimeError(f"{path}: QGIS cannot open the hillshade")
    layer.resampleFilter().setZoomedInResampler(QgsBilinearRasterResampler())
    layer.resampleFilter().setZoomedOutResampler(QgsBilinearRasterResampler())
    return layer


RELEASE_COLOUR = "#000000"


def release_layer(path, crs):
    """The release as QGIS opens it, in the run's CRS where the file has none: a vector layer
    (polygons as black outlines, points and lines black), else a raster drawn as a
    transparent-zero overlay (released cells black at 35 % opacity, 0 and nodata clear), so it
    never hides the map under it."""
    layer = QgsVectorLayer(path, "Release", "ogr")
    if layer.isValid():
        symbol = layer.renderer().symbol() if hasattr(layer.renderer(), "symbol") else None
        if symbol is not None:
            symbol.setColor(QColor(0, 0, 0, 0) if layer.geometryType() == 2 else QColor(RELEASE_COLOUR))
            if layer.geometryType() == 2:
                symbol.symbolLayer(0).setStrokeColor(QColor(RELEASE_COLOUR))
                symbol.symbolLayer(0).setStrokeWidth(0.5)
    else:
        layer = QgsRasterLayer(path, "Release", "gdal")
        if not layer.isValid():
            return None
        shader = QgsColorRampShader()
        shader.setColorRampType(QgsColorRampShader.Discrete)  # a value takes the first item >= it
        shader.setColorRampItemList([QgsColorRampShader.ColorRampItem(0.0, QColor(0, 0, 0, 0), "not released"),
                                     QgsColorRampShader.ColorRampItem(float("inf"), QColor(RELEASE_COLOUR),
                                                                      "released")])
        raster_shader = QgsRasterShader()
        raster_shader.setRasterShaderFunction(shader)
        renderer = QgsSingleBandPseudoColorRenderer(layer.dataProvider(), 1, raster_shader)
        transparent_zero = QgsRasterTransparency.TransparentSingleValuePixel()
        transparent_zero.min, transparent_zero.max, transparent_zero.percentTransparent = 0.0, 0.0, 100.0
        transparency = QgsRasterTransparency()
        transparency.setTransparentSingleValuePixelList([transparent_zero])
        renderer.setRasterTransparency(transparency)
        renderer.setOpacity(0.35)
        layer.setRenderer(renderer)
    if not layer.crs().isValid() and crs.isValid():
        layer.setCrs(crs)
    return layer


def particles_layer(path):
    """particles.gpkg with the style it carries, animated by QGIS's temporal controller: each
    particle is shown from its start_time to its end_time (docs/layers.md, "particles.gpkg")."""
    layer = QgsVectorLayer(path + "|layername=particles", "Particles (snapshots)", "ogr")
    if not layer.isValid():
        return None
    temporal = layer.temporalProperties()
    temporal.setMode(QgsVectorLayerTemporalProperties.ModeFeatureDateTimeStartAndEndFromFields)
    temporal.setStartField("start_time")
    temporal.setEndField("end_time")
    temporal.setIsActive(True)
    return layer


def animate(project, layer):
    """The project's time range: that of the particles, one frame per snapshot interval."""
    start_field, end_field = layer.fields().indexOf("start_time"), layer.fields().indexOf("end_time")
    first, last = layer.minimumValue(start_field), layer.maximumValue(end_field)
    if first is None or last is None:
        return
    project.timeSettings().setTemporalRange(QgsDateTimeRange(first, last))
    times = sorted({feature["time_s"] for feature in layer.getFeatures()})
    if len(times) > 1:
        project.timeSettings().setTimeStep(times[1] - times[0])
        project.timeSettings().setTimeStepUnit(QgsUnitTypes.TemporalSeconds)


def reached_extent(path, margin_cells=10):
    """The bounding box of the cells above 0, widened by a margin; the whole grid when none."""
    dataset = gdal.Open(path)
    values = dataset.GetRasterBand(1).ReadAsArray()
    x0, dx, _, y0, _, dy = dataset.GetGeoTransform()
    rows, cols = (values > 0).nonzero()
    if len(rows) == 0:
        rows, cols = [0, values.shape[0] - 1], [0, values.shape[1] - 1]
    top, bottom = max(min(rows) - margin_cells, 0), min(max(rows) + margin_cells + 1, values.shape[0])
    left, right = max(min(cols) - margin_cells, 0), min(max(cols) + margin_cells + 1, values.shape[1])
    return QgsRectangle(x0 + left * dx, y0 + bottom * dy, x0 + right * dx, y0 + top * dy)


def with_aspect(extent, aspect):
    """`extent` widened about its centre to the width / height ratio `aspect`."""
    width, height = extent.width(), extent.height()
    if width / height < aspect:
        width = height * aspect
    else:
        height = width / aspect
    centre = extent.center()
    return QgsRectangle(centre.x() - width / 2, centre.y() - height / 2, centre.x() + width / 2,
                        centre.y() + height / 2)


CREDIT_KEYS = ("SOURCE", "COPYRIGHT", "TIFFTAG_COPYRIGHT", "ATTRIBUTION", "CREDIT", "LICENSE")
NORTH_ARROW = "arrows/NorthArrow_02.svg"  # one of QGIS's own SVG symbols


def credits_of(paths):
    """The data credits the input files at `paths` carry in their metadata (SOURCE, COPYRIGHT,
    ...), each once, in order; the sample scene's DEM carries its licence's credit this way."""
    found = []
    for path in paths:
        dataset = gdal.OpenEx(path) if path and os.path.exists(path) else None
        if dataset is None:
            continue
        metadata = dataset.GetMetadata() or {}
        for key in CREDIT_KEYS:
            text = metadata.get(key, "").strip()
            if text and text not in found:
                found.append(text)
    return found


def page_facts(out, process, crs, dem_path):
    """The lines every page of a run carries: what made it (software, version, commit, date),
    what it shows (process, scenario or study file, mode), the CRS, and the data credits of its
    inputs, read from run.json (or study.json) in OUT and from the inputs' metadata."""
    record_path = os.path.join(out, "study.json" if process == "study" else "run.json")
    record = {}
    if os.path.exists(record_path):
        with open(record_path, encoding="utf-8") as file:
            record = json.load(file)
    version = record.get("version") or record.get("talus_version", "")
    commit = record.get("git_commit", "")[:7]
    when = (record.get("finished_utc") or record.get("started_utc") or "")[:16].replace("T", " ")
    if not when and os.path.exists(record_path):
        when = time.strftime("%Y-%m-%d %H:%M", time.gmtime(os.path.getmtime(record_path)))
    made = f"Talus {version}" + (f" ({commit})" if commit else "") + (f", run {when} UTC" if when else "")
    inputs = record.get("inputs", {})
    paths = [dem_path] + [e.get("path", "") for e in inputs.values() if isinstance(e, dict)]
    scenario = inputs.get("scenario", {}).get("path", "") if isinstance(inputs.get("scenario"), dict) else ""
    scenario = scenario or record.get("study", "")
    shown = {"rockfall": "Rock fall", "mudflow": "Mud flow", "study": "Study"}[process]
    mode = record.get("parameters", {}).get("run", {}).get("mode", "") if process == "rockfall" else ""
    what = shown + (f", {mode} mode" if mode else "") + \
        (f", {'study' if process == 'study' else 'scenario'} {os.path.basename(scenario)}" if scenario
         else ", default parameters")
    crs_text = f"CRS: {crs.description()} ({crs.authid()})" if crs.isValid() else "CRS: none"
    credits = credits_of(paths)
    return [f"{what}. {crs_text}. {made}.", "Data: " + "; ".join(credits) if credits else ""]


def add_label(layout, text, size, x, y, width, height):
    label = QgsLayoutItemLabel(layout)
    label.setText(text)
    label.setFont(QFont("DejaVu Sans", size))
    label.attemptMove(QgsLayoutPoint(x, y, QgsUnitTypes.LayoutMillimeters))
    label.attemptResize(QgsLayoutSize(width, height, QgsUnitTypes.LayoutMillimeters))
    layout.addLayoutItem(label)
    return label


def page(project, title, legend_layers, map_layers, extent, facts):
    """One A4 landscape page: the map of `map_layers` (top first) framed, its title, a legend of
    `legend_layers` only (one heading each: a raster's band description with its unit, a
    vector's name), a scale bar, a north arrow, and the facts at the foot. Returns the layout and
    the legend's tree, which must outlive any export."""
    layout = QgsPrintLayout(project)
    layout.initializeDefaults()
    layout.setName(title)
    layout.pageCollection().page(0).setPageSize(QgsLayoutSize(*PAGE_MM, QgsUnitTypes.LayoutMillimeters))
    x, y, width, height = MAP_MM
    map_item = QgsLayoutItemMap(layout)
    map_item.attemptMove(QgsLayoutPoint(x, y, QgsUnitTypes.LayoutMillimeters))
    map_item.attemptResize(QgsLayoutSize(width, height, QgsUnitTypes.LayoutMillimeters))
    map_item.setFrameEnabled(True)
    layout.addLayoutItem(map_item)
    map_item.setCrs(map_layers[0].crs())
    map_item.setLayers(map_layers)
    map_item.setExtent(with_aspect(extent, width / height))  # the item's own shape: no resize

    add_label(layout, title, 16, x, 8, PAGE_MM[0] - 20, 12)

    legend = QgsLayoutItemLegend(layout)
    legend.setLinkedMap(map_item)
    legend.setAutoUpdateModel(False)  # the legend keeps a tree of its own, saved with the layout
    root = legend.model().rootGroup()
    root.removeAllChildren()
    for layer in legend_layers:
        node = root.addLayer(layer)
        if layer.type() == layer.RasterLayer:
            QgsMapLayerLegendUtils.setLegendNodeUserLabel(node, 0, band_heading(layer.source()))
            QgsLegendRenderer.setNodeLegendStyle(node, QgsLegendStyle.Hidden)  # the band heading names it
        elif layer.name().startswith("Hazard zones"):
            node.setCustomProperty("legend/title-label", "Hazard degree")  # the page's title says the rest
    for node in root.findLayers():
        legend.model().refreshLayerLegend(node)
    legend.setTitle("")
    legend.attemptMove(QgsLayoutPoint(x + width + 8, y, QgsUnitTypes.LayoutMillimeters))
    layout.addLayoutItem(legend)

    arrow = QgsLayoutItemPicture(layout)
    arrow.setPicturePath(next((os.path.join(folder, NORTH_ARROW) for folder in QgsApplication.svgPaths()
                               if os.path.exists(os.path.join(folder, NORTH_ARROW))), NORTH_ARROW))
    arrow.setLinkedMap(map_item)
    arrow.setNorthMode(QgsLayoutItemPicture.GridNorth)
    arrow.attemptMove(QgsLayoutPoint(x + width + 8, y + height - 42, QgsUnitTypes.LayoutMillimeters))
    arrow.attemptResize(QgsLayoutSize(12, 20, QgsUnitTypes.LayoutMillimeters))
    layout.addLayoutItem(arrow)

    scale = QgsLayoutItemScaleBar(layout)
    scale.setStyle("Single Box")
    scale.setLinkedMap(map_item)
    scale.setUnits(QgsUnitTypes.DistanceMeters)
    scale.setUnitLabel("m")
    scale.applyDefaultSize()
    scale.attemptMove(QgsLayoutPoint(x + width + 8, y + height - 15, QgsUnitTypes.LayoutMillimeters))
    layout.addLayoutItem(scale)

    foot = "\n".join(line for line in facts if line)
    add_label(layout, foot, 8, x, y + height + 2, PAGE_MM[0] - 20, PAGE_MM[1] - y - height - 4)
    return layout, root


def layer_page(project, layer, base_layers, extent, facts):
    """The page of a layer over the base layers: its legend holds the layer and the release."""
    return page(project, layer.name(), [layer] + [b for b in base_layers if b.name() == "Release"],
                [layer] + base_layers, extent, facts)


def quicklook(project, layer, base_layers, extent, facts, path):
    """One page of a layer over the base layers, as PNG."""
    layout, root = layer_page(project, layer, base_layers, extent, facts)
    settings = QgsLayoutExporter.ImageExportSettings()
    settings.dpi = QUICKLOOK_DPI
    settings.exportMetadata = False  # GDAL cannot add it to a PNG
    # QGIS then tries to georeference the PNG through GDAL, which cannot update a PNG: quiet.
    gdal.PushErrorHandler("CPLQuietErrorHandler")
    result = QgsLayoutExporter(layout).exportToImage(path, settings)
    gdal.PopErrorHandler()
    if result != QgsLayoutExporter.Success:
        raise RuntimeError(f"{path}: the layout could not be exported (QGIS code {result})")
    return root  # the legend's tree must outlive the export


def report_layout(project, layer, base_layers, extent, facts, path):
    """The report page, "Report": the main layer over the base layers, saved in the project's
    layouts (Project > Layouts) for the user to edit, and exported as PDF at `path`."""
    layout, root = layer_page(project, layer, base_layers, extent, facts)
    layout.setName("Report")
    project.layoutManager().addLayout(layout)
    result = QgsLayoutExporter(layout).exportToPdf(path, QgsLayoutExporter.PdfExportSettings())
    if result != QgsLayoutExporter.Success:
        raise RuntimeError(f"{path}: the report page could not be exported (QGIS code {result})")
    return root


def add_raster(project, group, path, name, visible, layers):
    """The layer at `path` (styled by its .qml) under its .qmd title in `group`."""
    layer = QgsRasterLayer(path, name, "gdal")  # loads NAME.qml
    if not layer.isValid():
        raise RuntimeError(f"{path}: QGIS cannot open the layer")
    layer.setName(title_of(layer, name))
    project.addMapLayer(layer, False)
    node = group.addLayer(layer)
    QgsMapLayerLegendUtils.setLegendNodeUserLabel(node, 0, band_heading(path))
    node.setItemVisibilityChecked(visible)
    layers[name] = (layer, path)


def finish(project, out, process, dem_path, base, temporary_hillshade, quicklooks):
    """Writes the quicklooks ([(layer, path, base layers)]), the report page of the first of them
    (quicklook/report.pdf, and the layout "Report" in the project) and the project, renaming
    each when complete; the project names the hillshade by its final path, so it is renamed
    first."""
    quicklook_dir = os.path.join(out, ".quicklook.part")
    shutil.rmtree(quicklook_dir, ignore_errors=True)
    os.makedirs(quicklook_dir)
    facts = page_facts(out, process, project.crs(), dem_path)
    keep = []
    for name, (layer, path), base_layers in quicklooks:
        keep.append(quicklook(project, layer, base_layers, reached_extent(path), facts,
                              os.path.join(quicklook_dir, name + ".png")))
    if quicklooks:
        name, (layer, path), base_layers = quicklooks[0]
        keep.append(report_layout(project, layer, base_layers, reached_extent(path), facts,
                                  os.path.join(quicklook_dir, "report.pdf")))
    os.replace(temporary_hillshade, os.path.join(out, "hillshade.tif"))
    base.setDataSource(os.path.join(out, "hillshade.tif"), "Hillshade", "gdal")
    base.resampleFilter().setZoomedInResampler(QgsBilinearRasterResampler())
    base.resampleFilter().setZoomedOutResampler(QgsBilinearRasterResampler())
    temporary = os.path.join(out, ".project.part.qgz")
    if not project.write(temporary):
        raise RuntimeError(f"{temporary}: QGIS could not write the project: {project.error()}")
    os.replace(temporary, os.path.join(out, "project.qgz"))
    final_dir = os.path.join(out, "quicklook")
    shutil.rmtree(final_dir, ignore_errors=True)
    os.replace(quicklook_dir, final_dir)


def build_study(out, dem_path):
    """The study's project: hazard, the region, then each scenario, the sources and the hillshade."""
    with open(os.path.join(out, "study.json"), encoding="utf-8") as file:
        study = json.load(file)
    project = QgsProject.instance()
    temporary_hillshade = os.path.join(out, ".hillshade.part.tif")
    crs_wkt = layers_crs_wkt([os.path.join(out, "hazard", "hazard.tif")] +
                             [os.path.join(out, s["folder"], "intensity.tif") for s in study["scenarios"]])
    base = hillshade(dem_path, temporary_hillshade, crs_wkt)
    project.setCrs(base.crs())
    root = project.layerTreeRoot()
    layers = {}
    hazard = root.addGroup("Hazard")
    zones_path = os.path.join(out, "hazard", "hazard_zones.gpkg")
    zones = None
    if os.path.exists(zones_path):
        zones = QgsVectorLayer(zones_path + "|layername=hazard_zones", "Hazard zones", "ogr")  # loads its .qml
        if zones.isValid():
            project.addMapLayer(zones, False)
            hazard.addLayer(zones)
        else:
            zones = None
    for name in ["hazard", "hazard_rockfall", "hazard_mudflow"]:
        path = os.path.join(out, "hazard", name + ".tif")
        if os.path.exists(path):
            add_raster(project, hazard, path, name, name == "hazard" and zones is None, layers)
    for process, entry in study.get("region", {}).items():
        group = root.addGroup(f"Region: {PROCESS_WORDS[process].lower()}, envelope of its scenarios")
        for name in entry["layers"]:
            add_raster(project, group, os.path.join(out, entry["folder"], name + ".tif"), f"region/{process}/{name}",
                       False, layers)
        group.setExpanded(False)
    for scenario in study["scenarios"]:
        process = scenario["process"]
        group = root.addGroup(f"{scenario['name']} ({PROCESS_WORDS[process].lower()}, "
                              f"return period {scenario['return_period_years']:g} years)")
        names = GROUPS[process][0][1] + GROUPS[process][1][1]  # intensity and the main layers
        for name in names:
            path = os.path.join(out, scenario["folder"], name + ".tif")
            if os.path.exists(path):
                add_raster(project, group, path, f"{scenario['name']}/{name}", False, layers)
        group.setExpanded(False)
    sources_dir = os.path.join(out, "sources")
    if os.path.isdir(sources_dir):
        group = root.addGroup("Rock-fall sources from the slope")
        for file_name in sorted(os.listdir(sources_dir)):
            if file_name.endswith(".tif"):
                add_raster(project, group, os.path.join(sources_dir, file_name), "sources/" + file_name[:-4], False,
                           layers)
    project.addMapLayer(base, False)
    root.addLayer(base)
    # The study's page shows the generalised zones, named by degree; the raw cells where none exist.
    if "hazard" in layers and zones is not None:
        title = layers["hazard"][0].name()
        zones.setName("Hazard zones: " + title[0].lower() + title[1:])
        quicklooks = [("hazard", (zones, layers["hazard"][1]), [base])]
    else:
        quicklooks = [("hazard", layers["hazard"], [base])] if "hazard" in layers else []
    finish(project, out, "study", dem_path, base, temporary_hillshade, quicklooks)


def build(out, process, dem_path, release_path):
    project = QgsProject.instance()
    temporary_hillshade = os.path.join(out, ".hillshade.part.tif")
    crs_wkt = layers_crs_wkt([os.path.join(out, name + ".tif") for _, names in GROUPS[process] for name in names])
    base = hillshade(dem_path, temporary_hillshade, crs_wkt)
    project.setCrs(base.crs())
    root = project.layerTreeRoot()
    group = root.addGroup(PROCESS_WORDS[process])
    layers = {}
    for group_name, names in GROUPS[process]:
        sub = group.addGroup(group_name)
        for name in names:
            path = os.path.join(out, name + ".tif")
            if os.path.exists(path):
                add_raster(project, sub, path, name, group_name == "Intensity", layers)
        sub.setExpanded(group_name == "Intensity")
    vectors = []  # top first, with whether each is switched on
    if release_path:
        release = release_layer(release_path, base.crs())
        if release is not None:
            vectors.append((release, True))
    trajectories = os.path.join(out, "trajectories.gpkg")
    if os.path.exists(trajectories):
        lines = QgsVectorLayer(trajectories + "|layername=trajectories", "Trajectories (sample)", "ogr")
        if lines.isValid():
            vectors.append((lines, False))
    particles = os.path.join(out, "particles.gpkg")
    if os.path.exists(particles):
        points = particles_layer(particles)
        if points is not None:
            vectors.append((points, True))
            animate(project, points)
    for layer, visible in reversed(vectors):
        project.addMapLayer(layer, False)
        root.insertLayer(0, layer).setItemVisibilityChecked(visible)
    project.addMapLayer(base, False)
    root.addLayer(base)

    release = [v for v, _ in vectors if v.name() == "Release"]
    quicklooks = [(name, layers[name], release + [base]) for name in QUICKLOOKS[process] if name in layers]
    finish(project, out, process, dem_path, base, temporary_hillshade, quicklooks)


def main():
    if len(sys.argv) not in (4, 5) or sys.argv[2] not in list(GROUPS) + ["study"]:
        print(__doc__, file=sys.stderr)
        return 2
    out, process, dem = sys.argv[1:4]
    release = sys.argv[4] if len(sys.argv) == 5 else ""
    app = QgsApplication([], False)
    app.initQgis()
    try:
        if process == "study":
            build_study(out, dem)
        else:
            build(out, process, dem, release)
    except RuntimeError as error:
        print(f"project: {error}", file=sys.stderr)
        os._exit(1)
    # exitQgis after layouts may crash in 3.22 (docs/qgis.md); everything is written by now.
    os._exit(0)


if __name__ == "__main__":
    sys.exit(main())

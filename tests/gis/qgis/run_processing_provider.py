#!/usr/bin/python3
"""Runs the Talus Processing provider (gis/qgis/talus_processing) headless, as QGIS's toolbox would:
rock fall on the sample scene with two runs per source, an invalid parameter, and scene info.

usage: run_processing_provider.py PLUGIN_FOLDER TALUS_PROGRAM SAMPLE_DEM_FOLDER WORK_FOLDER

Checks: the provider lists rockfall, mudflow and info with every parameter of `talus params`;
the rock-fall run writes the layers and queues each styled layer for the project with a title
naming the process; a scenario value talus refuses fails with talus's own one-line error; info
returns the scene. Prints one line per problem; exit 0 when none.
"""
import json
import os
import subprocess
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ["GDAL_PAM_ENABLED"] = "NO"  # no .aux.xml beside the sample scene's files
plugins, program, sample, work = sys.argv[1:5]
os.environ["TALUS_PROGRAM"] = program
sys.path.insert(0, plugins)
sys.path.insert(0, "/usr/share/qgis/python/plugins")

from qgis.core import (QgsApplication, QgsProcessingContext, QgsProcessingFeedback,  # noqa: E402
                       QgsProcessingException, QgsProcessingParameterNumber, QgsProject, QgsRasterLayer,
                       QgsVectorLayer)

app = QgsApplication([], False)
app.initQgis()
from processing.core.Processing import Processing  # noqa: E402
Processing.initialize()
import processing  # noqa: E402
from talus_processing.provider import TalusProvider  # noqa: E402

problems = []
provider = TalusProvider()
QgsApplication.processingRegistry().addProvider(provider)
names = sorted(a.name() for a in provider.algorithms())
if names != ["info", "mudflow", "rockfall"]:
    problems.append(f"algorithms {names}")
table = json.loads(subprocess.run([program, "params"], capture_output=True, text=True, check=True).stdout)
for command in ("rockfall", "mudflow"):
    algorithm = QgsApplication.processingRegistry().algorithmById(f"talus:{command}")
    offered = {d.name() for d in algorithm.parameterDefinitions()}
    missing = [f"{e['section']}__{e['name']}" for e in table[command] if f"{e['section']}__{e['name']}" not in offered]
    if missing:
        problems.append(f"{command}: parameters of talus params not offered: {missing}")
    # Every range of talus params bounds its number in the dialog (issue 18, item 1).
    for e in table[command]:
        definition = algorithm.parameterDefinition(f"{e['section']}__{e['name']}")
        if "range" not in e or not isinstance(definition, QgsProcessingParameterNumber):
            continue
        low = min(e["range"]["min"], e["range"].get("off", e["range"]["min"]))
        if definition.minimum() != low or definition.maximum() < e["range"]["max"]:
            problems.append(f"{command}: {definition.name()} bounded {definition.minimum()}-{definition.maximum()}, "
                            f"not by its range {e['range']}")


class Progress(QgsProcessingFeedback):
    def __init__(self):
        super().__init__()
        self.steps = []

    def setProgress(self, value):  # noqa: N802
        self.steps.append(value)
        super().setProgress(value)


dem = QgsRasterLayer(os.path.join(sample, "dem.tif"), "dem")
release = QgsVectorLayer(os.path.join(sample, "rockfall_release.gpkg"), "release", "ogr")
context = QgsProcessingContext()
context.setProject(QgsProject.instance())
feedback = Progress()
out = os.path.join(work, "rockfall")
result = processing.run("talus:rockfall", {"DEM": dem, "RELEASE": release, "run__runs": 2, "OUTPUT": out},
                        context=context, feedback=feedback)
if result.get("OUTPUT") != out or not os.path.exists(os.path.join(out, "energy_max.tif")):
    problems.append(f"rock fall wrote no layers in {out}: {result}")
if not feedback.steps or max(feedback.steps) < 90:
    problems.append(f"progress not reported: {feedback.steps[:5]}")
queued = context.layersToLoadOnCompletion()
titles = sorted(details.name for details in queued.values())
if "energy max (rock fall)" not in titles or len(titles) < 9:
    problems.append(f"layers queued for the project: {titles}")
for path in queued:
    layer = QgsRasterLayer(path, "check")
    if not layer.isValid() or layer.renderer().type() == "multibandcolor":
        problems.append(f"{path}: not a valid styled layer")
with open(os.path.join(out, "run.json"), encoding="utf-8") as run_file:
    record = json.load(run_file)
if record["parameters"]["run"]["runs"] != 2:
    problems.append(f"run.json runs {record['parameters']['run']['runs']}, not the 2 given")

rockfall_algorithm = QgsApplication.processingRegistry().algorithmById("talus:rockfall")
if rockfall_algorithm.parameterDefinition("rock__density").checkValueIsAcceptable(50.0):
    problems.append("the dialog accepts a density of 50 kg/m3, outside its range")
# An excluded end of a range passes the dialog's inclusive bounds; talus refuses it.
try:
    processing.run("talus:rockfall", {"DEM": dem, "RELEASE": release, "run__convergence_tolerance": 0.0,
                                      "OUTPUT": os.path.join(work, "refused")}, context=context, feedback=Progress())
    problems.append("a convergence tolerance of 0 was not refused")
except QgsProcessingException as error:
    if "talus: error:" not in str(error) or "convergence_tolerance" not in str(error):
        problems.append(f"refusal without talus's error line: {error}")

info = processing.run("talus:info", {"DEM": dem}, context=context, feedback=Progress())
if "EPSG:31287" not in info.get("INFO", ""):
    problems.append(f"info: {info}")

for problem in problems:
    print(problem)
sys.stdout.flush()
# Leaves without QGIS's teardown, which can crash once Processing's providers are loaded.
os._exit(1 if problems else 0)

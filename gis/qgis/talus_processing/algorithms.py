"""Processing algorithms that run the talus program (docs/qgis.md): `talus rockfall` and
`talus mudflow` with every scenario parameter of `talus params` (the ones left at their default
are not passed), progress and cancel through QgsProcessingFeedback, talus's one-line errors as
the algorithm's error, and the styled layers added to the project; `talus info` on a DEM."""
import os
import re
import subprocess

from qgis.core import (QgsProcessing, QgsProcessingAlgorithm, QgsProcessingContext, QgsProcessingException,
                       QgsProcessingOutputString, QgsProcessingParameterBoolean, QgsProcessingParameterDefinition,
                       QgsProcessingParameterFolderDestination, QgsProcessingParameterMapLayer,
                       QgsProcessingParameterNumber, QgsProcessingParameterRasterLayer, QgsProcessingParameterString,
                       QgsProcessingUtils, QgsProviderRegistry)

PROGRESS = re.compile(r"^Progress: (\d+)%")

# The parameters shown first; every other one is under "Advanced parameters".
MAIN_PARAMETERS = {
    "rockfall": {("run", "mode"), ("run", "runs"), ("run", "seed"), ("rock", "block_shape"), ("rock", "block_size"),
                 ("rock", "density")},
    "mudflow": {("mud", "material"), ("mud", "particle_size"), ("mud", "release_depth"), ("mud", "depth_field"),
                ("run", "duration"), ("run", "seed")},
}

TITLES = {"rockfall": "Rock fall", "mudflow": "Mud flow"}

# Layer titles in the project, by process, so that rock-fall and mud-flow layers of one quantity differ.
PROCESS_WORDS = {"rockfall": "rock fall", "mudflow": "mud flow"}


def file_of(layer):
    """The file path of a layer's source, without the provider's options (|layername=...)."""
    parts = QgsProviderRegistry.instance().decodeUri(layer.providerType(), layer.source())
    return parts.get("path") or layer.source().split("|")[0]


def toml_value(value):
    """A parameter value as TOML text."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    return '"' + str(value).replace("\\", "\\\\").replace('"', '\\"') + '"'


def number_bounds(entry):
    """The lowest and highest value the dialog accepts: talus's range (issue 18), widened to its
    'off' value where it has one. QGIS bounds are inclusive; talus itself refuses an excluded end."""
    allowed = entry.get("range")
    if not allowed:
        return {}
    low, high = allowed["min"], allowed["max"]
    if "off" in allowed:
        low, high = min(low, allowed["off"]), max(high, allowed["off"])
    return {"minValue": low, "maxValue": high}


def parameter_key(entry):
    return f"{entry['section']}__{entry['name']}"


def run_talus(arguments, feedback):
    """Runs talus, its progress lines into the feedback; returns (exit code, error lines, other lines)."""
    errors, lines = [], []
    with subprocess.Popen(arguments, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1) as process:
        for line in process.stdout:
            line = line.rstrip("\n")
            if feedback.isCanceled():
                process.kill()
                break
            progress = PROGRESS.match(line)
            if progress:
                feedback.setProgress(int(progress.group(1)))
                feedback.setProgressText(line)
            elif line.startswith("talus: error:"):
                errors.append(line)
            else:
                lines.append(line)
                feedback.pushInfo(line)
    return process.returncode, errors, lines


class TalusRunAlgorithm(QgsProcessingAlgorithm):
    """`talus rockfall` or `talus mudflow` with the parameters of `talus params`."""

    def __init__(self, command, table):
        super().__init__()
        self.command = command
        self.table = table

    def createInstance(self):  # noqa: N802 (QGIS's name)
        return TalusRunAlgorithm(self.command, self.table)

    def name(self):
        return self.command

    def displayName(self):  # noqa: N802
        return TITLES[self.command]

    def shortHelpString(self):  # noqa: N802
        return (f"Runs talus {self.command} and adds its styled layers to the project. Every parameter is the "
                f"scenario parameter of the same section and name (talus params; docs/{self.command}.md); only "
                "those changed from their default are passed to talus, in a scenario file.")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.addParameter(QgsProcessingParameterRasterLayer("DEM", "DEM (elevations in metres)"))
        self.addParameter(QgsProcessingParameterMapLayer(
            "RELEASE", "Release (raster, or points / polygons)",
            types=[QgsProcessing.TypeRaster, QgsProcessing.TypeVectorAnyGeometry]))
        self.addParameter(QgsProcessingParameterRasterLayer("LITHOLOGY", "Lithology classes", optional=True))
        self.addParameter(QgsProcessingParameterRasterLayer("VEGETATION", "Vegetation", optional=True))
        if self.command == "mudflow":
            self.addParameter(QgsProcessingParameterRasterLayer("ERODIBLE", "Erodible depth (m)", optional=True))
        for entry in self.table:
            parameter = self._parameter(entry)
            if (entry["section"], entry["name"]) not in MAIN_PARAMETERS[self.command]:
                parameter.setFlags(parameter.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
            self.addParameter(parameter)
        self.addParameter(QgsProcessingParameterFolderDestination("OUTPUT", "Output folder"))

    @staticmethod
    def _parameter(entry):
        unit = f" ({entry['unit']})" if entry["unit"] and entry["unit"] != "-" else ""
        label = f"[{entry['section']}] {entry['name']}{unit}: {entry['description']}"
        key, default = parameter_key(entry), entry["default"]
        if isinstance(default, bool):
            return QgsProcessingParameterBoolean(key, label, defaultValue=default)
        if isinstance(default, int):
            return QgsProcessingParameterNumber(key, label, QgsProcessingParameterNumber.Integer, defaultValue=default,
                                                **number_bounds(entry))
        if isinstance(default, float):
            return QgsProcessingParameterNumber(key, label, QgsProcessingParameterNumber.Double, defaultValue=default,
                                                **number_bounds(entry))
        return QgsProcessingParameterString(key, label, defaultValue=str(default))

    def _value(self, entry, parameters, context):
        key, default = parameter_key(entry), entry["default"]
        if isinstance(default, bool):
            return self.parameterAsBoolean(parameters, key, context)
        if isinstance(default, int):
            return self.parameterAsInt(parameters, key, context)
        if isinstance(default, float):
            return self.parameterAsDouble(parameters, key, context)
        return self.parameterAsString(parameters, key, context)

    def _scenario(self, parameters, context):
        """The TOML text of the parameters whose value differs from talus's default."""
        sections = {}
        for entry in self.table:
            value = self._value(entry, parameters, context)
            if value != entry["default"]:
                sections.setdefault(entry["section"], []).append(f"{entry['name']} = {toml_value(value)}")
        return "".join(f"[{section}]\n" + "\n".join(lines) + "\n\n" for section, lines in sections.items())

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        from .provider import talus_program
        program = talus_program()
        if program is None:
            raise QgsProcessingException("the talus program was not found: put it on PATH or set TALUS_PROGRAM")
        out = self.parameterAsString(parameters, "OUTPUT", context)
        arguments = [program, self.command, "--dem", file_of(self.parameterAsRasterLayer(parameters, "DEM", context)),
                     "--release", file_of(self.parameterAsLayer(parameters, "RELEASE", context)), "--out", out]
        for key, flag in (("LITHOLOGY", "--lithology"), ("VEGETATION", "--vegetation"), ("ERODIBLE", "--erodible")):
            if key in [d.name() for d in self.parameterDefinitions()]:
                layer = self.parameterAsRasterLayer(parameters, key, context)
                if layer is not None:
                    arguments += [flag, file_of(layer)]
        scenario = self._scenario(parameters, context)
        if scenario:
            # In Processing's temporary folder, which QGIS removes when it quits.
            path = QgsProcessingUtils.generateTempFilename(f"talus_{self.command}_scenario.toml")
            with open(path, "w", encoding="utf-8") as f:
                f.write(scenario)
            arguments += ["--scenario", path]
            feedback.pushInfo(f"scenario {path}:\n{scenario}")
        feedback.pushCommandInfo(" ".join(arguments))
        code, errors, lines = run_talus(arguments, feedback)
        if feedback.isCanceled():
            raise QgsProcessingException("cancelled: talus stopped, nothing written")
        if code != 0:
            raise QgsProcessingException("\n".join(errors or lines[-5:]) or f"talus exited with code {code}")
        for name in sorted(os.listdir(out)):
            if name.endswith(".tif") and name != "hillshade.tif":  # the project's backdrop, not a result
                title = f"{name[:-4].replace('_', ' ')} ({PROCESS_WORDS[self.command]})"
                details = QgsProcessingContext.LayerDetails(title, context.project(), "")
                context.addLayerToLoadOnCompletion(os.path.join(out, name), details)
        return {"OUTPUT": out}


class TalusInfoAlgorithm(QgsProcessingAlgorithm):
    """`talus info`: the aligned scene (grid, CRS, classes, problems) of a DEM."""

    def createInstance(self):  # noqa: N802
        return TalusInfoAlgorithm()

    def name(self):
        return "info"

    def displayName(self):  # noqa: N802
        return "Scene info"

    def shortHelpString(self):  # noqa: N802
        return "Prints what talus reads from a DEM and its lithology and vegetation: grid, CRS, classes, problems."

    def initAlgorithm(self, config=None):  # noqa: N802
        self.addParameter(QgsProcessingParameterRasterLayer("DEM", "DEM (elevations in metres)"))
        self.addParameter(QgsProcessingParameterRasterLayer("LITHOLOGY", "Lithology classes", optional=True))
        self.addParameter(QgsProcessingParameterRasterLayer("VEGETATION", "Vegetation", optional=True))
        self.addOutput(QgsProcessingOutputString("INFO", "Scene"))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        from .provider import talus_program
        program = talus_program()
        if program is None:
            raise QgsProcessingException("the talus program was not found: put it on PATH or set TALUS_PROGRAM")
        arguments = [program, "info", file_of(self.parameterAsRasterLayer(parameters, "DEM", context))]
        for key, flag in (("LITHOLOGY", "--lithology"), ("VEGETATION", "--vegetation")):
            layer = self.parameterAsRasterLayer(parameters, key, context)
            if layer is not None:
                arguments += [flag, file_of(layer)]
        code, errors, lines = run_talus(arguments, feedback)
        if code != 0:
            raise QgsProcessingException("\n".join(errors or lines[-5:]) or f"talus exited with code {code}")
        return {"INFO": "\n".join(lines)}

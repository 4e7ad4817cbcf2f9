#!/usr/bin/python3
"""Installs talus-qgis-plugin.zip as QGIS's "Install from ZIP" does, headless (ctest label install).

usage: check_plugin_zip.py ZIP TALUS_PROGRAM VERSION

Checks the zip's layout (one folder at its root, metadata.txt in it with the fields QGIS reads
and the program's version, no compiled Python), unpacks it with QGIS's own unzip into an empty
plugin folder, and lets qgis.utils find, load and start it as the plugin manager does: the Talus
provider must then be in the Processing registry with its algorithms. Prints one line per
problem; exit 0 when none.
"""
import configparser
import os
import sys
import tempfile
import zipfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
zip_path, program, version = sys.argv[1:4]
os.environ["TALUS_PROGRAM"] = program
sys.path.insert(0, "/usr/share/qgis/python/plugins")
sys.path.insert(0, "/usr/share/qgis/python")

problems = []
with zipfile.ZipFile(zip_path) as archive:
    names = archive.namelist()
    roots = {name.split("/")[0] for name in names}
    if roots != {"talus_processing"}:
        problems.append(f"the zip's root holds {sorted(roots)}, not the one folder talus_processing")
    if any("__pycache__" in name or name.endswith(".pyc") for name in names):
        problems.append("the zip holds compiled Python")
    if "talus_processing/__init__.py" not in names:
        problems.append("talus_processing/__init__.py is not in the zip")
    if "talus_processing/metadata.txt" not in names:
        problems.append("talus_processing/metadata.txt is not in the zip")
    else:
        metadata = configparser.ConfigParser()
        metadata.read_string(archive.read("talus_processing/metadata.txt").decode("utf-8"))
        general = metadata["general"] if metadata.has_section("general") else {}
        for field in ("name", "qgisMinimumVersion", "description", "about", "version", "author", "email"):
            if not general.get(field):
                problems.append(f"metadata.txt has no {field}")
        if general.get("version") != version:
            problems.append(f"metadata.txt's version is {general.get('version')}, the program's {version}")
        if general.get("hasProcessingProvider") != "yes":
            problems.append("metadata.txt does not declare hasProcessingProvider=yes")

if not problems:
    from qgis.core import QgsApplication  # noqa: E402
    app = QgsApplication([], False)
    app.initQgis()
    from processing.core.Processing import Processing  # noqa: E402
    Processing.initialize()
    import qgis.utils  # noqa: E402
    from pyplugin_installer.unzip import unzip  # noqa: E402

    with tempfile.TemporaryDirectory() as plugins:
        unzip(zip_path, plugins)
        # QGIS puts the profile's plugin folder on the Python path and in plugin_paths at start.
        sys.path.insert(0, plugins)
        qgis.utils.plugin_paths = [plugins]
        qgis.utils.updateAvailablePlugins()
        if "talus_processing" not in qgis.utils.available_plugins:
            problems.append("QGIS does not find talus_processing in the unpacked zip")
        elif not qgis.utils.loadPlugin("talus_processing"):
            problems.append("QGIS cannot import talus_processing")
        elif not qgis.utils.startProcessingPlugin("talus_processing"):
            problems.append("QGIS cannot start talus_processing's Processing provider")
        else:
            provider = QgsApplication.processingRegistry().providerById("talus")
            if provider is None:
                problems.append("the Processing registry has no talus provider")
            else:
                found = sorted(a.name() for a in provider.algorithms())
                if found != ["info", "mudflow", "rockfall"]:
                    problems.append(f"the talus provider offers {found}")
            qgis.utils.unloadPlugin("talus_processing")
    app.exitQgis()

for line in problems:
    print(line)
sys.exit(1 if problems else 0)

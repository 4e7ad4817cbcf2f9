"""The Talus Processing provider: rock fall, mud flow and scene info, their parameters read from
`talus params` so that the toolbox always offers what the installed program takes (docs/qgis.md)."""
import json
import os
import shutil
import subprocess

from qgis.core import QgsProcessingProvider

from .algorithms import TalusInfoAlgorithm, TalusRunAlgorithm

# Environment variable naming the talus program; otherwise `talus` on PATH.
PROGRAM_VARIABLE = "TALUS_PROGRAM"


def talus_program():
    """The talus executable: $TALUS_PROGRAM, else `talus` on PATH; None when neither exists."""
    named = os.environ.get(PROGRAM_VARIABLE)
    if named:
        return named if os.path.isfile(named) and os.access(named, os.X_OK) else None
    return shutil.which("talus")


def program_parameters(program):
    """`talus params` as a dict (mudflow, rockfall: lists of {section, name, unit, default, description})."""
    done = subprocess.run([program, "params"], capture_output=True, text=True, timeout=60, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"{program} params failed: {done.stderr.strip()}")
    return json.loads(done.stdout)


class TalusProvider(QgsProcessingProvider):
    def __init__(self):
        super().__init__()
        self._problem = None

    def id(self):
        return "talus"

    def name(self):
        return "Talus"

    def longName(self):  # noqa: N802 (QGIS's name)
        return "Talus rock-fall and mud-flow hazard mapper"

    def loadAlgorithms(self):  # noqa: N802
        program = talus_program()
        if program is None:
            self._problem = f"the talus program was not found: put it on PATH or set {PROGRAM_VARIABLE}"
            return
        try:
            table = program_parameters(program)
        except (OSError, RuntimeError, ValueError, subprocess.TimeoutExpired) as error:
            self._problem = f"the talus program's parameters could not be read: {error}"
            return
        self.addAlgorithm(TalusRunAlgorithm("rockfall", table["rockfall"]))
        self.addAlgorithm(TalusRunAlgorithm("mudflow", table["mudflow"]))
        self.addAlgorithm(TalusInfoAlgorithm())

    def warningMessage(self):  # noqa: N802
        return self._problem or ""

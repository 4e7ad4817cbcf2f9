"""Registers the Talus provider with QGIS's Processing framework, in the desktop and in qgis_process."""
from qgis.core import QgsApplication

from .provider import TalusProvider


class TalusPlugin:
    def __init__(self):
        self.provider = None

    def initProcessing(self):  # noqa: N802 (QGIS's name)
        self.provider = TalusProvider()
        QgsApplication.processingRegistry().addProvider(self.provider)

    def initGui(self):  # noqa: N802
        self.initProcessing()

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)

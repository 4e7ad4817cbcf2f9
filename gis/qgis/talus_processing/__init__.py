"""QGIS plugin entry point: the Talus Processing provider (docs/qgis.md)."""


def classFactory(iface):  # noqa: N802 (QGIS's name)
    from .plugin import TalusPlugin
    return TalusPlugin()

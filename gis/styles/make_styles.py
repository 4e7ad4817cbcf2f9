#!/usr/bin/python3
"""Writes the QML style of every output layer (DESIGN.md section 3).

usage: /usr/bin/python3 gis/styles/make_styles.py [FOLDER]   (default: this folder)

Every style is a QGIS 3.22 single-band pseudocolor renderer with discrete classes: a value v
takes the colour of the first class whose upper break is >= v. The first class, up to 0, is
transparent because 0 means "never reached" in every layer; nodata is transparent too. The
classes and their sources are in CLASSES below (docs/layers.md explains them); the QML text is
the format QGIS 3.22 itself writes with saveNamedStyle, with attributes in a fixed order.
"""
import math
import os
import sys
from xml.sax.saxutils import quoteattr

QGIS_VERSION = "3.22.16-Białowieża"

# Swiss hazard-mapping intensities for rock fall (BUWAL/BWG 1997, "Empfehlungen:
# Berücksichtigung der Massenbewegungsgefahren", used by Rockyfor3D and RAMMS users): weak below
# 30 kJ, medium 30-300 kJ, strong above 300 kJ. The extra breaks at 100, 1000 and 3000 kJ are
# common rock-fall barrier ratings (EAD 340059-00-0106, formerly ETAG 027).
ENERGY_KJ = [30, 100, 300, 1000, 3000]
ENERGY_COLOURS = ["#ffffb2", "#fecc5c", "#fd8d3c", "#f03b20", "#bd0026", "#67000d"]

# name: (unit, integer counts?, upper breaks, colours: one per break plus one above the last).
# Colours are ColorBrewer sequential ramps (Brewer, colorbrewer2.org), light = low intensity.
CLASSES = {
    # Rock fall.
    "reach_probability": ("", False, [0.01, 0.05, 0.1, 0.25, 0.5],
                          ["#ffffb2", "#fed976", "#feb24c", "#fd8d3c", "#f03b20", "#bd0026"]),
    "passages": ("", True, [1, 10, 100, 1000, 10000],
                 ["#eff3ff", "#c6dbef", "#6baed6", "#2171b5", "#084594", "#08306b"]),
    "deposits": ("", True, [1, 10, 100, 1000, 10000],
                 ["#f2f0f7", "#dadaeb", "#bcbddc", "#9e9ac8", "#756bb1", "#54278f"]),
    "energy_max": ("kJ", False, ENERGY_KJ, ENERGY_COLOURS),
    "energy_p95": ("kJ", False, ENERGY_KJ, ENERGY_COLOURS),
    "jump_height_p95": ("m", False, [0.5, 1, 2, 5, 10, 20],
                        ["#ffffcc", "#c7e9b4", "#7fcdbb", "#41b6c4", "#1d91c0", "#225ea8",
                         "#0c2c84"]),
    # Shared by rock fall and mud flow (one file name, one style).
    "velocity_max": ("m/s", False, [1, 2, 5, 10, 20, 30],
                     ["#f1eef6", "#d0d1e6", "#a6bddb", "#74a9cf", "#3690c0", "#0570b0",
                      "#034e7b"]),
    "energy_loss_friction": ("kJ", False, [0.1, 1, 10, 100, 1000],
                             ["#edf8e9", "#c7e9c0", "#a1d99b", "#74c476", "#31a354", "#006d2c"]),
    "energy_loss_deformation": ("kJ", False, [0.1, 1, 10, 100, 1000],
                                ["#feedde", "#fdd0a2", "#fdae6b", "#fd8d3c", "#e6550d",
                                 "#a63603"]),
    # Mud flow. 1 m flow depth is the Swiss medium/strong debris-flow intensity limit (BWG 1997);
    # 3 and 30 kPa are the pressure limits of Swiss avalanche hazard zoning (BFF/SLF 1984),
    # often reused for debris-flow impact pressure.
    "flow_depth_max": ("m", False, [0.1, 0.25, 0.5, 1, 2, 5],
                       ["#eff3ff", "#c6dbef", "#9ecae1", "#6baed6", "#4292c6", "#2171b5",
                        "#084594"]),
    "pressure_max": ("kPa", False, [1, 3, 10, 30, 100, 300],
                     ["#feebe2", "#fcc5c0", "#fa9fb5", "#f768a1", "#dd3497", "#ae017e",
                      "#7a0177"]),
    "deposit_depth": ("m", False, [0.05, 0.1, 0.25, 0.5, 1, 2],
                      ["#ffffd4", "#fee391", "#fec44f", "#fe9929", "#ec7014", "#cc4c02",
                       "#8c2d04"]),
    # Early arrival is the most dangerous: red first, blue last.
    "arrival_time": ("s", False, [5, 10, 30, 60, 120, 300, 600],
                     ["#d53e4f", "#f46d43", "#fdae61", "#fee08b", "#e6f598", "#abdda4",
                      "#66c2a5", "#3288bd"]),
    "erosion_depth": ("m", False, [0.05, 0.1, 0.25, 0.5, 1, 2],
                      ["#fef0d9", "#fdd49e", "#fdbb84", "#fc8d59", "#ef6548", "#d7301f",
                       "#990000"]),
}


def number(x):
    """A break as QGIS writes it: shortest round-trip form, 'inf' for the open last class."""
    return "inf" if math.isinf(x) else f"{x:g}"


def labels(unit, counts, breaks):
    """Legend labels of the classes above 0: '0 - 30 kJ', '30 - 100 kJ', ..., '> 3000 kJ'."""
    suffix = f" {unit}" if unit else ""
    out, low = [], 0
    for high in breaks:
        first = low + 1 if counts else low
        out.append((f"{number(first)}" if first == high else f"{number(first)} - {number(high)}") + suffix)
        low = high
    out.append(f"> {number(low)}{suffix}")
    return out


def rgba(hex_colour):
    return ",".join(str(int(hex_colour[i:i + 2], 16)) for i in (1, 3, 5)) + ",255"


def source_ramp(colours):
    """The classes' colours as a discrete gradient, the ramp the Symbology dialog offers."""
    n = len(colours)  # QGIS's discrete convention: colour i holds from i/n, the last repeats color2
    stops = ":".join(f"{i / n:g};{rgba(c)}" for i, c in enumerate(colours[1:], start=1))
    props = [("color1", rgba(colours[0])), ("color2", rgba(colours[-1])), ("discrete", "1"),
             ("rampType", "gradient"), ("stops", stops)]
    options = "".join(f'\n              <Option type="QString" value="{v}" name="{k}"/>' for k, v in props)
    legacy = "".join(f'\n            <prop v="{v}" k="{k}"/>' for k, v in props)
    return (f'          <colorramp type="gradient" name="[source]">\n            <Option type="Map">'
            f"{options}\n            </Option>{legacy}\n          </colorramp>")


def items(unit, counts, breaks, colours):
    rows = ['          <item label="0 (never reached)" alpha="0" value="0" color="#000000"/>']
    for label, high, colour in zip(labels(unit, counts, breaks), breaks + [math.inf], colours):
        rows.append(f'          <item label={quoteattr(label)} alpha="255" value="{number(high)}" color="{colour}"/>')
    return "\n".join(rows)


def style(unit, counts, breaks, colours):
    assert len(colours) == len(breaks) + 1, "one colour per class"
    assert breaks == sorted(breaks) and breaks[0] > 0, "breaks rise from above 0"
    top = number(breaks[-1])
    precision = 0 if counts else 2
    return f"""<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>
<qgis version="{QGIS_VERSION}" styleCategories="AllStyleCategories" hasScaleBasedVisibilityFlag="0" maxScale="0" minScale="1e+08">
  <flags>
    <Identifiable>1</Identifiable>
    <Removable>1</Removable>
    <Searchable>1</Searchable>
    <Private>0</Private>
  </flags>
  <temporal mode="0" fetchMode="0" enabled="0">
    <fixedRange>
      <start></start>
      <end></end>
    </fixedRange>
  </temporal>
  <customproperties>
    <Option type="Map">
      <Option type="QString" value="Value" name="identify/format"/>
    </Option>
  </customproperties>
  <pipe-data-defined-properties>
    <Option type="Map">
      <Option type="QString" value="" name="name"/>
      <Option name="properties"/>
      <Option type="QString" value="collection" name="type"/>
    </Option>
  </pipe-data-defined-properties>
  <pipe>
    <provider>
      <resampling maxOversampling="2" zoomedInResamplingMethod="nearestNeighbour" zoomedOutResamplingMethod="nearestNeighbour" enabled="false"/>
    </provider>
    <rasterrenderer type="singlebandpseudocolor" nodataColor="" band="1" classificationMin="0" classificationMax="{top}" opacity="1" alphaBand="-1">
      <minMaxOrigin>
        <limits>None</limits>
        <extent>WholeRaster</extent>
        <statAccuracy>Estimated</statAccuracy>
        <cumulativeCutLower>0.02</cumulativeCutLower>
        <cumulativeCutUpper>0.98</cumulativeCutUpper>
        <stdDevFactor>2</stdDevFactor>
      </minMaxOrigin>
      <rastershader>
        <colorrampshader labelPrecision="{precision}" minimumValue="0" clip="0" maximumValue="{top}" classificationMode="1" colorRampType="DISCRETE">
{source_ramp(colours)}
{items(unit, counts, breaks, colours)}
          <rampLegendSettings useContinuousLegend="0" direction="0" prefix="" minimumLabel="" orientation="2" suffix="" maximumLabel="">
            <numericFormat id="basic">
              <Option type="Map">
                <Option type="QChar" value="" name="decimal_separator"/>
                <Option type="int" value="6" name="decimals"/>
                <Option type="int" value="0" name="rounding_type"/>
                <Option type="bool" value="false" name="show_plus"/>
                <Option type="bool" value="true" name="show_thousand_separator"/>
                <Option type="bool" value="false" name="show_trailing_zeros"/>
                <Option type="QChar" value="" name="thousand_separator"/>
              </Option>
            </numericFormat>
          </rampLegendSettings>
        </colorrampshader>
      </rastershader>
    </rasterrenderer>
    <brightnesscontrast gamma="1" contrast="0" brightness="0"/>
    <huesaturation grayscaleMode="0" colorizeGreen="128" colorizeStrength="100" colorizeOn="0" colorizeRed="255" invertColors="0" colorizeBlue="128" saturation="0"/>
    <rasterresampler maxOversampling="2"/>
    <resamplingStage>resamplingFilter</resamplingStage>
  </pipe>
  <blendMode>0</blendMode>
</qgis>
"""


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, spec in CLASSES.items():
        with open(os.path.join(folder, name + ".qml"), "w", encoding="utf-8") as f:
            f.write(style(*spec))


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Writes the QML style of every output layer (docs/architecture.md section 3).

usage: /usr/bin/python3 gis/styles/make_styles.py [FOLDER]   (default: this folder)

Every raster style is a QGIS 3.22 single-band pseudocolor renderer with discrete classes: a
value v takes the colour of the first class whose upper break is >= v. The value 0 ("never
reached" in every layer) is made transparent by the renderer's transparency list, not by a
class of its own, so a legend or print layout lists only classes that are drawn (QGIS draws a
legend swatch with the layer's opacity whatever the class's alpha, so a transparent class used
to print as a black box); nodata is transparent too. The layer is drawn at OPACITY so a hillshade
or map under it stays readable. The classes and their sources are in CLASSES below
(docs/layers.md explains them).
trajectories.qml styles the lines of trajectories.gpkg: a graduated renderer on max_energy_kj
with the energy classes of energy_max in blues of their own, the strongest drawn on top, and
field aliases with units.
The QML text is the format QGIS 3.22 itself writes with saveNamedStyle, with attributes in a
fixed order.
"""
import math
import os
import sys
from xml.sax.saxutils import quoteattr

QGIS_VERSION = "3.22.16-Białowieża"
OPACITY = "0.8"

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
    # Stored as a fraction, labelled in percent as zoning methods quote it.
    "reach_probability": ("%", False, [0.01, 0.05, 0.1, 0.25, 0.5],
                          ["#ffffb2", "#fed976", "#feb24c", "#fd8d3c", "#f03b20", "#bd0026"]),
    "passages": ("", True, [1, 10, 100, 1000, 10000],
                 ["#eff3ff", "#c6dbef", "#6baed6", "#2171b5", "#084594", "#08306b"]),
    # Release sources whose rocks reach a cell (Rockyfor3D's Nr_sourcecells): 1 is a single
    # source, the rest roughly logarithmic steps.
    "source_count": ("", True, [1, 5, 10, 50, 100, 500],
                     ["#edf8fb", "#bfd3e6", "#9ebcda", "#8c96c6", "#8c6bb1", "#88419d", "#6e016b"]),
    "deposits": ("", True, [1, 10, 100, 1000, 10000],
                 ["#f2f0f7", "#dadaeb", "#bcbddc", "#9e9ac8", "#756bb1", "#54278f"]),
    "energy_max": ("kJ", False, ENERGY_KJ, ENERGY_COLOURS),
    "energy_p95": ("kJ", False, ENERGY_KJ, ENERGY_COLOURS),
    "jump_height_p95": ("m", False, [0.5, 1, 2, 5, 10, 20],
                        ["#ffffcc", "#c7e9b4", "#7fcdbb", "#41b6c4", "#1d91c0", "#225ea8",
                         "#0c2c84"]),
    # Shared by rock fall and mud flow (one file name, one style). The top limit is 40 m/s: rocks
    # of the sample scene pass 30 m/s on half of the cells they reach at 100 runs (issue 17).
    "velocity_max": ("m/s", False, [1, 5, 10, 20, 30, 40],
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
    """Legend labels of the classes above 0: '≤ 30 kJ', '30 - 100 kJ', ..., '> 3000 kJ'; counts
    from 1 ('1', '2 - 10', ...); unit '%' labels fractions in percent."""
    scale = 100 if unit == "%" else 1
    suffix = f" {unit}" if unit else ""
    out, low = [], None
    for high in breaks:
        if counts:
            first = 1 if low is None else low + 1
            text = f"{number(first)}" if first == high else f"{number(first)} - {number(high)}"
        else:
            text = f"≤ {number(high * scale)}" if low is None else f"{number(low * scale)} - {number(high * scale)}"
        out.append(text + suffix)
        low = high
    out.append(f"> {number(low * scale)}{suffix}")
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
    rows = []
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
    <rasterrenderer type="singlebandpseudocolor" nodataColor="" band="1" classificationMin="0" classificationMax="{top}" opacity="{OPACITY}" alphaBand="-1">
      <rasterTransparency>
        <singleValuePixelList>
          <pixelListEntry min="0" max="0" percentTransparent="100"/>
        </singleValuePixelList>
      </rasterTransparency>
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


# trajectories.gpkg: (field, alias) in the layer's order; QGIS shows the GeoPackage's fid first.
TRAJECTORY_FIELDS = [("fid", ""), ("run_id", "Run"), ("source_id", "Release source (0-based, as --only-source)"),
                     ("release_fid", "Release feature (FID of the release layer)"),
                     ("stop_reason", "Stop reason"), ("max_energy_kj", "Maximum kinetic energy (kJ)"),
                     ("runout_length_m", "Runout length (m)")]
TRAJECTORY_LINE_WIDTH_MM = "0.3"
# Blues (ColorBrewer), light to dark by energy: the lines' own scheme, so that drawn over the
# intensity or energy layers they are not read as one of their classes.
TRAJECTORY_COLOURS = ["#c6dbef", "#9ecae1", "#6baed6", "#3182bd", "#08519c", "#08306b"]


def option_map(props, indent):
    """QGIS's two copies of a symbol layer's properties: an Option map and legacy props."""
    pad = " " * indent
    options = "".join(f'\n{pad}  <Option type="QString" value={quoteattr(v)} name="{k}"/>' for k, v in props)
    legacy = "".join(f"\n{pad}<prop v={quoteattr(v)} k=\"{k}\"/>" for k, v in props)
    return f'{pad}<Option type="Map">{options}\n{pad}</Option>{legacy}'


def data_defined(indent):
    pad = " " * indent
    return (f"{pad}<data_defined_properties>\n{pad}  <Option type=\"Map\">\n"
            f'{pad}    <Option type="QString" value="" name="name"/>\n{pad}    <Option name="properties"/>\n'
            f'{pad}    <Option type="QString" value="collection" name="type"/>\n{pad}  </Option>\n'
            f"{pad}</data_defined_properties>")


def line_symbol(index, colour):
    """A solid line with round caps and joins, drawn in rendering pass `index`."""
    scale = "3x:0,0,0,0,0,0"
    props = [("align_dash_pattern", "0"), ("capstyle", "round"), ("customdash", "5;2"),
             ("customdash_map_unit_scale", scale), ("customdash_unit", "MM"), ("dash_pattern_offset", "0"),
             ("dash_pattern_offset_map_unit_scale", scale), ("dash_pattern_offset_unit", "MM"),
             ("draw_inside_polygon", "0"), ("joinstyle", "round"), ("line_color", rgba(colour)),
             ("line_style", "solid"), ("line_width", TRAJECTORY_LINE_WIDTH_MM), ("line_width_unit", "MM"),
             ("offset", "0"), ("offset_map_unit_scale", scale), ("offset_unit", "MM"), ("ring_filter", "0"),
             ("trim_distance_end", "0"), ("trim_distance_end_map_unit_scale", scale),
             ("trim_distance_end_unit", "MM"), ("trim_distance_start", "0"),
             ("trim_distance_start_map_unit_scale", scale), ("trim_distance_start_unit", "MM"),
             ("tweak_dash_pattern_on_corners", "0"), ("use_custom_dash", "0"), ("width_map_unit_scale", scale)]
    return (f'      <symbol type="line" name="{index}" alpha="1" clip_to_extent="1" force_rhr="0">\n'
            f"{data_defined(8)}\n"
            f'        <layer class="SimpleLine" pass="{index}" enabled="1" locked="0">\n'
            f"{option_map(props, 10)}\n{data_defined(10)}\n        </layer>\n      </symbol>")


def bound(x):
    """A class limit as QGIS writes it in a graduated renderer."""
    return "inf" if math.isinf(x) else f"{x:.15f}"


def per_field(template):
    return "\n".join(template.format(index=i, field=f, alias=quoteattr(a)[1:-1])
                      for i, (f, a) in enumerate(TRAJECTORY_FIELDS))


def trajectory_style():
    lows = [0] + ENERGY_KJ
    highs = ENERGY_KJ + [math.inf]
    names = labels("kJ", False, ENERGY_KJ)
    ranges = "\n".join(f'      <range symbol="{i}" label={quoteattr(label)} lower="{bound(low)}" '
                       f'upper="{bound(high)}" render="true"/>'
                       for i, (low, high, label) in enumerate(zip(lows, highs, names)))
    symbols = "\n".join(line_symbol(i, c) for i, c in enumerate(TRAJECTORY_COLOURS))
    field_configuration = per_field('    <field name="{field}" configurationFlags="None">\n'
                                    '      <editWidget type="">\n        <config>\n          <Option/>\n'
                                    "        </config>\n      </editWidget>\n    </field>")
    constraints = "\n".join(
        f'    <constraint field="{f}" constraints="{3 if f == "fid" else 0}" unique_strength="{int(f == "fid")}" '
        f'notnull_strength="{int(f == "fid")}" exp_strength="0"/>' for f, _ in TRAJECTORY_FIELDS)
    return f"""<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>
<qgis version="{QGIS_VERSION}" styleCategories="AllStyleCategories" hasScaleBasedVisibilityFlag="0" maxScale="0" minScale="100000000" readOnly="0" labelsEnabled="0" symbologyReferenceScale="-1" simplifyAlgorithm="0" simplifyDrawingHints="1" simplifyDrawingTol="1" simplifyLocal="1" simplifyMaxScale="1">
  <flags>
    <Identifiable>1</Identifiable>
    <Removable>1</Removable>
    <Searchable>1</Searchable>
    <Private>0</Private>
  </flags>
  <temporal mode="0" enabled="0" accumulate="0" durationField="" durationUnit="min" endExpression="" endField="" fixedDuration="0" limitMode="0" startExpression="" startField="">
    <fixedRange>
      <start></start>
      <end></end>
    </fixedRange>
  </temporal>
  <renderer-v2 type="graduatedSymbol" attr="max_energy_kj" graduatedMethod="GraduatedColor" symbollevels="1" enableorderby="0" forceraster="0" referencescale="-1">
    <ranges>
{ranges}
    </ranges>
    <symbols>
{symbols}
    </symbols>
    <classificationMethod id="Custom">
      <symmetricMode enabled="0" symmetrypoint="0" astride="0"/>
      <labelFormat format="%1 - %2" labelprecision="4" trimtrailingzeroes="1"/>
      <parameters>
        <Option/>
      </parameters>
      <extraInformation/>
    </classificationMethod>
    <rotation/>
    <sizescale/>
  </renderer-v2>
  <customproperties>
    <Option/>
  </customproperties>
  <blendMode>0</blendMode>
  <featureBlendMode>0</featureBlendMode>
  <layerOpacity>1</layerOpacity>
  <geometryOptions geometryPrecision="0" removeDuplicateNodes="0">
    <activeChecks type="StringList">
      <Option type="QString" value=""/>
    </activeChecks>
    <checkConfiguration/>
  </geometryOptions>
  <legend type="default-vector" showLabelLegend="0"/>
  <referencedLayers/>
  <fieldConfiguration>
{field_configuration}
  </fieldConfiguration>
  <aliases>
{per_field('    <alias field="{field}" index="{index}" name="{alias}"/>')}
  </aliases>
  <defaults>
{per_field('    <default field="{field}" expression="" applyOnUpdate="0"/>')}
  </defaults>
  <constraints>
{constraints}
  </constraints>
  <constraintExpressions>
{per_field('    <constraint field="{field}" exp="" desc=""/>')}
  </constraintExpressions>
  <expressionfields/>
  <attributeactions/>
  <attributetableconfig actionWidgetStyle="dropDown" sortExpression="" sortOrder="0">
    <columns/>
  </attributetableconfig>
  <conditionalstyles>
    <rowstyles/>
    <fieldstyles/>
  </conditionalstyles>
  <storedexpressions/>
  <editform tolerant="1"></editform>
  <editforminit/>
  <editforminitcodesource>0</editforminitcodesource>
  <editforminitfilepath></editforminitfilepath>
  <editforminitcode><![CDATA[]]></editforminitcode>
  <featformsuppress>0</featformsuppress>
  <editorlayout>generatedlayout</editorlayout>
  <editable/>
  <labelOnTop/>
  <reuseLastValue/>
  <dataDefinedFieldProperties/>
  <widgets/>
  <previewExpression></previewExpression>
  <mapTip></mapTip>
  <layerGeometryType>1</layerGeometryType>
</qgis>
"""


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, spec in CLASSES.items():
        with open(os.path.join(folder, name + ".qml"), "w", encoding="utf-8") as f:
            f.write(style(*spec))
    with open(os.path.join(folder, "trajectories.qml"), "w", encoding="utf-8") as f:
        f.write(trajectory_style())


if __name__ == "__main__":
    main()

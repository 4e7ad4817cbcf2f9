<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>
<qgis version="3.22.16-Białowieża" styleCategories="AllStyleCategories" hasScaleBasedVisibilityFlag="0" maxScale="0" minScale="1e+08">
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
    <rasterrenderer type="singlebandpseudocolor" nodataColor="" band="1" classificationMin="0" classificationMax="600" opacity="0.8" alphaBand="-1">
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
        <colorrampshader labelPrecision="2" minimumValue="0" clip="0" maximumValue="600" classificationMode="1" colorRampType="DISCRETE">
          <colorramp type="gradient" name="[source]">
            <Option type="Map">
              <Option type="QString" value="213,62,79,255" name="color1"/>
              <Option type="QString" value="50,136,189,255" name="color2"/>
              <Option type="QString" value="1" name="discrete"/>
              <Option type="QString" value="gradient" name="rampType"/>
              <Option type="QString" value="0.125;244,109,67,255:0.25;253,174,97,255:0.375;254,224,139,255:0.5;230,245,152,255:0.625;171,221,164,255:0.75;102,194,165,255:0.875;50,136,189,255" name="stops"/>
            </Option>
            <prop v="213,62,79,255" k="color1"/>
            <prop v="50,136,189,255" k="color2"/>
            <prop v="1" k="discrete"/>
            <prop v="gradient" k="rampType"/>
            <prop v="0.125;244,109,67,255:0.25;253,174,97,255:0.375;254,224,139,255:0.5;230,245,152,255:0.625;171,221,164,255:0.75;102,194,165,255:0.875;50,136,189,255" k="stops"/>
          </colorramp>
          <item label="≤ 5 s" alpha="255" value="5" color="#d53e4f"/>
          <item label="5 - 10 s" alpha="255" value="10" color="#f46d43"/>
          <item label="10 - 30 s" alpha="255" value="30" color="#fdae61"/>
          <item label="30 - 60 s" alpha="255" value="60" color="#fee08b"/>
          <item label="60 - 120 s" alpha="255" value="120" color="#e6f598"/>
          <item label="120 - 300 s" alpha="255" value="300" color="#abdda4"/>
          <item label="300 - 600 s" alpha="255" value="600" color="#66c2a5"/>
          <item label="&gt; 600 s" alpha="255" value="inf" color="#3288bd"/>
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

#!/usr/bin/python3
"""Writes the seed corpus of the fuzz targets (docs/fuzzing.md) into corpus/<target>/: a few
tiny valid and nearly valid inputs each, made here rather than copied. Reproducers of findings
are added beside them by hand (named after what they found) and are not rewritten by this script.
Run on Debian's /usr/bin/python3 (GDAL's osgeo): tests/fuzz/make_corpus.py"""
import os
import shutil
from pathlib import Path

from osgeo import gdal, osr

gdal.UseExceptions()
HERE = Path(__file__).resolve().parent
CORPUS = HERE / "corpus"
ROOT = HERE.parent.parent

# The fixed DEM of the raster and release targets (fuzz_input.cpp): 16 x 16 cells of 10 m from
# (600000, 5200000) in EPSG:32632.
X0, Y0, TOP = 600000.0, 5200000.0, 5200160.0


def text(target, name, content):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_text(content)


def raster(target, name, values, geotransform, epsg=32632, dtype=gdal.GDT_Float32, nodata=None, driver="GTiff"):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    rows, cols = len(values), len(values[0])
    mem = gdal.GetDriverByName("MEM").Create("", cols, rows, 1, dtype)
    mem.SetGeoTransform(geotransform)
    if epsg:
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(epsg)
        mem.SetSpatialRef(srs)
    band = mem.GetRasterBand(1)
    if nodata is not None:
        band.SetNoDataValue(nodata)
    for r, row in enumerate(values):
        for c, v in enumerate(row):
            band.WriteArray(__import__("numpy").array([[v]]), c, r)
    gdal.GetDriverByName(driver).CreateCopy(str(folder / name), mem)
    for extra in folder.glob(name + ".aux.xml"):
        extra.unlink()


def scenario():
    text("scenario", "rockfall.toml", '[run]\nruns = 20\nseed = 7\n\n[rock]\nshape = "ellipsoid"\nsize = "1,0.8,0.5"\n'
         'density = 2600.0\n\n[stochastic]\nrelease_jitter = 0.5\nnoise_octaves = 3\n\n[fast_bounce]\ngravity = 9.81\n')
    text("scenario", "rockfall_auto.toml", '[run]\nruns = "auto"\nmin_runs = 20\nmax_runs = 640\n'
         'convergence_tolerance = 0.05\n\n[outputs]\nintensity = "none"\nproject = "off"\n')
    text("scenario", "rockfall_full.toml", '[run]\nmode = "full"\nruns = 2\n\n[rock]\nfracture_parts = 4\n'
         'fracture_strength = 500.0\n\n[full]\ncarpet_spacing = 0.1\nmax_retries = 8\nguard = true\n')
    text("scenario", "mudflow.toml", '[mud]\nmaterial = "granular"\nparticle_size = 2.5\nrelease_thickness = "vertical"\n\n'
         '[run]\nduration = 120.0\n\n[rheology]\nrheology = "coulomb"\nfriction = 0.3\n\n'
         '[outputs]\nsnapshot_interval = 5.0\nsnapshot_start = "2021-07-14T18:30:00"\n')
    text("scenario", "mudflow_bingham.toml", '[rheology]\nrheology = "bingham"\nviscosity = 50.0\nyield_stress = 800.0\n\n'
         '[adaptivity]\nadaptive = false\ncoarse_levels = 3\n\n[time_steps]\ncourant = 0.4\ndeepest_level = 6\n')
    text("scenario", "out_of_range.toml", '[fast_bounce]\ncontact_time_step = 0.0\n\n[mud]\ngravity = -9.81\n')
    text("scenario", "unknown_key.toml", '[run]\nrunz = 3\n[rheology]\nfriction_factor = 0.5\n')
    text("scenario", "broken.toml", '[run\nruns = = 2\n')


def materials():
    folder = CORPUS / "materials"
    folder.mkdir(parents=True, exist_ok=True)
    shutil.copy(ROOT / "docs" / "materials-default.toml", folder / "default.toml")
    text("materials", "small.toml", 'default_lithology = 1\ndefault_vegetation = 0\n\n[[lithology]]\ncode = 1\n'
         'name = "rock"\nelastic_slope = 1.0e8\nyield_pressure = 1.0e6\nplastic_slope = 1.0e7\nunloading_slope = 5.0e8\n'
         'friction = 0.5\nrolling_friction = 0.2\nrestitution_normal = 0.5\nrestitution_tangential = 0.8\n'
         'noise_amplitude = 0.1\n\n[[vegetation]]\ncode = 0\nname = "bare"\ndeperdition = 0.0\n')
    text("materials", "missing_default.toml", 'default_lithology = 9\n\n[[lithology]]\ncode = 1\nname = "x"\n')


def intensity():
    folder = CORPUS / "intensity"
    folder.mkdir(parents=True, exist_ok=True)
    shutil.copy(ROOT / "src" / "cli" / "intensity_guidelines.toml", folder / "built_in.toml")
    text("intensity", "custom.toml", '[local-2020]\ntitle = "Local classes"\nsource = "none"\n\n'
         '[[local-2020.rockfall]]\nvalue = 1\nname = "weak"\ncolour = "#ffff00"\nwhen = ["energy_p95 > 0"]\n\n'
         '[[local-2020.rockfall]]\nvalue = 2\nname = "strong"\ncolour = "#ff0000"\nwhen = ["energy_p95 >= 300"]\n\n'
         '[[local-2020.mudflow]]\nvalue = 3\nname = "strong"\ncolour = "#ff0000"\n'
         'when = ["flow_depth_max > 1 and velocity_max > 1", "flow_depth_max * velocity_max > 1"]\n')


def studies():
    folder = CORPUS / "study"
    folder.mkdir(parents=True, exist_ok=True)
    shutil.copy(ROOT / "sample_dem" / "study.toml", folder / "sample.toml")
    shutil.copy(ROOT / "docs" / "examples" / "tirol_alr.study.toml", folder / "tirol_alr.toml")
    text("study", "auto.toml", '[inputs]\ndem = "dem.tif"\n[hazard]\nrockfall_probability = "onset"\n\n'
         '[[rockfall]]\nname = "cliffs"\nrelease = "auto"\nsource_slope = 50\nsource_lithology = [5, 6]\n'
         'annual_frequency = 0.1\n[rockfall.run]\nruns = 5\n')
    text("study", "bad_name.toml", '[inputs]\ndem = "dem.tif"\n[[mudflow]]\nname = "../x"\nrelease = "r.gpkg"\n'
         'return_period = 0\n')


def rasters():
    slope = [[1500.0 - 4 * c - 6 * r for c in range(4)] for r in range(4)]
    raster("raster", "dem.tif", slope, (X0, 40.0, 0, TOP, 0, -40.0))
    raster("raster", "dem_nodata.tif", [[-9999.0, 1200.0], [1190.0, -9999.0]], (X0, 80.0, 0, TOP, 0, -80.0), nodata=-9999.0)
    raster("raster", "dem_degrees.tif", slope, (11.0, 0.001, 0, 47.0, 0, -0.001), epsg=4326)
    raster("raster", "lithology.tif", [[1, 2, 3], [4, 5, 6], [4, 4, 255]], (X0, 60.0, 0, TOP, 0, -60.0),
           dtype=gdal.GDT_Byte, nodata=255)
    raster("raster", "vegetation.tif", [[0.0, 0.02], [0.05, 0.0]], (X0, 80.0, 0, TOP, 0, -80.0))
    text("raster", "grid.asc", "ncols 3\nnrows 2\nxllcorner 600000\nyllcorner 5200000\ncellsize 50\nNODATA_value -9999\n"
         "1200 1190 1180\n1210 -9999 1170\n")
    text("raster", "flipped.asc", "ncols 2\nnrows 2\nxllcorner 600000\nyllcorner 5200000\ndx 10\ndy -10\n1 2\n3 4\n")


def releases():
    raster("release", "depths.tif", [[0.0, 1.5], [2.0, 0.0]], (X0, 80.0, 0, TOP, 0, -80.0))
    raster("release", "mask.tif", [[0, 1], [1, 0]], (X0, 80.0, 0, TOP, 0, -80.0), dtype=gdal.GDT_Byte)
    crs = '"crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}}, '
    text("release", "points.geojson", '{"type": "FeatureCollection", ' + crs + '"features": [\n'
         '{"type": "Feature", "properties": {"depth": 1.0, "shape": "box", "block_size": "1,0.5,0.5", "vx": 1.0}, '
         '"geometry": {"type": "Point", "coordinates": [600055, 5200105]}},\n'
         '{"type": "Feature", "properties": {"depth": 2.0, "density": 2500}, '
         '"geometry": {"type": "MultiPoint", "coordinates": [[600015, 5200145], [600125, 5200025]]}}]}\n')
    text("release", "polygon.geojson", '{"type": "FeatureCollection", ' + crs + '"features": [\n'
         '{"type": "Feature", "properties": {"depth": 1.8, "release_height": 0.5}, "geometry": {"type": "Polygon", '
         '"coordinates": [[[600020, 5200020], [600090, 5200020], [600090, 5200090], [600020, 5200020]]]}}]}\n')
    text("release", "no_depth.geojson", '{"type": "FeatureCollection", "features": [{"type": "Feature", '
         '"properties": {}, "geometry": {"type": "Point", "coordinates": [600050, 5200050]}}]}\n')
    text("release", "line.geojson", '{"type": "Feature", "properties": {"depth": 1}, "geometry": {"type": "LineString", '
         '"coordinates": [[600010, 5200010], [600100, 5200100]]}}\n')


if __name__ == "__main__":
    scenario()
    studies()
    materials()
    intensity()
    rasters()
    releases()

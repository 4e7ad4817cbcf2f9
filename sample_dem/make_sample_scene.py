#!/usr/bin/python3
"""Build the Talus sample scene from the Alplehner DEM (Land Tirol, 5 m).

Writes, next to this script (or into --out-dir):
  dem.tif                 Float32 crop of the source DEM, EPSG:31287, nodata -9999
  lithology.tif           Byte, Rockyfor3D soil types 1-6, nodata 255
  vegetation.tif          Byte, 0 bare .. 4 dense forest, nodata 255
  rockfall_release.gpkg   layer "release": points on the main cliff band, field source_id
  mudflow_release.gpkg    layer "release": one polygon in a gully, field depth (m)

Every class is derived from the terrain by the simple rules written out below and in
README.md; none of them is mapped. The output is deterministic: same source, same files.

Run with Debian's interpreter (it has osgeo and numpy):
  /usr/bin/python3 sample_dem/make_sample_scene.py [--source DEM] [--out-dir DIR]
"""

import argparse
import os
import sys

import numpy as np
from osgeo import gdal, ogr, osr

gdal.UseExceptions()
ogr.UseExceptions()
osr.UseExceptions()

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SOURCE = os.path.join(HERE, "..", "data", "tirol_alr", "avaAlr.tif")

# Crop window in source cells: column offset, row offset, columns, rows (5 m cells, so
# 1.3 km east-west by 2.0 km north-south). Found by scanning all windows of this size for the
# most cells steeper than 50 degrees among those with (almost) no nodata, then moved 15 rows
# north so that the crest above the cliff band is inside; that costs 62 nodata cells in the
# north-east corner (the catchment is a wedge that narrows uphill, and a window 300 cells wide
# holding the cliff band would lose about 2000 cells to nodata). The crop holds the cliff band
# in its north-east, talus and forest slopes below it, a gully in its north-west, a gentle
# bench with a debris fan, and the heads of the lower gullies along its southern edge.
WINDOW = (20, 255, 260, 400)
EPSG = 31287
DEM_NODATA = -9999.0
CLASS_NODATA = 255

# Terrain rules (degrees, metres, 1/m). Curvature is the Laplacian of the DEM smoothed by a
# 3 x 3 mean: negative is convex (ridges, cliff edges), positive is concave (gullies, hollows).
CLIFF_SLOPE = 45.0          # bedrock at or above this slope
THIN_COVER_SLOPE = 35.0     # bedrock with thin cover: this steep and convex (or high)
TALUS_SLOPE = 25.0          # talus / scree from this slope up
FINE_SOIL_SLOPE = 10.0      # deep fine soil below this slope
CONVEX = -0.02              # Laplacian below this is convex
CONCAVE = 0.02              # Laplacian above this is concave
HIGH_ELEVATION = 2000.0     # above this, steep convex-or-not ground keeps only a thin cover
TALUS_REACH = 150.0         # talus lies within this horizontal distance of a cliff cell ...
TALUS_DROP = 20.0           # ... that is at least this much higher
CONCAVE_TALUS_MAX = 40.0    # concave slopes up to this angle collect talus too

# Vegetation rules.
BARE_ABOVE = 2200.0         # no vegetation above this elevation
TREELINE = 1850.0           # no forest above this elevation (Tirol, northern limestone Alps)
ECOTONE = 200.0             # forest thins out within this height below the treeline
MEADOW_SLOPE = 10.0         # gentle ground below the treeline is kept open (meadows, pasture)

# Rock-fall release: cells of the largest connected cliff band, thinned to at most this many.
MAX_RELEASE_POINTS = 300

# Mud-flow release: a stretch of the gully bed, buffered. The seed is a point in the large
# gully that crosses the top-left of the crop (it drains the upper catchment); it is snapped
# to the cell with the largest flow accumulation within SNAP_RADIUS, from where the
# steepest-descent (D8) path is followed downstream for SOURCE_LENGTH and buffered by
# SOURCE_HALF_WIDTH on each side.
MUD_SEED_XY = (255654.58, 380528.49)
SNAP_RADIUS = 25.0
SOURCE_LENGTH = 250.0
SOURCE_HALF_WIDTH = 15.0
SOURCE_DEPTH = 1.8          # m
RUNOUT_SLOPE = 12.0         # the path must reach ground gentler than this ...
RUNOUT_CELLS = 10           # ... for this many consecutive cells, inside the crop

LITHOLOGY_CLASSES = {
    1: ("fine soil, depth > 1 m", (196, 160, 100)),
    2: ("fine soil, depth < 1 m", (222, 196, 140)),
    3: ("scree / medium compact soil with small rock fragments", (200, 200, 170)),
    4: ("talus slope / compact soil with large rock fragments", (170, 150, 130)),
    5: ("bedrock with thin weathered cover", (140, 120, 120)),
    6: ("bedrock", (90, 80, 85)),
}
VEGETATION_CLASSES = {
    0: ("bare", (235, 235, 225)),
    1: ("meadow", (200, 230, 150)),
    2: ("shrubs", (150, 190, 90)),
    3: ("open forest", (70, 150, 70)),
    4: ("dense forest", (20, 90, 40)),
}

# 8 neighbours as (row step, column step).
NEIGHBOURS = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)]


def read_window(path):
    src = gdal.Open(path)
    srs = src.GetSpatialRef()
    if srs is None:
        sys.exit(f"{path}: no CRS")
    srs.AutoIdentifyEPSG()
    if srs.GetAuthorityCode(None) != str(EPSG):
        sys.exit(f"{path}: expected EPSG:{EPSG}, found {srs.GetAuthorityCode(None)}")
    xoff, yoff, cols, rows = WINDOW
    if xoff + cols > src.RasterXSize or yoff + rows > src.RasterYSize:
        sys.exit(f"{path}: crop window {WINDOW} does not fit {src.RasterXSize} x {src.RasterYSize}")
    band = src.GetRasterBand(1)
    z = band.ReadAsArray(xoff, yoff, cols, rows).astype(np.float64)
    nodata = band.GetNoDataValue()
    valid = np.isfinite(z) if nodata is None else (z != nodata) & np.isfinite(z)
    gt = list(src.GetGeoTransform())
    if gt[2] != 0 or gt[4] != 0:
        sys.exit(f"{path}: rotated grids are not supported")
    gt[0] += xoff * gt[1]
    gt[3] += yoff * gt[5]
    return z, valid, tuple(gt), srs


def shifted(a, dr, dc):
    """a shifted so that result[r, c] == a[r + dr, c + dc], edges repeated."""
    p = np.pad(a, 1, mode="edge")
    rows, cols = a.shape
    return p[1 + dr:1 + dr + rows, 1 + dc:1 + dc + cols]


def fill_nodata(z, valid):
    """Nodata cells take the mean of their valid neighbours, repeatedly (derivatives only)."""
    z = np.where(valid, z, np.nan)
    while np.isnan(z).any():
        stack = np.stack([shifted(z, dr, dc) for dr, dc in NEIGHBOURS])
        count = np.sum(~np.isnan(stack), axis=0)
        total = np.nansum(stack, axis=0)
        mean = np.where(count > 0, total / np.maximum(count, 1), np.nan)
        z = np.where(np.isnan(z), mean, z)
    return z


def slope_degrees(z, cell):
    """Horn's (1981) 3 x 3 slope, as gdaldem computes it."""
    s = lambda dr, dc: shifted(z, dr, dc)
    dzdx = ((s(-1, 1) + 2 * s(0, 1) + s(1, 1)) - (s(-1, -1) + 2 * s(0, -1) + s(1, -1))) / (8 * cell)
    dzdy = ((s(1, -1) + 2 * s(1, 0) + s(1, 1)) - (s(-1, -1) + 2 * s(-1, 0) + s(-1, 1))) / (8 * cell)
    return np.degrees(np.arctan(np.hypot(dzdx, dzdy)))


def laplacian(z, cell):
    """Laplacian (1/m) of the DEM smoothed by a 3 x 3 mean; > 0 concave, < 0 convex."""
    smooth = sum(shifted(z, dr, dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1)) / 9.0
    s = lambda dr, dc: shifted(smooth, dr, dc)
    return (s(-1, 0) + s(1, 0) + s(0, -1) + s(0, 1) - 4 * smooth) / (cell * cell)


def disk_offsets(radius_cells):
    r = int(np.floor(radius_cells))
    return [(dr, dc) for dr in range(-r, r + 1) for dc in range(-r, r + 1)
            if dr * dr + dc * dc <= radius_cells * radius_cells]


def max_within(values, radius_cells, fill):
    """Maximum of values over a disk around every cell (outside the grid counts as fill)."""
    rows, cols = values.shape
    r = int(np.floor(radius_cells))
    p = np.pad(values, r, mode="constant", constant_values=fill)
    out = np.full(values.shape, fill)
    for dr, dc in disk_offsets(radius_cells):
        np.maximum(out, p[r + dr:r + dr + rows, r + dc:r + dc + cols], out=out)
    return out


def classify_lithology(z, valid, slope, lap, cell):
    lith = np.full(z.shape, CLASS_NODATA, dtype=np.uint8)
    bedrock = valid & (slope >= CLIFF_SLOPE)
    thin = valid & ~bedrock & (slope >= THIN_COVER_SLOPE) & ((lap < CONVEX) | (z >= HIGH_ELEVATION))
    cliff_top = max_within(np.where(bedrock, z, -np.inf), TALUS_REACH / cell, -np.inf)
    below_cliff = cliff_top >= z + TALUS_DROP
    steep = valid & ~bedrock & ~thin & (slope >= TALUS_SLOPE)
    talus = steep & (below_cliff | ((lap > CONCAVE) & (slope < CONCAVE_TALUS_MAX)))
    scree = steep & ~talus
    gentle = valid & (slope < TALUS_SLOPE)
    deep_fine = gentle & (slope < FINE_SOIL_SLOPE) & (z < HIGH_ELEVATION)
    lith[gentle] = 2
    lith[deep_fine] = 1
    lith[scree] = 3
    lith[talus] = 4
    lith[thin] = 5
    lith[bedrock] = 6
    return lith


def classify_vegetation(z, valid, slope, lith):
    veg = np.full(z.shape, CLASS_NODATA, dtype=np.uint8)
    bare = valid & ((lith == 6) | (slope >= CLIFF_SLOPE) | (z >= BARE_ABOVE))
    alpine = valid & ~bare & (z >= TREELINE)
    forest_zone = valid & ~bare & (z < TREELINE)
    # Above the treeline: alpine meadow on soil, dwarf shrubs (dwarf pine) on rocky ground.
    veg[alpine & (lith <= 3)] = 1
    veg[alpine & (lith >= 4)] = 2
    # Below it, first match wins.
    rocky = forest_zone & ((lith == 5) | ((lith == 4) & (slope >= THIN_COVER_SLOPE)))
    open_ground = forest_zone & ~rocky & (slope < MEADOW_SLOPE)
    sparse = forest_zone & ~rocky & ~open_ground & (
        (lith == 4) | (slope >= THIN_COVER_SLOPE) | (z >= TREELINE - ECOTONE))
    dense = forest_zone & ~rocky & ~open_ground & ~sparse
    veg[rocky] = 2
    veg[open_ground] = 1
    veg[sparse] = 3
    veg[dense] = 4
    veg[bare] = 0
    return veg


def flow_directions(z, valid, cell):
    """D8 steepest descent: index of the downstream cell, -1 at pits, edges and nodata."""
    rows, cols = z.shape
    zp = np.pad(np.where(valid, z, np.inf), 1, mode="constant", constant_values=np.inf)
    steepest = np.zeros(z.shape)
    down = np.full(z.shape, -1, dtype=np.int64)
    index = np.arange(rows * cols).reshape(rows, cols)
    for dr, dc in NEIGHBOURS:
        drop = (z - zp[1 + dr:1 + dr + rows, 1 + dc:1 + dc + cols]) / (cell * np.hypot(dr, dc))
        better = valid & (drop > steepest)
        steepest[better] = drop[better]
        down[better] = index[better] + dr * cols + dc
    return down.ravel()


def flow_accumulation(z, valid, down):
    """Number of cells draining through each cell (itself included)."""
    acc = valid.ravel().astype(np.int64)
    order = np.argsort(-np.where(valid, z, -np.inf), axis=None, kind="stable")
    for i in order:
        if down[i] >= 0:
            acc[down[i]] += acc[i]
    return acc.reshape(z.shape)


def largest_component(mask):
    """Boolean mask of the largest 8-connected region of mask (ties: first in row order)."""
    rows, cols = mask.shape
    label = np.zeros(mask.shape, dtype=np.int32)
    best, best_size, current = 0, 0, 0
    for start in np.flatnonzero(mask):
        r0, c0 = divmod(int(start), cols)
        if label[r0, c0]:
            continue
        current += 1
        label[r0, c0] = current
        stack, size = [(r0, c0)], 0
        while stack:
            r, c = stack.pop()
            size += 1
            for dr, dc in NEIGHBOURS:
                rr, cc = r + dr, c + dc
                if 0 <= rr < rows and 0 <= cc < cols and mask[rr, cc] and not label[rr, cc]:
                    label[rr, cc] = current
                    stack.append((rr, cc))
        if size > best_size:
            best, best_size = current, size
    return label == best


def thin_points(rows_cols, priority, cell, limit):
    """Greedy thinning: walk the cells by decreasing priority (ties in row order) and keep a
    cell when no kept cell is closer than the spacing; the spacing grows by one cell until at
    most `limit` cells are kept. Returns (kept indices in walk order, spacing in metres)."""
    order = np.lexsort((np.arange(len(priority)), -priority))
    pts = rows_cols[order].astype(np.float64) * cell
    spacing = 0.0
    while True:
        kept = []
        for k in range(len(pts)):
            if spacing > 0 and kept:
                d2 = np.sum((pts[kept] - pts[k]) ** 2, axis=1)
                if np.min(d2) < spacing * spacing:
                    continue
            kept.append(k)
        if len(kept) <= limit:
            return order[kept], spacing
        spacing += cell


def cell_centre(gt, r, c):
    return gt[0] + (c + 0.5) * gt[1], gt[3] + (r + 0.5) * gt[5]


def write_raster(path, array, gt, srs, gdal_type, nodata, description, unit=None,
                 classes=None, predictor=None):
    if os.path.exists(path):
        gdal.GetDriverByName("GTiff").Delete(path)
    options = ["TILED=YES", "BLOCKXSIZE=256", "BLOCKYSIZE=256", "COMPRESS=DEFLATE", "ZLEVEL=9"]
    if predictor:
        options.append(f"PREDICTOR={predictor}")
    rows, cols = array.shape
    ds = gdal.GetDriverByName("GTiff").Create(path, cols, rows, 1, gdal_type, options)
    ds.SetGeoTransform(gt)
    ds.SetSpatialRef(srs)
    ds.SetMetadataItem("AREA_OR_POINT", "Area")
    ds.SetMetadataItem("SOURCE", "Datenquelle: Land Tirol - data.tirol.gv.at (CC BY 4.0)")
    band = ds.GetRasterBand(1)
    band.SetNoDataValue(nodata)
    band.SetDescription(description)
    if unit:
        band.SetUnitType(unit)
    if classes:
        table = gdal.ColorTable()
        for code, (name, rgb) in classes.items():
            table.SetColorEntry(code, (*rgb, 255))
            band.SetMetadataItem(f"CLASS_{code}", name)
        table.SetColorEntry(nodata, (0, 0, 0, 0))
        band.SetRasterColorTable(table)
        band.SetRasterColorInterpretation(gdal.GCI_PaletteIndex)
    band.WriteArray(array)
    band.FlushCache()
    ds = None


def new_layer(path, srs, geom_type):
    driver = ogr.GetDriverByName("GPKG")
    if os.path.exists(path):
        driver.DeleteDataSource(path)
    ds = driver.CreateDataSource(path)
    layer = ds.CreateLayer("release", srs, geom_type, ["FID=fid", "GEOMETRY_NAME=geom"])
    return ds, layer


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", default=DEFAULT_SOURCE,
                        help="source DEM (default: %(default)s)")
    parser.add_argument("--out-dir", default=HERE, help="output folder (default: %(default)s)")
    args = parser.parse_args()
    # GeoPackages carry a last-change timestamp: pin it so that reruns give identical files.
    gdal.SetConfigOption("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z")
    os.makedirs(args.out_dir, exist_ok=True)
    out = lambda name: os.path.join(args.out_dir, name)

    z, valid, gt, srs = read_window(args.source)
    cell = gt[1]
    if abs(gt[1] + gt[5]) > 1e-9:
        sys.exit(f"{args.source}: cells are not square")
    rows, cols = z.shape
    zf = fill_nodata(z, valid)
    slope = slope_degrees(zf, cell)
    lap = laplacian(zf, cell)

    lith = classify_lithology(zf, valid, slope, lap, cell)
    veg = classify_vegetation(zf, valid, slope, lith)

    # Rock-fall release points.
    cliff = largest_component(lith == 6)
    cells = np.argwhere(cliff)
    keep, spacing = thin_points(cells, slope[cliff], cell, MAX_RELEASE_POINTS)
    keep = np.sort(keep)  # write in row order
    ds, layer = new_layer(out("rockfall_release.gpkg"), srs, ogr.wkbPoint)
    for name, kind in (("source_id", ogr.OFTInteger), ("elevation", ogr.OFTReal),
                       ("slope_deg", ogr.OFTReal)):
        layer.CreateField(ogr.FieldDefn(name, kind))
    for n, k in enumerate(keep, start=1):
        r, c = cells[k]
        x, y = cell_centre(gt, r, c)
        f = ogr.Feature(layer.GetLayerDefn())
        f.SetField("source_id", n)
        f.SetField("elevation", round(float(zf[r, c]), 2))
        f.SetField("slope_deg", round(float(slope[r, c]), 1))
        f.SetGeometry(ogr.CreateGeometryFromWkt(f"POINT ({x:.4f} {y:.4f})"))
        layer.CreateFeature(f)
    ds = None

    # Mud-flow release polygon.
    down = flow_directions(zf, valid, cell)
    acc = flow_accumulation(zf, valid, down)
    sc = int(np.floor((MUD_SEED_XY[0] - gt[0]) / cell))
    sr = int(np.floor((MUD_SEED_XY[1] - gt[3]) / gt[5]))
    if not (0 <= sr < rows and 0 <= sc < cols):
        sys.exit("mud-flow seed lies outside the crop window")
    near = [(sr + dr, sc + dc) for dr, dc in disk_offsets(SNAP_RADIUS / cell)
            if 0 <= sr + dr < rows and 0 <= sc + dc < cols and valid[sr + dr, sc + dc]]
    start = max(near, key=lambda rc: (acc[rc], -rc[0], -rc[1]))
    # Follow the steepest-descent path down to the first stretch of gentle ground.
    i = start[0] * cols + start[1]
    path, distance, gentle_run = [i], [0.0], 0
    while gentle_run < RUNOUT_CELLS:
        j = int(down[i])
        if j < 0:
            sys.exit("the mud-flow path leaves the crop before reaching a runout area")
        distance.append(distance[-1] + cell * np.hypot(j // cols - i // cols, j % cols - i % cols))
        path.append(j)
        gentle_run = gentle_run + 1 if slope.flat[j] < RUNOUT_SLOPE else 0
        i = j
    runout = (path[-RUNOUT_CELLS], distance[-RUNOUT_CELLS])
    source = [k for k, d in zip(path, distance) if d <= SOURCE_LENGTH + 1e-9]
    length = distance[len(source) - 1]
    line = ogr.Geometry(ogr.wkbLineString)
    for k in source:
        line.AddPoint_2D(*cell_centre(gt, k // cols, k % cols))
    polygon = line.Buffer(SOURCE_HALF_WIDTH, 8)
    ds, layer = new_layer(out("mudflow_release.gpkg"), srs, ogr.wkbPolygon)
    layer.CreateField(ogr.FieldDefn("depth", ogr.OFTReal))
    f = ogr.Feature(layer.GetLayerDefn())
    f.SetField("depth", SOURCE_DEPTH)
    f.SetGeometry(polygon)
    layer.CreateFeature(f)
    ds = None

    write_raster(out("dem.tif"), np.where(valid, z, DEM_NODATA).astype(np.float32), gt, srs,
                 gdal.GDT_Float32, DEM_NODATA, "elevation", unit="m", predictor=3)
    write_raster(out("lithology.tif"), lith, gt, srs, gdal.GDT_Byte, CLASS_NODATA,
                 "lithology (Rockyfor3D soil type)", classes=LITHOLOGY_CLASSES, predictor=2)
    write_raster(out("vegetation.tif"), veg, gt, srs, gdal.GDT_Byte, CLASS_NODATA,
                 "vegetation class", classes=VEGETATION_CLASSES, predictor=2)

    # Summary.
    n_valid = int(valid.sum())
    print(f"crop: columns {WINDOW[0]}..{WINDOW[0] + cols - 1}, rows {WINDOW[1]}..{WINDOW[1] + rows - 1}"
          f" of the source; {cols} x {rows} cells of {cell:g} m")
    print(f"extent: x {gt[0]:.4f} .. {gt[0] + cols * cell:.4f}, y {gt[3] + rows * gt[5]:.4f} .. {gt[3]:.4f}")
    print(f"nodata cells: {rows * cols - n_valid}; elevation {z[valid].min():.1f} .. {z[valid].max():.1f} m")
    for title, grid, classes in (("lithology", lith, LITHOLOGY_CLASSES),
                                 ("vegetation", veg, VEGETATION_CLASSES)):
        shares = ", ".join(f"{code} {100.0 * np.sum(grid == code) / n_valid:.1f}%" for code in classes)
        print(f"{title}: {shares}")
    print(f"rock-fall release: {len(keep)} points of {len(cells)} cells in the largest cliff band"
          f" (spacing >= {spacing:g} m)")
    sx, sy = cell_centre(gt, *start)
    rx, ry = cell_centre(gt, runout[0] // cols, runout[0] % cols)
    print(f"mud-flow release: {polygon.GetArea():.0f} m2, depth {SOURCE_DEPTH} m, from ({sx:.1f}, {sy:.1f})"
          f" {length:.0f} m down the gully; path reaches gentle ground at ({rx:.1f}, {ry:.1f}) after"
          f" {runout[1]:.0f} m, {zf[start] - zf.flat[runout[0]]:.0f} m lower")


if __name__ == "__main__":
    main()

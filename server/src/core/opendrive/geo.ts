/**
 * A WGS84 latitude/longitude as x, y of a road network, by its `<header><geoReference>`.
 *
 * Two readings of a geoReference exist, and the export must say which it used:
 * - a PROJ string (`+proj=tmerc ...`): the projection OpenDRIVE means, computed by proj4js (the JavaScript port of
 *   PROJ, its projections and datums; grid files are not available offline, so a `+nadgrids` string is refused);
 * - CARLA's: CARLA reads only `+lat_0` and `+lon_0` of any geoReference (defaults 42, 2) and maps with a Mercator
 *   scaled at lat_0 about that origin (LibCarla geom/GeoLocation; ScenarioRunner's copy is
 *   srunner/tools/route_manipulation.py `_location_to_gps` and `_get_latlon_ref`). CARLA's own towns write no
 *   `+proj` (Town05: `+lat_0=49 +lon_0=8`), so for them CARLA's reading is the only one, and it inverts exactly.
 */
import type { RoadNetwork } from './road';

/** LibCarla geom/GeoLocation's EARTH_RADIUS_EQUA (also route_manipulation.py). */
const EARTH_RADIUS_EQUA = 6378137.0;
/** How far from every road's reference line start a converted point may lie before the geoReference is taken not to describe the file's x, y. */
const REACH_MARGIN = 1000;

export interface RoadXY {
  x: number;
  y: number;
  /** Which reading of the geoReference placed it, for the report. */
  how: string;
  /** Where CARLA's own reading (its GNSS, its geolocation) puts the same latitude/longitude, when it differs from `how`'s. */
  carla?: { x: number; y: number };
}

/** The `+key=value` terms of a PROJ string (a bare `+key` is `''`). */
function projTerms(text: string): Map<string, string> {
  const terms = new Map<string, string>();
  for (const item of text.split(/\s+/)) {
    const match = /^\+([^=]+)(?:=(.*))?$/.exec(item);
    if (match) terms.set(match[1], match[2] ?? '');
  }
  return terms;
}

/** CARLA's geo-reference inverted: the x, y (OpenDRIVE's, y to the left) whose geolocation CARLA reports as latitude, longitude. */
function carlaGeoToXY(latitude: number, longitude: number, lat0: number, lon0: number): { x: number; y: number } {
  const scale = Math.cos((lat0 * Math.PI) / 180);
  const mercator = (lat: number, lon: number) => ({
    x: (scale * lon * Math.PI * EARTH_RADIUS_EQUA) / 180,
    y: scale * EARTH_RADIUS_EQUA * Math.log(Math.tan(((90 + lat) * Math.PI) / 360)),
  });
  const origin = mercator(lat0, lon0);
  const point = mercator(latitude, longitude);
  // CARLA's y points right (y = -y of OpenDRIVE); its transform subtracts that y: my -= location.y.
  return { x: point.x - origin.x, y: point.y - origin.y };
}

/** The x, y of a latitude/longitude (degrees, WGS84) in the road network, or why the export cannot compute it exactly. */
export async function geoToRoad(network: RoadNetwork, latitude: number, longitude: number): Promise<RoadXY | string> {
  const reference = network.geoReference;
  if (!reference) return 'the road file has no geoReference to place it by';
  if (network.geoOffset) return `the road file's header has an <offset> (${network.geoOffset}), which the export does not apply`;
  const terms = projTerms(reference);
  const lat0 = Number(terms.get('lat_0') ?? 42);
  const lon0 = Number(terms.get('lon_0') ?? 2);
  const carla = Number.isFinite(lat0) && Number.isFinite(lon0) ? carlaGeoToXY(latitude, longitude, lat0, lon0) : undefined;
  let placed: RoadXY;
  if (!terms.has('proj')) {
    if (!carla || !terms.has('lat_0') || !terms.has('lon_0'))
      return `its geoReference '${reference}' names no projection and no +lat_0/+lon_0`;
    placed = { ...carla, how: `CARLA's reading of the geoReference '${reference}' (no +proj: LibCarla GeoLocation, Mercator at lat_0)` };
  } else {
    if (terms.has('nadgrids')) return `its geoReference '${reference}' shifts the datum by grid files, which are not available here`;
    const { default: proj4 } = await import('proj4');
    let xy: number[];
    try {
      xy = proj4('WGS84', reference).forward([longitude, latitude]);
    } catch (error) {
      return `its geoReference '${reference}' is not a projection proj4js computes (${error instanceof Error ? error.message : String(error)})`;
    }
    if (!xy.every(Number.isFinite)) return `its geoReference '${reference}' has no finite x, y for this place`;
    placed = { x: xy[0], y: xy[1], how: `the geoReference '${reference}' (computed with proj4js, PROJ's projections)` };
    if (carla && Math.hypot(carla.x - placed.x, carla.y - placed.y) > 0.01) placed.carla = carla;
  }
  const far = distanceFromRoads(network, placed.x, placed.y);
  if (far > REACH_MARGIN)
    return `its geoReference puts it at x ${placed.x.toFixed(1)}, y ${placed.y.toFixed(1)}, ${(far / 1000).toFixed(1)} km from every road: the geoReference does not describe the file's coordinates`;
  return placed;
}

/** How far a point lies from the nearest road (its reference line's start and end points, each widened by its length). */
function distanceFromRoads(network: RoadNetwork, x: number, y: number): number {
  let nearest = Infinity;
  for (const road of network.roads)
    for (const geometry of road.geometries)
      nearest = Math.min(nearest, Math.max(0, Math.hypot(geometry.x - x, geometry.y - y) - geometry.length));
  return nearest;
}

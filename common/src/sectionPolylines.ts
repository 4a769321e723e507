/** The road drawing the server samples for the bird's-eye view: plain data, so that the scene protocol can carry it. */

/** One lane section drawn as its lane borders: polylines of x, y pairs (metres, rounded to the centimetre), left to right. */
export interface SectionPolylines {
  road: string;
  /** Index of the lane section in its road. */
  section: number;
  junction: boolean;
  /** Lanes left to right, the center lane (0) included. */
  lanes: { id: number; type: string; driving: boolean }[];
  /** Outer border of each lane in `lanes` (lane 0: the lane-offset line); flat [x0, y0, x1, y1, ...]. */
  borders: number[][];
}

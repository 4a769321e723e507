/** Placing the entities' names on the bird's-eye view so that no two overlap. Pure, no imports. */

/** minX, minY, maxX, maxY. */
export type Bounds = [number, number, number, number];

/** A label to place beside its anchor (an entity's box on screen, px); lower `priority` is placed first. */
export interface LabelRequest {
  text: string;
  anchor: Bounds;
  width: number;
  height: number;
  priority: number;
}

export interface PlacedLabel {
  text: string;
  /** The text's left end and baseline. */
  x: number;
  y: number;
  box: Bounds;
  /** From the anchor's middle to the label, when the label is not right beside its anchor. */
  leader?: [number, number, number, number];
}

export const overlaps = (a: Bounds, b: Bounds): boolean => a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];

/** Directions around the anchor, the usual map-labelling order: upper right first. */
const DIRECTIONS: [number, number][] = [
  [1, -1],
  [1, 1],
  [-1, -1],
  [-1, 1],
  [1, 0],
  [-1, 0],
  [0, -1],
  [0, 1],
];
/** Gaps from the anchor tried in turn, px; beyond the first, a leader line joins label and anchor. */
const DISTANCES = [3, 18, 36, 60];

/**
 * Greedy placement: by priority, each label takes the first free place around its anchor (8 directions,
 * then farther out with a leader line) that overlaps no label placed before, no entity (`obstacles`,
 * screen boxes) and stays on screen; a label that finds none is left out. Placed labels never overlap.
 */
export function placeLabels(requests: LabelRequest[], obstacles: Bounds[], width: number, height: number): PlacedLabel[] {
  const placed: PlacedLabel[] = [];
  const taken: Bounds[] = [];
  for (const request of [...requests].sort((a, b) => a.priority - b.priority)) {
    const [ax0, ay0, ax1, ay1] = request.anchor;
    const middleX = (ax0 + ax1) / 2;
    const middleY = (ay0 + ay1) / 2;
    let chosen: PlacedLabel | undefined;
    for (const distance of DISTANCES) {
      for (const [dx, dy] of DIRECTIONS) {
        const x0 = dx > 0 ? ax1 + distance : dx < 0 ? ax0 - distance - request.width : middleX - request.width / 2;
        const y0 = dy > 0 ? ay1 + distance : dy < 0 ? ay0 - distance - request.height : middleY - request.height / 2;
        const box: Bounds = [x0, y0, x0 + request.width, y0 + request.height];
        if (box[0] < 0 || box[1] < 0 || box[2] > width || box[3] > height) continue;
        if (taken.some((other) => overlaps(box, other)) || obstacles.some((other) => overlaps(box, other))) continue;
        const nearX = Math.min(Math.max(middleX, box[0]), box[2]);
        const nearY = Math.min(Math.max(middleY, box[1]), box[3]);
        chosen = { text: request.text, x: x0, y: y0 + request.height * 0.8, box };
        if (distance > DISTANCES[0]) chosen.leader = [middleX, middleY, nearX, nearY];
        break;
      }
      if (chosen) break;
    }
    if (!chosen) continue;
    placed.push(chosen);
    taken.push(chosen.box);
  }
  return placed;
}

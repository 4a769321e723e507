/**
 * A collision esmini's detection logged (`--collision`), in words: the run's message (server/src/esmini/run.ts
 * `collisionSentence`) and the bird's-eye view's notes (client/src/birdsEye/runData.ts) say it alike.
 */

/** Two entities whose bounding boxes begin to overlap at `time` (s). */
export interface RunCollision {
  entities: [string, string];
  time: number;
}

/** Why a collision is said at all: esmini does not stop there. */
export const COLLISION_WHY = 'their bounding boxes overlap; esmini drives on through each other';

/** Seconds without trailing zeros: 30, 2.5, 4.45. */
export function secondsText(seconds: number): string {
  return String(Number(seconds.toFixed(3)));
}

/**
 * `A and B collide at t=4.45 s`; `named` gives how each entity is named (a run's message adds where it is declared), and a
 * collision without a time is one from the start.
 */
export function collisionWords(
  collision: { entities: readonly [string, string]; time: number | undefined },
  named: (entity: string) => string = (entity) => entity,
): string {
  const [a, b] = collision.entities.map(named);
  return `${a} and ${b} collide${collision.time === undefined ? ' at the start' : ` at t=${secondsText(collision.time)} s`}`;
}

/** One collision as a note of its own: `A and B collide at t=4.45 s (their bounding boxes overlap; ...)`. */
export function collisionNote(collision: RunCollision): string {
  return `${collisionWords(collision)} (${COLLISION_WHY})`;
}

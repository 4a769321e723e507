/**
 * A LateralDistanceAction's `displacement` and `coordinateSystem` (1.1+) in the 1.0 form ScenarioRunner reads.
 * ScenarioRunner builds it as ChangeLateralDistance (SR_PARSER convert_maneuver_to_atomic), whose distance is an
 * offset from the lane centre on the side its sign says: positive to the right, negative to the left (SR_ATOMICS
 * ChangeLateralDistance: its docstring and the offset it sets from the reference's lane centre). With the displacement
 * dropped, a distance to the left of the reference became one to the right; it is now written with that sign.
 */
import { SR_ATOMICS, SR_PARSER } from './carlaFacts';
import type { LossSink } from './carlaLosses';
import { attr, fourDecimals, named, Node, removeAttr, setAttr } from './tree';

const SIDES: Record<string, { sign: 1 | -1; side: string }> = {
  leftToReferencedEntity: { sign: -1, side: 'left' },
  rightToReferencedEntity: { sign: 1, side: 'right' },
};

const CHANGE_LATERAL_DISTANCE = `${SR_PARSER} convert_maneuver_to_atomic, ${SR_ATOMICS} ChangeLateralDistance`;

export function lateralDistances(tree: Node, sink: LossSink): void {
  for (const action of named(tree, 'LateralDistanceAction')) {
    const displacement = attr(action, 'displacement');
    const coordinateSystem = attr(action, 'coordinateSystem');
    removeAttr(action, 'displacement');
    removeAttr(action, 'coordinateSystem');
    if (coordinateSystem === 'entity' || coordinateSystem === 'trajectory')
      sink.approximated(
        action,
        'LateralDistanceAction/@coordinateSystem',
        `${coordinateSystem} is not in 1.0: dropped; the distance is measured between lane centres`,
        `ScenarioRunner offsets the actor from its lane's centre by the reference's offset from its own and the distance (${CHANGE_LATERAL_DISTANCE})`,
      );
    if (displacement === undefined) continue;
    const side = SIDES[displacement];
    const written = attr(action, 'distance');
    const distance = Number(written);
    if (!side || written === undefined || !Number.isFinite(distance)) {
      sink.approximated(
        action,
        'LateralDistanceAction/@displacement',
        `${displacement} is not in 1.0: dropped; the distance ${written ?? '(none)'} is written as it is`,
        `ScenarioRunner puts a positive distance to the right of the reference, a negative one to the left (${CHANGE_LATERAL_DISTANCE})`,
      );
      continue;
    }
    const signed = side.sign * Math.abs(distance);
    setAttr(action, 'distance', fourDecimals(signed));
    sink.approximated(
      action,
      'LateralDistanceAction/@displacement',
      `${displacement} is written as the distance ${fourDecimals(signed)} m (1.0 has no displacement: ScenarioRunner takes the side from the sign; esmini reads a 1.0 sign the other way, positive to the left)`,
      `ScenarioRunner puts a positive distance to the right of the reference, a negative one to the left (${CHANGE_LATERAL_DISTANCE}), so the actor keeps to the ${side.side} as written`,
    );
  }
}

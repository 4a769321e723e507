import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** The related location's note: the private action with no actor. */
export const NO_ACTOR_ACTION_NOTE = 'a private action of the group';

/** ManeuverGroup `group` holds private actions but names no actor. */
export function noActorWording(group: string): ProblemWording<'no-actor'> {
  return {
    severity: 'warning',
    code: 'no-actor',
    message: `ManeuverGroup '${group}' holds private actions but names no actor for them to act on (ASAM's Quality Checker reports it as an error; esmini runs it, the actions acting on no entity)`,
    hint: 'add <EntityRef entityRef="..."/> to its <Actors>',
  };
}

export const NO_ACTOR = defineDiagnostic({
  code: 'no-actor',
  rule: {
    description: 'A ManeuverGroup with private actions names an actor (an EntityRef, or selectTriggeringEntities).',
    qcRule: QC.privateActionActor,
  },
  severity: 'warning',
});

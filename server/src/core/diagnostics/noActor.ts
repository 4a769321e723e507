import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** The related location's note: the private action with no actor. */
export const NO_ACTOR_ACTION_NOTE = 'a private action of the group';

/**
 * ManeuverGroup `group` holds private actions but names no actor (`selectsTriggering`: it selects the triggering
 * entities, but its Act's StartTrigger has no entity condition to take them from). An error, as ASAM's Quality
 * Checker reports it: esmini 3.6 quits ("PrivateAction ... missing actor(s)", ScenarioReader.cpp:5304-5310).
 */
export function noActorWording(group: string, selectsTriggering = false): ProblemWording<'no-actor'> {
  const why = selectsTriggering
    ? "takes its actors from the triggering entities, and its Act's StartTrigger has no entity condition to give any"
    : 'names no actor for them to act on';
  return {
    severity: 'error',
    code: 'no-actor',
    message: `ManeuverGroup '${group}' holds private actions but ${why} (esmini refuses the scenario: "missing actor(s)")`,
    hint: 'add <EntityRef entityRef="..."/> to its <Actors>',
  };
}

export const NO_ACTOR = defineDiagnostic({
  code: 'no-actor',
  rule: {
    description:
      "A ManeuverGroup with private actions names an actor (an EntityRef, or selectTriggeringEntities with an entity condition in its Act's StartTrigger).",
    qcRule: QC.privateActionActor,
  },
  severity: 'error',
});

import { defineDiagnostic, ProblemWording } from './definition';

/** A ManeuverGroup holding a ScenarioReference with no actor for the imported groups. */
export function noActorsWording(group: string): ProblemWording<'no-entity-ref'> {
  return {
    severity: 'error',
    code: 'no-entity-ref',
    message: `ManeuverGroup '${group}' has no <Actors><EntityRef entityRef="..."/></Actors>, so the imported groups have no actor`,
    hint: 'add an Actors element with the EntityRef of the entity that performs the imported groups',
  };
}

/** The actor's EntityRef without its entityRef attribute. */
export function noEntityRefAttributeWording(): ProblemWording<'no-entity-ref'> {
  return {
    severity: 'error',
    code: 'no-entity-ref',
    message: 'this EntityRef has no entityRef attribute',
    hint: 'write entityRef="NAME" with the name of a ScenarioObject',
  };
}

export const NO_ENTITY_REF = defineDiagnostic({
  code: 'no-entity-ref',
  rule: { description: 'A ManeuverGroup holding a ScenarioReference names its actor with an EntityRef.' },
  severity: 'error',
});

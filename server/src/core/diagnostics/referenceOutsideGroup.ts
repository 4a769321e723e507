import { defineDiagnostic, ProblemWording } from './definition';

/** A ScenarioReference that does not stand directly inside a ManeuverGroup. */
export function referenceOutsideGroupWording(): ProblemWording<'reference-outside-group'> {
  return {
    severity: 'error',
    code: 'reference-outside-group',
    message: 'a ScenarioReference must stand directly inside a ManeuverGroup',
    hint: undefined,
  };
}

export const REFERENCE_OUTSIDE_GROUP = defineDiagnostic({
  code: 'reference-outside-group',
  rule: { description: 'A ScenarioReference stands inside a ManeuverGroup.' },
  severity: 'error',
});

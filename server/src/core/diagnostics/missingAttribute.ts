import { defineDiagnostic, ProblemWording } from './definition';

/** A ScenarioReference without its scenarioFileName. */
export function missingScenarioFileNameWording(): ProblemWording<'missing-attribute'> {
  return {
    severity: 'error',
    code: 'missing-attribute',
    message: 'ScenarioReference has no scenarioFileName attribute',
    hint: 'add scenarioFileName="NAME.xosc" or "NAME.mosc"',
  };
}

/** A ManeuverGroupReference without its maneuverGroupName. */
export function missingGroupNameWording(): ProblemWording<'missing-attribute'> {
  return { severity: 'error', code: 'missing-attribute', message: 'ManeuverGroupReference has no maneuverGroupName attribute' };
}

/** A ParameterReference without its key or its value. */
export function incompleteParameterReferenceWording(): ProblemWording<'missing-attribute'> {
  return {
    severity: 'error',
    code: 'missing-attribute',
    message: 'ParameterReference needs both key and value attributes',
    hint: 'write <ParameterReference key="Element.attribute" value="..."/>',
  };
}

export const MISSING_ATTRIBUTE = defineDiagnostic({
  code: 'missing-attribute',
  rule: { description: 'A reference element has its required attributes.' },
  severity: 'error',
});

import { Severity } from '../problems';
import { defineDiagnostic, ProblemWording } from './definition';

/**
 * A problem the variations engine (core/variations/) found in a distribution file, or in its ScenarioFile
 * (`inScenario`: that file's name and 1-based line, where the problem is shown at the ScenarioFile).
 */
export function distributionWording(
  severity: Severity,
  engineMessage: string,
  inScenario?: { file: string; line: number },
): ProblemWording<'distribution'> {
  return {
    severity,
    code: 'distribution',
    message: inScenario ? `in the ScenarioFile (${inScenario.file}:${inScenario.line}): ${engineMessage}` : engineMessage,
  };
}

/** A ParameterValueDistribution that does not expand: the engine says why. */
export const DISTRIBUTION = defineDiagnostic({
  code: 'distribution',
  rule: {
    description:
      'A ParameterValueDistribution expands: its ScenarioFile resolves, its values fit their parameters, its ranges and steps make sense.',
  },
  severity: 'error',
});

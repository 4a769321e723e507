import { Severity } from '../problems';
import { changeToSuggestion, defineDiagnostic, isSuggestion, ProblemWording } from './definition';

/** A parameterName the ScenarioFile does not declare at its root, as the engine says it, with the closest declared name. */
export function unknownDistributionParameterWording(
  severity: Severity,
  engineMessage: string,
  suggestion: string | undefined,
): ProblemWording<'unknown-distribution-parameter'> {
  return {
    severity,
    code: 'unknown-distribution-parameter',
    message: engineMessage + (suggestion ? `; did you mean '${suggestion}'?` : ''),
  };
}

/** A distribution's parameter the scenario lacks: the closest one it declares. */
export const UNKNOWN_DISTRIBUTION_PARAMETER = defineDiagnostic({
  code: 'unknown-distribution-parameter',
  rule: { description: "A distribution's parameterName is a parameter its ScenarioFile declares at its root." },
  severity: 'error',
  isData: isSuggestion,
  fixes: changeToSuggestion,
});

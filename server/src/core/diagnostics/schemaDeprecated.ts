import { ProblemDataByCode } from '../problems';
import { SchemaFactsByCode } from '../schema/facts';
import { changeToSuggestion, defineDiagnostic, isSuggestion, Words } from './definition';

export function schemaDeprecatedWording(facts: SchemaFactsByCode['schema-deprecated']): Words {
  if (facts.kind === 'value') {
    const { value, element, attribute, version, instead } = facts;
    return {
      message: `the value '${value}' of ${element}.${attribute} is deprecated in OpenSCENARIO ${version}${instead ? `; write '${instead}'` : ''}`,
    };
  }
  const writeInstead = facts.instead !== undefined ? `; write ${facts.instead} instead` : '';
  if (facts.kind === 'element') {
    const { element, since, version } = facts;
    return {
      message: `<${element}> is deprecated${since ? ` since OpenSCENARIO ${since}` : ` in OpenSCENARIO ${version}`}${writeInstead}`,
    };
  }
  const { element, attribute, together, keptFor } = facts;
  const since = facts.since ? ` since OpenSCENARIO ${facts.since}` : '';
  if (keptFor) {
    // Leaving it out makes a file that simulator refuses: the advice keeps it, and says why.
    const needs = `keep ${attribute} while the scenario runs in ${keptFor.simulator}, which reads ${attribute} alone and refuses the action without it (${keptFor.note}; ${keptFor.source})`;
    return {
      message:
        together.length > 0
          ? `${element}.${attribute} is deprecated${since} and written together with its replacement ${together.join(' and ')}: ${needs}; leave it out only for a simulator that reads ${together.join(' and ')}`
          : `${element}.${attribute} is deprecated${since}; write ${facts.instead ?? 'its replacement'} as well, and ${needs}`,
    };
  }
  return {
    message:
      together.length > 0
        ? `${element}.${attribute} is deprecated${since} and written together with its replacement ${together.join(' and ')}: leave out ${attribute}`
        : `${element}.${attribute} is deprecated${since}${writeInstead}`,
  };
}

/** A deprecated element, attribute or value: a warning, struck through, whose fix writes the standard's replacement. */
export const SCHEMA_DEPRECATED = defineDiagnostic({
  code: 'schema-deprecated',
  rule: {
    description: 'No deprecated element, attribute or value is used (a warning, as in both official checkers); the replacement is named.',
  },
  severity: 'warning',
  deprecated: true,
  isData: (value): value is ProblemDataByCode['schema-deprecated'] => isSuggestion(value),
  fixes: changeToSuggestion,
});

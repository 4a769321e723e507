import { ProblemDataByCode } from '../problems';
import { OtherVersions, SchemaFactsByCode, VersionRead } from '../schema/facts';
import { defineDiagnostic, didYouMean, isSuggestion, Words } from './definition';

/** The version a file is read as, in a hint: the one its FileHeader states, or the one read. */
function readAsWords({ version, stated }: VersionRead): string {
  return stated ? `the FileHeader states ${stated}` : `the file is read as ${version}`;
}

/** `NAME belongs to OpenSCENARIO 1.2, 1.3; the FileHeader states 1.0 (revMinor)`: the versions that know a name the file's does not. */
export function otherVersionsWords(name: string, { versions, ...read }: OtherVersions, what = 'belongs to'): string {
  return `${name} ${what} OpenSCENARIO ${versions.join(', ')}; ${readAsWords(read)} (revMinor)`;
}

export function schemaVersionWording(facts: SchemaFactsByCode['schema-version']): Words {
  if (facts.kind === 'fallback') return { message: `${facts.fallback}: checked against the OpenSCENARIO ${facts.version} schema` };
  return {
    message: `the expression '${facts.value}' needs OpenSCENARIO 1.1 or later; this file is read as ${facts.version}`,
    hint: didYouMean(facts.suggestion),
  };
}

/** A FileHeader naming a version the project has no schema of, or a form that version lacks: the file is checked against another. */
export const SCHEMA_VERSION = defineDiagnostic({
  code: 'schema-version',
  rule: { description: 'The FileHeader names an OpenSCENARIO version the project knows.' },
  severity: 'information',
  isData: (value): value is ProblemDataByCode['schema-version'] => isSuggestion(value),
});

import { Problem } from '../problems';
import { SchemaFacts } from '../schema/facts';
import { FindingWords, SchemaCheckMemory } from '../schema/problems';
import { SchemaCheckOptions } from '../schema/validate';
import { refId, SourceRef } from '../sources';
import { XmlDocument } from '../xml';
import { setByWords, Words } from './definition';
import { schemaCardinalityWording } from './schemaCardinality';
import { schemaDeprecatedWording } from './schemaDeprecated';
import { schemaMissingAttributeWording } from './schemaMissingAttribute';
import { schemaMissingElementWording } from './schemaMissingElement';
import { schemaOrderWording } from './schemaOrder';
import { schemaUnknownAttributeWording } from './schemaUnknownAttribute';
import { schemaUnknownElementWording } from './schemaUnknownElement';
import { schemaValueWording } from './schemaValue';
import { schemaVersionWording } from './schemaVersion';

/*
 * The schema check's findings as problems: each worded by its code's module from the facts the check
 * found (core/schema/ produces facts; it lies below this folder).
 */

/** The message and hint of a schema finding; `setBy` names the ParameterReference that set the value checked. */
export function schemaFindingWords(finding: SchemaFacts, setBy?: string): Words {
  const words = wordsOf(finding);
  return setBy === undefined ? words : { ...words, message: setByWords(words.message, setBy) };
}

function wordsOf(finding: SchemaFacts): Words {
  switch (finding.code) {
    case 'schema-version':
      return schemaVersionWording(finding.facts);
    case 'schema-unknown-element':
      return schemaUnknownElementWording(finding.facts);
    case 'schema-unknown-attribute':
      return schemaUnknownAttributeWording(finding.facts);
    case 'schema-value':
      return schemaValueWording(finding.facts);
    case 'schema-deprecated':
      return schemaDeprecatedWording(finding.facts);
    case 'schema-missing-attribute':
      return schemaMissingAttributeWording(finding.facts);
    case 'schema-missing-element':
      return schemaMissingElementWording(finding.facts);
    case 'schema-order':
      return schemaOrderWording(finding.facts);
    case 'schema-cardinality':
      return schemaCardinalityWording(finding.facts);
  }
}

/** A finding as a problem at offsets of `document`; `setBy` names the ParameterReference that set the value checked. */
export function toProblem(
  source: SourceRef,
  document: XmlDocument,
  finding: FindingWords,
  start: number,
  end: number,
  setBy?: string,
): Problem {
  const { message, hint } = schemaFindingWords(finding, setBy);
  const problem: Problem = {
    source,
    range: document.lines.range(start, end),
    severity: finding.severity,
    code: finding.code,
    message,
  };
  if (hint) problem.hint = hint;
  if (finding.data) problem.data = finding.data;
  if (finding.subject) problem.subject = finding.subject;
  return problem;
}

/** The schema's problems of one file as it is written (the modular extension allowed). */
export function schemaProblems(
  source: SourceRef,
  document: XmlDocument,
  memory: SchemaCheckMemory,
  options: Omit<SchemaCheckOptions, 'modular'> = {},
): Problem[] {
  return memory
    .check(refId(source), document, { ...options, modular: true })
    .map((entry) => toProblem(source, document, entry.finding, entry.start, entry.end));
}

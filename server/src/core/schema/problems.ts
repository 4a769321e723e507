import { copiedFrom, FlatSource, originOf } from '../flatten';
import { ParameterReferenceInfo } from '../model';
import { Problem } from '../problems';
import { SourceRef } from '../sources';
import { attribute, XmlDocument, XmlElement } from '../xml';
import { checkSchema, findingOffsets, SchemaCheckOptions, SchemaFinding } from './validate';

function toProblem(source: SourceRef, document: XmlDocument, finding: SchemaFinding, start: number, end: number): Problem {
  const problem: Problem = { source, range: document.lines.range(start, end), severity: finding.severity, code: finding.code, message: finding.message };
  if (finding.hint) problem.hint = finding.hint;
  if (finding.data) problem.data = finding.data;
  return problem;
}

/** The schema's problems of one file as it is written (the modular extension allowed). */
export function schemaProblems(source: SourceRef, document: XmlDocument, options: Omit<SchemaCheckOptions, 'modular'> = {}): Problem[] {
  return checkSchema(document, { ...options, modular: true }).findings.map((finding) => {
    const [start, end] = findingOffsets(finding);
    return toProblem(source, document, finding, start, end);
  });
}

/**
 * The schema's problems of a flattened output, strictly (no extension), each at the place in the
 * source files that the offending element or attribute was copied from.
 */
export function outputSchemaProblems(output: FlatSource, options: Omit<SchemaCheckOptions, 'modular'> = {}): Problem[] {
  const document = output.model?.document;
  if (!document) return [];
  const problems: Problem[] = [];
  for (const finding of checkSchema(document, { ...options, modular: false }).findings) {
    const origin = originOf(output, finding.element);
    const originDocument = (origin.source.original ?? origin.source.model)?.document;
    if (!originDocument) continue;
    // Data offsets (insertAt) belong to the output; they are dropped rather than pointing into the wrong file.
    const data = finding.data ? { ...finding.data } : undefined;
    if (data) delete data.insertAt;
    const override = finding.part === 'value' && finding.attribute ? overrideOf(output, finding.element, finding.attribute.name) : undefined;
    if (override?.valueAttribute && output.original) {
      // The value came from a ParameterReference of this file: that is where it must be fixed.
      const [start, end] = [override.valueAttribute.valueStart, override.valueAttribute.valueEnd];
      problems.push(toProblem(output.ref, output.original.document, { ...finding, message: `${finding.message} (set by ParameterReference '${override.key}')`, data }, start, end));
      continue;
    }
    const mapped: SchemaFinding = { ...finding, element: origin.element, data };
    if (finding.attribute) mapped.attribute = attribute(origin.element, finding.attribute.name);
    if (finding.part !== 'tag' && !mapped.attribute) mapped.part = 'tag';
    const [start, end] = findingOffsets(mapped);
    problems.push(toProblem(origin.source.ref, originDocument, mapped, start, end));
  }
  return problems;
}

/** The ParameterReference of the output's own file that set an attribute of an imported element, if one did. */
function overrideOf(output: FlatSource, element: XmlElement, attributeName: string): ParameterReferenceInfo | undefined {
  const insertion = output.insertions.find((candidate) => element.start >= candidate.start && element.end <= candidate.end);
  const copied = insertion ? copiedFrom(output, insertion, element) : undefined;
  if (!insertion || !copied) return undefined;
  for (const [target, parameter] of insertion.group.plan?.applied ?? []) {
    if (target.element === copied.element && target.attributeName === attributeName) return parameter;
  }
  return undefined;
}

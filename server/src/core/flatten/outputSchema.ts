import { ParameterReferenceInfo } from '../model';
import { Problem } from '../problems';
import { refId } from '../sources';
import { SchemaIndex, schemaIndex } from '../schema/index';
import { attributeType, siteTypeProblem } from '../semantics/parameterValues';
import { toProblem } from '../diagnostics/schemaFindings';
import { PlacedFinding, SchemaCheckMemory } from '../schema/problems';
import { typeOfElement } from '../schema/query';
import { checkAttribute, checkSchema, findingOffsets, SchemaCheckOptions, SchemaFinding, subjectOf } from '../schema/validate';
import { ChosenVersion, chooseVersion } from '../schema/version';
import { OverridableAttribute } from '../keys';
import { coreMemo } from '../memos';
import { ownString } from '../text';

import { attribute, elementAt, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { copiedFrom, originOf } from './origin';
import { FlatSource, LinkedReference } from './types';

/*
 * The schema check of a flattened output: its findings placed where the source files wrote the
 * offending element or attribute, and override values checked before anything is rendered.
 */

/** A remembered finding on the tree of `document` again: undefined when its element or attribute is not where its offsets say. */
function locatedFinding(document: XmlDocument, entry: PlacedFinding): SchemaFinding | undefined {
  const element = elementAt(document, entry.start);
  if (!element) return undefined;
  const found = entry.attributeName === undefined ? undefined : attribute(element, entry.attributeName);
  const finding: SchemaFinding = { ...entry.finding, element };
  if (found) finding.attribute = found;
  if (entry.attributeName !== undefined && !found) return undefined;
  const [start, end] = findingOffsets(finding);
  return start === entry.start && end === entry.end ? finding : undefined;
}

/** The strict check of an output, reusing the check of its previous rendering after an edit inside one value (the live preview). */
function outputFindings(
  output: FlatSource,
  document: XmlDocument,
  memory: SchemaCheckMemory,
  options: Omit<SchemaCheckOptions, 'modular'>,
): SchemaFinding[] {
  const strict = { ...options, modular: false };
  const located = memory.check(`output:${refId(output.ref)}`, document, strict).map((entry) => locatedFinding(document, entry));
  if (located.every((finding) => finding !== undefined)) return located as SchemaFinding[];
  return checkSchema(document, strict).findings;
}

/**
 * The schema's problems of a flattened output, strictly (no extension), each at the place in the
 * source files that the offending element or attribute was copied from.
 */
export function outputSchemaProblems(
  output: FlatSource,
  memory: SchemaCheckMemory,
  options: Omit<SchemaCheckOptions, 'modular'> = {},
): Problem[] {
  const document = output.model?.document;
  if (!document) return [];
  const problems: Problem[] = [];
  for (const finding of outputFindings(output, document, memory, options)) {
    const origin = originOf(output, finding.element);
    const originDocument = (origin.source.original ?? origin.source.model)?.document;
    if (!originDocument) continue;
    // Data offsets (insertAt) belong to the output; they are dropped rather than pointing into the wrong file.
    const data = finding.data ? { ...finding.data } : undefined;
    if (data) delete data.insertAt;
    const override =
      finding.part === 'value' && finding.attribute ? overrideOf(output, finding.element, finding.attribute.name) : undefined;
    if (override?.valueAttribute && output.original) {
      // The value came from a ParameterReference of this file: that is where it must be fixed.
      const [start, end] = [override.valueAttribute.valueStart, override.valueAttribute.valueEnd];
      problems.push(
        toProblem(output.ref, output.original.document, { ...finding, data, subject: subjectOf(finding) }, start, end, override.key),
      );
      continue;
    }
    const mapped: SchemaFinding = { ...finding, element: origin.element, data };
    if (finding.attribute) mapped.attribute = attribute(origin.element, finding.attribute.name);
    if (finding.part !== 'tag' && !mapped.attribute) mapped.part = 'tag';
    const [start, end] = findingOffsets(mapped);
    problems.push(toProblem(origin.source.ref, originDocument, { ...mapped, subject: subjectOf(mapped) }, start, end));
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

/** Above this many values of one attribute its memo starts again (a value typed one character at a time is a new value each time). */
const MAX_REMEMBERED_VALUES = 64;

// A group's attributes and the schemas never change: each value an attribute is given is checked once, not on every edit of the main file.
/** The values checked in one attribute, for one version read and type (messages and hints name the version read and the one stated). */
interface OverrideChecks {
  chosen: Pick<ChosenVersion, 'version' | 'stated' | 'fallback'>;
  typeName: string;
  findings: Map<string, SchemaFinding[]>;
}

const overrideChecks = coreMemo<OverridableAttribute, OverrideChecks>('overrideValueChecks');

/** The findings of the value part of the attribute as the output will hold it: the override's value in place of the default. */
function overrideFindings(
  index: SchemaIndex,
  chosen: ChosenVersion,
  target: OverridableAttribute,
  typeName: string,
  written: XmlAttribute,
  value: string,
): SchemaFinding[] {
  let known = overrideChecks.get(target);
  if (
    !known ||
    known.chosen.version !== chosen.version ||
    known.chosen.stated !== chosen.stated ||
    known.chosen.fallback !== chosen.fallback ||
    known.typeName !== typeName ||
    known.findings.size >= MAX_REMEMBERED_VALUES
  ) {
    known = { chosen: { version: chosen.version, stated: chosen.stated, fallback: chosen.fallback }, typeName, findings: new Map() };
    overrideChecks.set(target, known);
  }
  let findings = known.findings.get(value);
  if (!findings) {
    const found: SchemaFinding[] = [];
    checkAttribute(index, chosen, target.element, typeName, { ...written, value }, (finding) => {
      if (finding.part === 'value' && finding.severity !== 'information') found.push(finding);
    });
    known.findings.set(ownString(value), (findings = found));
  }
  return findings;
}

/** What the check of override values reads of the main file for every reference: its tree and the schema it is read by. */
export interface OverrideContext {
  readonly document: XmlDocument;
  readonly chosen: ChosenVersion;
  readonly index: SchemaIndex;
}

/** The schema the main file's override values are checked by; undefined when it was not read. */
export function overrideContextOf(main: FlatSource, options: Omit<SchemaCheckOptions, 'modular'> = {}): OverrideContext | undefined {
  const document = main.original?.document;
  if (!document) return undefined;
  const chosen = chooseVersion(document, options.version ?? 'auto');
  return { document, chosen, index: schemaIndex(chosen.version) };
}

/**
 * One reference's override values against the type of the attribute they set; `readsParameters` when a value is a
 * parameter of the main file (its problems then depend on declarations outside the reference).
 */
export function referenceOverrideProblems(
  main: FlatSource,
  link: LinkedReference,
  context: OverrideContext,
): { problems: Problem[]; readsParameters: boolean } {
  const { document, chosen, index } = context;
  const problems: Problem[] = [];
  let readsParameters = false;
  for (const group of link.groups) {
    for (const [target, parameter] of group.plan?.applied ?? []) {
      const valueAttribute = parameter.valueAttribute;
      const typeName = valueAttribute ? typeOfElement(index, target.element) : undefined;
      const written = attribute(target.element, target.attributeName);
      if (!valueAttribute || !typeName || !written) continue;
      for (const finding of overrideFindings(index, chosen, target, typeName, written, parameter.value)) {
        problems.push(
          toProblem(
            main.ref,
            document,
            { ...finding, data: undefined, subject: subjectOf(finding) },
            valueAttribute.valueStart,
            valueAttribute.valueEnd,
            parameter.key,
          ),
        );
      }
      // An override `$name`: the main file's parameter must fit the attribute it sets.
      const site = main.semantics?.model.siteOf.get(valueAttribute);
      if (site) readsParameters = true;
      const attributeTypeOf = site ? attributeType(index, target.element, target.attributeName) : undefined;
      const mismatch =
        site && attributeTypeOf && main.semantics
          ? siteTypeProblem(main.semantics, site, attributeTypeOf, `${target.element.name}.${target.attributeName}`, parameter.key)
          : undefined;
      if (mismatch) problems.push(mismatch);
    }
  }
  return { problems, readsParameters };
}

/**
 * Override values against the type of the attribute they set, without rendering the output (for the
 * editor): the same problems, at the same ParameterReference, as the strict check of the output.
 */
export function overrideValueProblems(main: FlatSource, options: Omit<SchemaCheckOptions, 'modular'> = {}): Problem[] {
  const context = overrideContextOf(main, options);
  return context ? main.links.flatMap((link) => referenceOverrideProblems(main, link, context).problems) : [];
}

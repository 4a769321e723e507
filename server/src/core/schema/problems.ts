import { copiedFrom, FlatSource, originOf } from '../flatten';
import { ParameterReferenceInfo } from '../model';
import { Problem } from '../problems';
import { refId, SourceRef } from '../sources';
import { schemaIndex } from './index';
import { typeOfElement } from './query';
import { chooseVersion, ChosenVersion } from './version';
import { attribute, elementAt, markupFreeEdit, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { checkAttribute, checkSchema, findingOffsets, SchemaCheckOptions, SchemaFinding } from './validate';

function toProblem(source: SourceRef, document: XmlDocument, finding: FindingWords, start: number, end: number): Problem {
  const problem: Problem = { source, range: document.lines.range(start, end), severity: finding.severity, code: finding.code, message: finding.message };
  if (finding.hint) problem.hint = finding.hint;
  if (finding.data) problem.data = finding.data;
  return problem;
}

/** A finding by offsets only, so that a remembered check holds no parse tree. */
interface PlacedFinding {
  start: number;
  end: number;
  /** The name of the finding's attribute, to find it again in a later parse. */
  attributeName?: string;
  finding: FindingWords;
}

type FindingWords = Omit<SchemaFinding, 'element' | 'attribute'>;

interface RememberedCheck {
  text: string;
  setting: string;
  chosen: ChosenVersion;
  placed: PlacedFinding[];
}

/** The last check of each file, for edits inside one attribute value (typing a value in a large file). */
const remembered = new Map<string, RememberedCheck>();
const REMEMBERED_FILES = 64;

function placed(finding: SchemaFinding): PlacedFinding {
  const [start, end] = findingOffsets(finding);
  // The tree is dropped: only offsets and words are kept.
  const { element: _element, attribute: _attribute, ...words } = finding;
  return { start, end, attributeName: finding.attribute?.name, finding: words };
}

/**
 * The check of `document` from the remembered check of its previous text, when one edit inside one
 * attribute value separates them: the other findings only move, and that attribute is checked again.
 */
function recheckValueEdit(previous: RememberedCheck, document: XmlDocument): PlacedFinding[] | undefined {
  if (!document.root) return undefined;
  const edit = markupFreeEdit(previous.text, document.text);
  if (!edit) return undefined;
  const delta = edit.insertedEnd - edit.removedEnd;
  let element: XmlElement | undefined = document.root;
  let edited: XmlAttribute | undefined;
  while (element && !edited) {
    edited = element.attributes.find((candidate) => candidate.valueStart <= edit.prefix && edit.insertedEnd <= candidate.valueEnd);
    if (edited || edit.prefix < element.startTagEnd) break;
    element = element.children.find((child) => child.start <= edit.prefix && edit.insertedEnd <= child.end);
  }
  // The FileHeader's revMajor/revMinor choose the schema: an edit there checks everything again.
  if (!element || !edited || element.name === 'FileHeader') return undefined;
  const index = schemaIndex(previous.chosen.version);
  const typeName = typeOfElement(index, element);
  const oldValueEnd = edited.valueEnd - delta;
  const kept = previous.placed
    .filter((entry) => entry.start < edited.nameStart || entry.start > oldValueEnd)
    .map((entry) => (entry.start >= edit.removedEnd ? { ...entry, start: entry.start + delta, end: entry.end + delta } : entry));
  const fresh: PlacedFinding[] = [];
  if (typeName) checkAttribute(index, previous.chosen, element, typeName, edited, (finding) => fresh.push(placed(finding)));
  for (const entry of kept) {
    const insertAt = entry.finding.data?.insertAt;
    if (insertAt !== undefined && Number(insertAt) >= edit.removedEnd) entry.finding = { ...entry.finding, data: { ...entry.finding.data, insertAt: String(Number(insertAt) + delta) } };
  }
  return [...kept, ...fresh].sort((a, b) => a.start - b.start);
}

/** The schema check of a document, from the remembered check of its previous text where one value edit separates them. */
function rememberedCheck(key: string, document: XmlDocument, options: SchemaCheckOptions): PlacedFinding[] {
  const setting = `${options.version ?? 'auto'} ${options.modular ? 'modular' : 'strict'}`;
  const previous = remembered.get(key);
  let check: RememberedCheck | undefined;
  // The same text checks the same (a file read again by a new generation's flattener).
  const same = previous && previous.setting === setting && previous.text === document.text;
  const moved = same ? previous.placed : previous && previous.setting === setting ? recheckValueEdit(previous, document) : undefined;
  if (previous && moved) check = { ...previous, text: document.text, placed: moved };
  else {
    const full = checkSchema(document, options);
    check = { text: document.text, setting, chosen: full.chosen, placed: full.findings.map(placed) };
  }
  remembered.delete(key);
  remembered.set(key, check);
  if (remembered.size > REMEMBERED_FILES) remembered.delete(remembered.keys().next().value as string);
  return check.placed;
}

/** The schema's problems of one file as it is written (the modular extension allowed). */
export function schemaProblems(source: SourceRef, document: XmlDocument, options: Omit<SchemaCheckOptions, 'modular'> = {}): Problem[] {
  return rememberedCheck(refId(source), document, { ...options, modular: true }).map((entry) => toProblem(source, document, entry.finding, entry.start, entry.end));
}

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
function outputFindings(output: FlatSource, document: XmlDocument, options: Omit<SchemaCheckOptions, 'modular'>): SchemaFinding[] {
  const strict = { ...options, modular: false };
  const located = rememberedCheck(`output:${refId(output.ref)}`, document, strict).map((entry) => locatedFinding(document, entry));
  if (located.every((finding) => finding !== undefined)) return located as SchemaFinding[];
  return checkSchema(document, strict).findings;
}

/**
 * The schema's problems of a flattened output, strictly (no extension), each at the place in the
 * source files that the offending element or attribute was copied from.
 */
export function outputSchemaProblems(output: FlatSource, options: Omit<SchemaCheckOptions, 'modular'> = {}): Problem[] {
  const document = output.model?.document;
  if (!document) return [];
  const problems: Problem[] = [];
  for (const finding of outputFindings(output, document, options)) {
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

/**
 * Override values against the type of the attribute they set, without rendering the output (for the
 * editor): the same problems, at the same ParameterReference, as the strict check of the output.
 */
export function overrideValueProblems(main: FlatSource, options: Omit<SchemaCheckOptions, 'modular'> = {}): Problem[] {
  const document = main.original?.document;
  if (!document) return [];
  const chosen = chooseVersion(document, options.version ?? 'auto');
  const index = schemaIndex(chosen.version);
  const problems: Problem[] = [];
  for (const link of main.links) {
    for (const group of link.groups) {
      for (const [target, parameter] of group.plan?.applied ?? []) {
        const valueAttribute = parameter.valueAttribute;
        const typeName = valueAttribute ? typeOfElement(index, target.element) : undefined;
        const written = attribute(target.element, target.attributeName);
        if (!valueAttribute || !typeName || !written) continue;
        // The attribute as the output will hold it: the override's value in place of the default.
        const overridden: XmlAttribute = { ...written, value: parameter.value };
        checkAttribute(index, chosen, target.element, typeName, overridden, (finding) => {
          if (finding.part !== 'value' || finding.severity === 'information') return;
          problems.push(toProblem(main.ref, document, { ...finding, message: `${finding.message} (set by ParameterReference '${parameter.key}')`, data: undefined }, valueAttribute.valueStart, valueAttribute.valueEnd));
        });
      }
    }
  }
  return problems;
}

import { ProblemCode, ProblemSubject, SCHEMA_PROBLEM_CODE_LIST, SchemaFindingData, Severity } from '../problems';
import { closestMatch } from '../text';
import { XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { StateSet } from './automaton';
import { replacementOf, valueReplacementOf } from './deprecations';
import { SchemaIndex, schemaIndex, versionsWith } from './index';
import { ElementParticle, SCHEMA_VERSIONS } from './model';
import { MODULAR_ATTRIBUTE, MODULAR_PLACEMENT, MODULAR_TYPES } from './modular';
import { checkValue, describeType, enumerationValues, repairedValue } from './values';
import { OtherVersions, SchemaFacts } from './facts';
import { chooseVersion, ChosenVersion, SchemaVersionSetting } from './version';

/** Problems the schema finds; `--force` writes a flattened output despite them. */
export const SCHEMA_PROBLEM_CODES: ReadonlySet<ProblemCode> = new Set<ProblemCode>(SCHEMA_PROBLEM_CODE_LIST);

/** Where a finding stands and what it is, apart from its facts. */
interface FindingPlace {
  element: XmlElement;
  attribute?: XmlAttribute;
  part: 'tag' | 'attribute' | 'value';
  severity: Severity;
  /** For quick fixes: the shape `ProblemDataByCode` names for the code. */
  data?: SchemaFindingData;
}

/**
 * A problem at an element's tag name, an attribute's name or an attribute's value (offsets of the document
 * checked): its code and facts, which the code's module (core/diagnostics/) words.
 */
export type SchemaFinding = FindingPlace & SchemaFacts;

export interface SchemaCheckOptions {
  /** Accept the modular extension (SPEC 2): ScenarioReference in a ManeuverGroup. Off for flattened outputs. */
  modular: boolean;
  version?: SchemaVersionSetting;
}

export interface SchemaCheck {
  chosen: ChosenVersion;
  findings: SchemaFinding[];
}

/** At most this many findings per document: a broken file must not flood the editor. */
const MAX_FINDINGS = 2000;

function names(particles: ElementParticle[]): string[] {
  return particles.map((particle) => particle.name);
}

/** The other versions of the schema whose type has an element or attribute of that name. */
function introducedIn(typeName: string, name: string, kind: 'element' | 'attribute', chosen: ChosenVersion): OtherVersions | undefined {
  const versions = versionsWith(typeName, name, kind).filter((version) => version !== chosen.version);
  return versions.length === 0 ? undefined : { versions, version: chosen.version, stated: chosen.stated };
}

/** Where an attribute's value is valid in other versions of the schema: which, and the version the file is read as. */
function validIn(typeName: string, attribute: XmlAttribute, chosen: ChosenVersion): OtherVersions | undefined {
  const versions = SCHEMA_VERSIONS.filter((version) => {
    if (version === chosen.version) return false;
    const index = schemaIndex(version);
    const declaration = index.attribute(typeName, attribute.name);
    const simple = declaration ? index.simpleType(declaration.type) : undefined;
    return simple !== undefined && checkValue(simple, attribute.value).valid;
  });
  return versions.length === 0 ? undefined : { versions, version: chosen.version, stated: chosen.stated };
}

/**
 * Checks a parsed document against the schema of its version: elements, their order and number,
 * attributes and their values. Linear in the document; each content model is a small automaton.
 */
export function checkSchema(document: XmlDocument, options: SchemaCheckOptions): SchemaCheck {
  const chosen = chooseVersion(document, options.version ?? 'auto');
  const findings: SchemaFinding[] = [];
  const root = document.root;
  if (!root) return { chosen, findings };
  const index = schemaIndex(chosen.version);
  const report = (finding: SchemaFinding) => {
    if (findings.length < MAX_FINDINGS) findings.push(finding);
  };
  if (chosen.fallback && chosen.header) {
    report({
      element: chosen.header,
      part: 'tag',
      severity: 'information',
      code: 'schema-version',
      facts: { kind: 'fallback', fallback: chosen.fallback, version: chosen.version },
    });
  }
  if (root.name !== index.schema.rootElement) {
    report({
      element: root,
      part: 'tag',
      severity: 'error',
      code: 'schema-unknown-element',
      facts: { kind: 'root', expected: index.schema.rootElement, found: root.name },
      data: { suggestion: index.schema.rootElement },
    });
    return { chosen, findings };
  }
  const stack: { element: XmlElement; typeName: string }[] = [{ element: root, typeName: index.schema.rootType }];
  // One list of an element's known children, refilled for each element rather than made anew.
  const accepted: KnownChild[] = [];
  while (stack.length > 0 && findings.length < MAX_FINDINGS) {
    const { element, typeName } = stack.pop() as { element: XmlElement; typeName: string };
    checkAttributes(index, chosen, element, typeName, report);
    checkChildren(index, chosen, element, typeName, options, report, accepted);
    for (let i = accepted.length - 1; i >= 0; i--) stack.push(accepted[i]);
  }
  // In document order, as a reader goes through the file.
  findings.sort((a, b) => findingOffsets(a)[0] - findingOffsets(b)[0]);
  return { chosen, findings };
}

/** The checks of one attribute: its name, its value, deprecation. */
export function checkAttribute(
  index: SchemaIndex,
  chosen: ChosenVersion,
  element: XmlElement,
  typeName: string,
  attribute: XmlAttribute,
  report: (finding: SchemaFinding) => void,
): void {
  const type = index.complexType(typeName);
  if (!type) return;
  if (attribute.name === MODULAR_ATTRIBUTE || attribute.name.startsWith('xmlns') || attribute.name.startsWith('xsi:')) return;
  const declaration = index.attribute(typeName, attribute.name);
  if (!declaration) {
    const candidates = type.attributes
      .map((candidate) => candidate.name)
      .filter((name) => !element.attributes.some((other) => other.name === name));
    const suggestion = closestMatch(attribute.name, candidates);
    report({
      element,
      attribute,
      part: 'attribute',
      severity: 'error',
      code: 'schema-unknown-attribute',
      facts: {
        element: element.name,
        attribute: attribute.name,
        version: chosen.version,
        introducedIn: introducedIn(typeName, attribute.name, 'attribute', chosen),
        suggestion,
        candidates,
      },
      data: suggestion ? { suggestion } : undefined,
    });
    return;
  }
  const simple = index.simpleType(declaration.type);
  if (!simple) return;
  const check = checkValue(simple, attribute.value);
  if (!check.valid) {
    const values = enumerationValues(simple);
    // A value of a later version ('override', 1.2) is not misspelt: the closest value here may be the one that version deprecates ('overwrite').
    const inVersions = check.expressionNotInVersion ? undefined : validIn(typeName, attribute, chosen);
    const suggestion = inVersions
      ? undefined
      : values.length > 0
        ? closestMatch(attribute.value, values)
        : repairedValue(simple, attribute.value);
    const place = { element, attribute, part: 'value', data: suggestion ? { suggestion } : undefined } as const;
    report(
      check.expressionNotInVersion
        ? {
            ...place,
            severity: 'warning',
            code: 'schema-version',
            facts: { kind: 'expression', value: attribute.value, version: chosen.version, suggestion },
          }
        : {
            ...place,
            severity: 'error',
            code: 'schema-value',
            facts: {
              element: element.name,
              attribute: attribute.name,
              value: attribute.value,
              type: declaration.type,
              expected: describeType(simple),
              validIn: inVersions,
              suggestion,
            },
          },
    );
  } else if (check.deprecated) {
    const instead = valueReplacementOf(attribute.value.trim());
    report({
      element,
      attribute,
      part: 'value',
      severity: 'warning',
      code: 'schema-deprecated',
      facts: { kind: 'value', element: element.name, attribute: attribute.name, value: attribute.value, version: chosen.version, instead },
      data: instead ? { suggestion: instead } : undefined,
    });
  }
  if (index.isAttributeDeprecated(declaration)) {
    const replacement = replacementOf(typeName, attribute.name);
    const together = [
      ...(replacement?.attributes?.filter((name) => element.attributes.some((other) => other.name === name)) ?? []),
      ...(replacement?.elements?.filter((name) => element.children.some((child) => child.name === name)).map((name) => `<${name}>`) ?? []),
    ];
    report({
      element,
      attribute,
      part: 'attribute',
      severity: 'warning',
      code: 'schema-deprecated',
      facts: {
        kind: 'attribute',
        element: element.name,
        attribute: attribute.name,
        since: declaration.deprecatedSince,
        together,
        instead: replacement?.instead,
        ...(replacement?.keptFor ? { keptFor: replacement.keptFor } : {}),
      },
      data: replacement?.rename && together.length === 0 ? { suggestion: replacement.rename } : undefined,
    });
  }
}

function checkAttributes(
  index: SchemaIndex,
  chosen: ChosenVersion,
  element: XmlElement,
  typeName: string,
  report: (finding: SchemaFinding) => void,
): void {
  const type = index.complexType(typeName);
  if (!type) return;
  // Index loops, no closures: this runs for every element of every file a flatten reads and writes.
  const attributes = element.attributes;
  for (let i = 0; i < attributes.length; i++) checkAttribute(index, chosen, element, typeName, attributes[i], report);
  // The extension's own attributes are checked where the flattener reads them.
  if (MODULAR_TYPES[typeName]) return;
  let missing: string[] | undefined;
  const declarations = type.attributes;
  for (let i = 0; i < declarations.length; i++) {
    const declaration = declarations[i];
    if (declaration.required && !isWritten(attributes, declaration.name)) (missing ??= []).push(declaration.name);
  }
  if (missing) {
    report({
      element,
      part: 'tag',
      severity: 'error',
      code: 'schema-missing-attribute',
      facts: { element: element.name, missing },
      data: { missing },
    });
  }
}

function isWritten(attributes: readonly XmlAttribute[], name: string): boolean {
  for (let i = 0; i < attributes.length; i++) if (attributes[i].name === name) return true;
  return false;
}

/** A child the content model knows: where the check descends, and what the order and number checks read. */
interface KnownChild {
  element: XmlElement;
  typeName: string;
  particle: ElementParticle;
}

/** Checks the children of an element against its content model; fills `accepted` with the children to descend into. */
function checkChildren(
  index: SchemaIndex,
  chosen: ChosenVersion,
  element: XmlElement,
  typeName: string,
  options: SchemaCheckOptions,
  report: (finding: SchemaFinding) => void,
  accepted: KnownChild[],
): void {
  const type = index.complexType(typeName);
  const children = element.children;
  accepted.length = 0;
  if (!type) return;
  for (let i = 0; i < children.length; i++) {
    const child = children[i];
    // A ScenarioReference outside a ManeuverGroup is reported by the flattener.
    if (options.modular && child.name === MODULAR_PLACEMENT.element && typeName !== MODULAR_PLACEMENT.parentType) continue;
    const particle = index.childParticle(typeName, child.name, options.modular);
    if (!particle) {
      const others = index.childParticles(typeName).map((candidate) => candidate.name);
      const suggestion = closestMatch(child.name, others);
      report({
        element: child,
        part: 'tag',
        severity: 'error',
        code: 'schema-unknown-element',
        facts: {
          kind: 'child',
          parent: element.name,
          child: child.name,
          version: chosen.version,
          holdsNoElements: Boolean(type.text) || others.length === 0,
          introducedIn: introducedIn(typeName, child.name, 'element', chosen),
          suggestion,
          children: others,
        },
        data: suggestion ? { suggestion } : undefined,
      });
      continue;
    }
    accepted.push({ element: child, typeName: particle.type, particle });
    if (index.isDeprecated(particle)) {
      report({
        element: child,
        part: 'tag',
        severity: 'warning',
        code: 'schema-deprecated',
        facts: {
          kind: 'element',
          element: child.name,
          since: particle.deprecatedSince,
          version: chosen.version,
          instead: replacementOf(typeName, child.name)?.instead,
        },
      });
    }
  }
  if (type.content?.kind === 'all') checkAll(type.content.items as ElementParticle[], element, accepted, report);
  else checkSequence(index, typeName, element, accepted, options, report);
}

function checkAll(items: ElementParticle[], element: XmlElement, known: KnownChild[], report: (finding: SchemaFinding) => void): void {
  const counts = new Map<string, number>();
  for (const { element: child, particle } of known) {
    const count = (counts.get(child.name) ?? 0) + 1;
    counts.set(child.name, count);
    if (particle.max !== -1 && count > particle.max) {
      report({
        element: child,
        part: 'tag',
        severity: 'error',
        code: 'schema-cardinality',
        facts: { element: child.name, parent: element.name, max: particle.max },
      });
    }
  }
  const missing = items.filter((item) => item.kind === 'element' && item.min > (counts.get(item.name) ?? 0));
  if (missing.length > 0) reportMissing(element, missing, undefined, report);
}

function checkSequence(
  index: SchemaIndex,
  typeName: string,
  element: XmlElement,
  known: KnownChild[],
  options: SchemaCheckOptions,
  report: (finding: SchemaFinding) => void,
): void {
  const automaton = index.automaton(typeName);
  let states: StateSet = automaton.start;
  // A valid sequence (nearly every one) is stepped through without allocating; any misstep is redone below.
  let valid = true;
  for (let position = 0; position < known.length && valid; position++) {
    const next = automaton.step(states, index.modelName(typeName, known[position].element.name, options.modular));
    if (next) states = next.states;
    else valid = false;
  }
  if (valid) {
    if (!automaton.accepts(states)) {
      const missing = automaton.missingToEnd(states);
      if (missing.length > 0) reportMissing(element, missing, undefined, report);
    }
    return;
  }
  states = automaton.start;
  const seen = new Map<string, number>();
  let reportedOrder = false;
  /** Children written later that an order problem already placed earlier in the content model. */
  const placedEarly = new Set<XmlElement>();
  for (let position = 0; position < known.length; position++) {
    const { element: child, particle } = known[position];
    if (placedEarly.has(child)) continue;
    const name = index.modelName(typeName, child.name, options.modular);
    seen.set(name, (seen.get(name) ?? 0) + 1);
    const next = automaton.step(states, name);
    if (next) {
      states = next.states;
      continue;
    }
    const missing = automaton.missingBefore(states, name);
    if (missing && missing.length > 0 && missing.every((candidate) => !seen.has(candidate.name))) {
      const later = missing.map(
        (candidate) =>
          known
            .slice(position + 1)
            .find(
              (other) =>
                !placedEarly.has(other.element) && index.modelName(typeName, other.element.name, options.modular) === candidate.name,
            )?.element,
      );
      if (later.every((other) => other !== undefined)) {
        // The "missing" elements are written, only after this one: an order problem, reported once here.
        for (const other of later) placedEarly.add(other as XmlElement);
        report({
          element: child,
          part: 'tag',
          severity: 'error',
          code: 'schema-order',
          facts: { kind: 'before', element: child.name, parent: element.name, before: names(missing) },
        });
      } else {
        reportMissing(element, missing, child, report);
      }
      const after = missing.reduce<StateSet | undefined>(
        (current, candidate) => (current ? automaton.step(current, candidate.name)?.states : undefined),
        states,
      );
      const stepped = after ? automaton.step(after, name) : undefined;
      if (stepped) {
        states = stepped.states;
        continue;
      }
    }
    const count = seen.get(name) ?? 0;
    if (particle.max !== -1 && count > particle.max) {
      report({
        element: child,
        part: 'tag',
        severity: 'error',
        code: 'schema-cardinality',
        facts: { element: child.name, parent: element.name, max: particle.max },
      });
    } else if (!reportedOrder) {
      // One order problem per parent: after it, the position in the content model is a guess.
      reportedOrder = true;
      const allowed = automaton.allowed(states);
      report({
        element: child,
        part: 'tag',
        severity: 'error',
        code: 'schema-order',
        facts: { kind: 'expected', element: child.name, parent: element.name, expected: names(allowed) },
      });
    }
  }
  if (!automaton.accepts(states)) {
    const missing = automaton.missingToEnd(states);
    if (missing.length > 0) reportMissing(element, missing, undefined, report);
  }
}

function reportMissing(
  element: XmlElement,
  missing: ElementParticle[],
  before: XmlElement | undefined,
  report: (finding: SchemaFinding) => void,
): void {
  const missingNames = names(missing);
  report({
    element: before ?? element,
    part: 'tag',
    severity: 'error',
    code: 'schema-missing-element',
    facts: { parent: element.name, missing: missingNames, before: before?.name },
    data: { missing: missingNames, parent: element.name, ...(before ? { insertAt: String(before.start) } : {}) },
  });
}

/** What a finding is about, by name, for a problem that outlives the parse tree. */
export function subjectOf(finding: Pick<SchemaFinding, 'code' | 'element' | 'attribute' | 'data'>): ProblemSubject {
  const parent = finding.data?.parent;
  // A missing child is about its parent, though the finding stands at the sibling it belongs before.
  const element =
    finding.code === 'schema-missing-element' && parent !== undefined && finding.element.name !== parent
      ? (finding.element.parent ?? finding.element)
      : finding.element;
  const subject: ProblemSubject = { element: element.name };
  if (finding.attribute) subject.attribute = finding.attribute.name;
  if (!element.parent) subject.root = true;
  if (finding.code === 'schema-missing-element') {
    const present = new Set(element.children.map((child) => child.name));
    subject.absent = (finding.data?.missing ?? []).filter((name) => !present.has(name));
  }
  return subject;
}

/** The offsets a finding points at in the document it was found in. */
export function findingOffsets(finding: SchemaFinding): [number, number] {
  if (finding.part === 'attribute' && finding.attribute) return [finding.attribute.nameStart, finding.attribute.nameEnd];
  if (finding.part === 'value' && finding.attribute) return [finding.attribute.valueStart, finding.attribute.valueEnd];
  return [finding.element.start + 1, finding.element.nameEnd];
}

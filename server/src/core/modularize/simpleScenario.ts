import * as path from 'node:path';
import { applyEdits, reindent } from '../flatten/edits';
import { indentationAt } from '../text';
import { attributeValue, descendants, escapeAttributeValue, parseXml, XmlDocument, XmlElement } from '../xml';
import { GroupOccurrence } from './shape';
import { ParsedInput, PooledGroup, RebasePaths } from './types';
import { coreMemo } from '../memos';
import { PARAMETER_REF_ELEMENTS } from '../semantics/parameterUses';

/** One group of a simple scenario: its text as written there, its name, where it came from, its defaults. */
export interface SimpleScenarioParts {
  groupText: string;
  groupName: string;
  /** Where the simple scenario is written (absolute). */
  file: string;
  occurrences: GroupOccurrence[];
  inputs: ParsedInput[];
  /** The group's attribute values as the simple scenario holds them. */
  defaults: string[];
  /** The group's own copies of parameters (PooledGroup.copies). */
  copies?: ReadonlyMap<string, string>;
  /** More groups the same file holds (a pool of behaviours sharing its declarations, catalogs and roads). */
  others?: PooledGroup[];
  unit: string;
  eol: string;
  rebase: RebasePaths;
}

const PARAMETER_USE = /\$\{?([A-Za-z_][\w]*)/g;
/** A ParameterCondition or ParameterAction names its parameter without a `$` (a ParameterAssignment's names its catalog entry's). */
const PARAMETER_REF = new RegExp(
  `<(?:${[...PARAMETER_REF_ELEMENTS].join('|')})\\b[^>]*?\\bparameterRef\\s*=\\s*["']\\$?([A-Za-z_]\\w*)["']`,
  'g',
);
const VARIABLE_REF = /\bvariableRef\s*=\s*["']([^"']+)["']/g;

/** An element's text moved to `depth` levels of `unit`. */
function copied(document: XmlDocument, element: XmlElement, unit: string, depth: number, eol: string): string {
  return (
    unit.repeat(depth) +
    reindent(document.text.slice(element.start, element.end), indentationAt(document.text, element.start), unit.repeat(depth), eol)
  );
}

/**
 * A declaration copied for the simple scenario: one that holds only comments is written on one line
 * (the comments stay in the main, which keeps its own declaration); one with constraints as written.
 */
function declarationText(document: XmlDocument, element: XmlElement, unit: string, eol: string): string {
  if (element.selfClosing || element.children.length > 0) return copied(document, element, unit, 2, eol);
  const startTag = document.text.slice(element.start, element.startTagEnd).replace(/\s*>$/, '');
  return `${unit.repeat(2)}${startTag.replace(/\s*\r?\n\s*/g, ' ')}/>`;
}

function child(element: XmlElement | undefined, name: string): XmlElement | undefined {
  return element?.children.find((candidate) => candidate.name === name);
}

// Each document's elements by kind and `name`, built once however many behaviours look into it.
const namedIndex = coreMemo<XmlDocument, Map<string, XmlElement>>('namedElements');

/** The first element of one of `elementNames` whose `name` attribute is `wanted`, looked for in each document in turn. */
function findNamed(
  documents: XmlDocument[],
  elementNames: string[],
  wanted: string,
): { document: XmlDocument; element: XmlElement } | undefined {
  for (const document of documents) {
    if (!document.root) continue;
    let index = namedIndex.get(document);
    if (!index) {
      index = new Map();
      for (const element of descendants(document.root)) {
        const name = attributeValue(element, 'name');
        const key = `${element.name}\n${name}`;
        if (name !== undefined && !index.has(key)) index.set(key, element);
      }
      namedIndex.set(document, index);
    }
    for (const elementName of elementNames) {
      // A declaration may be written name="$owner", the lenient form check and flatten accept.
      const element =
        index.get(`${elementName}\n${wanted}`) ??
        (elementName === 'ParameterDeclaration' ? index.get(`${elementName}\n$${wanted}`) : undefined);
      if (element) return { document, element };
    }
  }
  return undefined;
}

/** A declaration's text declaring `name` instead, where a group's own copy of a parameter is declared. */
function named(declaration: string, name: string | undefined): string {
  if (name === undefined) return declaration;
  return declaration.replace(/(\bname\s*=\s*["'])[^"']*(["'])/, (_, open: string, close: string) => open + name + close);
}

/**
 * A valid scenario around one group, as the paper's simple_1 and simple_2 are: the declarations and
 * entities the group names (taken from the inputs it came from), the representative input's road
 * network and catalog locations (rebased onto the simple scenario's folder), and a story that plays it.
 */
export async function simpleScenarioText(parts: SimpleScenarioParts): Promise<string> {
  const { groupName, file, occurrences, inputs, unit, eol, rebase } = parts;
  const groups: PooledGroup[] = [parts, ...(parts.others ?? [])];
  const groupText = groups.map((group) => group.groupText).join(eol);
  const defaults = groups.flatMap((group) => group.defaults);
  const representative = inputs[occurrences[0].input];
  const documents = [...new Set(groups.flatMap((group) => group.occurrences).map((occurrence) => inputs[occurrence.input]))].map(
    (input) => input.document,
  );
  const root = representative.document.root as XmlElement;
  const header = child(root, 'FileHeader');
  const lines: string[] = ['<?xml version="1.0" encoding="UTF-8"?>', representative.text.slice(root.start, root.startTagEnd)];
  const headerAttributes = [
    ['revMajor', attributeValue(header ?? root, 'revMajor') ?? '1'],
    ['revMinor', attributeValue(header ?? root, 'revMinor') ?? '0'],
    ['date', attributeValue(header ?? root, 'date') ?? '2020-01-01T00:00:00'],
    [
      'description',
      groups.length === 1
        ? `${groupName}: a behaviour shared by ${occurrences.length} groups, extracted by modular2simple modularize`
        : `${groups.map((group) => group.groupName).join(', ')}: ${groups.length} behaviours, extracted by modular2simple modularize`,
    ],
    ['author', attributeValue(header ?? root, 'author') ?? 'modular2simple'],
  ];
  lines.push(`${unit}<FileHeader ${headerAttributes.map(([name, value]) => `${name}="${escapeAttributeValue(value)}"`).join(' ')}/>`);

  // A group's own copy of a parameter is declared as the parameter is in that group's scenarios, under the copy's name.
  const copyOf = new Map<string, { original: string; documents: XmlDocument[] }>();
  for (const group of groups)
    for (const [copy, original] of group.copies ?? [])
      copyOf.set(copy, { original, documents: [...new Set(group.occurrences.map((occurrence) => inputs[occurrence.input].document))] });
  const declarationOf = (name: string) => {
    const copy = copyOf.get(name);
    return copy ? findNamed(copy.documents, ['ParameterDeclaration'], copy.original) : findNamed(documents, ['ParameterDeclaration'], name);
  };

  // Every value of the group that names an entity of its inputs: the entity is declared here too.
  // A parameter's value may name an entity too (an `entityRef="$owner"`).
  const parameterValues: string[] = [];
  for (const match of groupText.matchAll(PARAMETER_USE)) {
    const declared = declarationOf(match[1]);
    const value = declared && attributeValue(declared.element, 'value');
    if (value !== undefined) parameterValues.push(value);
  }
  const entities: string[] = [];
  const seen = new Set<string>();
  for (const value of [...defaults, ...parameterValues]) {
    if (seen.has(value)) continue;
    seen.add(value);
    const found = findNamed(documents, ['ScenarioObject', 'EntitySelection'], value);
    if (found && found.element.parent?.name === 'Entities') entities.push(copied(found.document, found.element, unit, 2, eol));
  }

  const catalogs = child(root, 'CatalogLocations');
  const catalogText = catalogs ? copied(representative.document, catalogs, unit, 1, eol) : `${unit}<CatalogLocations/>`;
  const roads = child(root, 'RoadNetwork');
  const roadText = roads ? copied(representative.document, roads, unit, 1, eol) : `${unit}<RoadNetwork/>`;
  // Parameters the group uses, with those their values use in turn, in the order first needed.
  const needed: string[] = [];
  const want = (text: string) => {
    for (const match of [...text.matchAll(PARAMETER_USE), ...text.matchAll(PARAMETER_REF)])
      if (!needed.includes(match[1])) needed.push(match[1]);
  };
  for (const text of [groupText, ...entities, catalogText, roadText]) want(text);
  // And those the catalog entries the group references read from its scenario.
  for (const occurrence of groups.flatMap((group) => group.occurrences)) {
    const fromCatalogs = inputs[occurrence.input].catalogParameters;
    for (const element of fromCatalogs ? occurrence.elements : [])
      for (const name of element.name === 'CatalogReference' ? (fromCatalogs?.get(element.start) ?? []) : [])
        if (!needed.includes(name)) needed.push(name);
  }
  const foundDeclarations: { document: XmlDocument; element: XmlElement; copy?: string }[] = [];
  for (let i = 0; i < needed.length; i++) {
    const found = declarationOf(needed[i]);
    if (!found) continue;
    const copy = copyOf.has(needed[i]) ? needed[i] : undefined;
    foundDeclarations.push({ ...found, copy });
    want(named(found.document.text.slice(found.element.start, found.element.end), copy));
  }
  // In the order the inputs declare them: a value may only use parameters declared before it.
  foundDeclarations.sort((a, b) => documents.indexOf(a.document) - documents.indexOf(b.document) || a.element.start - b.element.start);
  const declarations = foundDeclarations.map((found) => named(declarationText(found.document, found.element, unit, eol), found.copy));
  lines.push(
    declarations.length > 0
      ? [`${unit}<ParameterDeclarations>`, ...declarations, `${unit}</ParameterDeclarations>`].join(eol)
      : `${unit}<ParameterDeclarations/>`,
  );

  // Variables the group uses; a catalog entry it references may use any the scenario declares (a catalog declares none).
  const variables = new Set([...groupText.matchAll(VARIABLE_REF)].map((match) => match[1]));
  const declaredVariables = child(root, 'VariableDeclarations');
  if (declaredVariables && /<CatalogReference\b/.test(groupText))
    for (const declaration of declaredVariables.children) {
      const name = attributeValue(declaration, 'name');
      if (name !== undefined) variables.add(name);
    }
  const variableDeclarations = [...variables].flatMap((name) => {
    const found = findNamed(documents, ['VariableDeclaration'], name);
    return found ? [found] : [];
  });
  variableDeclarations.sort((a, b) => documents.indexOf(a.document) - documents.indexOf(b.document) || a.element.start - b.element.start);
  if (variableDeclarations.length > 0)
    lines.push(
      [
        `${unit}<VariableDeclarations>`,
        ...variableDeclarations.map((found) => copied(found.document, found.element, unit, 2, eol)),
        `${unit}</VariableDeclarations>`,
      ].join(eol),
    );

  lines.push(catalogText, roadText);
  lines.push(entities.length > 0 ? [`${unit}<Entities>`, ...entities, `${unit}</Entities>`].join(eol) : `${unit}<Entities/>`);

  // Each Act and Story keeps the name it had around its groups, which their conditions may name.
  const u = (depth: number) => unit.repeat(depth);
  const stories = new Map<string, Map<string, PooledGroup[]>>();
  for (const group of groups) {
    const act = group.occurrences[0].group.element.parent;
    const actName = (act?.name === 'Act' && attributeValue(act, 'name')) || `${group.groupName}Act`;
    const story = act?.parent;
    const storyName = (story?.name === 'Story' && attributeValue(story, 'name')) || `${group.groupName}Story`;
    const acts = stories.get(storyName) ?? new Map<string, PooledGroup[]>();
    stories.set(storyName, acts);
    acts.set(actName, [...(acts.get(actName) ?? []), group]);
  }
  const storyboard = [`${u(1)}<Storyboard>`, `${u(2)}<Init>`, `${u(3)}<Actions/>`, `${u(2)}</Init>`];
  for (const [storyName, acts] of stories) {
    storyboard.push(`${u(2)}<Story name="${escapeAttributeValue(storyName)}">`);
    for (const [actName, members] of acts) {
      storyboard.push(`${u(3)}<Act name="${escapeAttributeValue(actName)}">`);
      for (const member of members) storyboard.push(`${u(4)}${member.groupText}`);
      storyboard.push(
        `${u(4)}<StartTrigger>`,
        `${u(5)}<ConditionGroup>`,
        `${u(6)}<Condition name="${escapeAttributeValue(members[0].groupName)}Start" delay="0" conditionEdge="none">`,
        `${u(7)}<ByValueCondition>`,
        `${u(8)}<SimulationTimeCondition value="0" rule="greaterThan"/>`,
        `${u(7)}</ByValueCondition>`,
        `${u(6)}</Condition>`,
        `${u(5)}</ConditionGroup>`,
        `${u(4)}</StartTrigger>`,
        `${u(3)}</Act>`,
      );
    }
    storyboard.push(`${u(2)}</Story>`);
  }
  storyboard.push(`${u(2)}<StopTrigger/>`, `${u(1)}</Storyboard>`, `</${root.name}>`);
  lines.push(storyboard.join(eol));
  const text = lines.join(eol) + eol;
  return applyEdits(text, await rebase(parseXml(text), path.dirname(representative.path), path.dirname(file)));
}

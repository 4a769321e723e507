import * as path from 'node:path';
import { reindent, TextEdit } from '../flatten/edits';
import { detectEol, indentationAt } from '../text';
import { RefactoringRefusal } from './refusal';
import { attributeValue, endTagStart, escapeAttributeValue, parseXml, selfAndDescendants, XmlDocument, XmlElement } from '../xml';

/** The catalog kind (its `CatalogLocations` child) of each element that can move into a catalog, and the parent it must stand in. */
const CATALOG_KINDS: Record<string, { kind: string; parent: string }> = {
  Vehicle: { kind: 'VehicleCatalog', parent: 'ScenarioObject' },
  Pedestrian: { kind: 'PedestrianCatalog', parent: 'ScenarioObject' },
  MiscObject: { kind: 'MiscObjectCatalog', parent: 'ScenarioObject' },
  Controller: { kind: 'ControllerCatalog', parent: 'ObjectController' },
  Maneuver: { kind: 'ManeuverCatalog', parent: 'ManeuverGroup' },
};

/** Whether *Extract to catalog* applies to an element: an entity's object or controller, or a group's Maneuver, with a name. */
export function catalogCandidate(element: XmlElement | undefined): element is XmlElement {
  const kind = element ? CATALOG_KINDS[element.name] : undefined;
  return kind !== undefined && element?.parent?.name === kind.parent && attributeValue(element, 'name') !== undefined;
}

/** A catalog file read by the caller. */
export interface CatalogFileText {
  path: string;
  text: string;
}

export interface ExtractCatalogRequest {
  /** Absolute path of the scenario. */
  file: string;
  document: XmlDocument;
  element: XmlElement;
  /** The catalog files (`.xosc` holding a `Catalog`) of a directory; none when it does not exist. */
  catalogsIn(directory: string): Promise<CatalogFileText[]>;
  exists(file: string): Promise<boolean>;
}

export interface ExtractedCatalog {
  catalogName: string;
  entryName: string;
  /** The catalog file: created with `text`, or edited by `edits` (offsets of its text); neither when an equal entry was there. */
  catalog: { path: string; create: boolean; text?: string; edits: TextEdit[] };
  /** The edits of the scenario: the element replaced by a CatalogReference, the location added. */
  edits: TextEdit[];
  /** Whether an entry already in the catalog is reused. */
  reused: boolean;
}

// Inside ${...} only $name is a parameter: a bare word there is not.
const PARAMETER_USE = /\$([A-Za-z_]\w*)/g;

function child(element: XmlElement | undefined, name: string): XmlElement | undefined {
  return element?.children.find((candidate) => candidate.name === name);
}

/** The parameters an element declares for itself (its own ParameterDeclarations). */
function ownParameters(element: XmlElement): Map<string, string> {
  const declared = new Map<string, string>();
  for (const declaration of child(element, 'ParameterDeclarations')?.children ?? []) {
    const name = attributeValue(declaration, 'name');
    if (name !== undefined) declared.set(name, attributeValue(declaration, 'value') ?? '');
  }
  return declared;
}

/** The ParameterDeclaration in scope at `element` for `name`: the nearest ancestor's. */
function declarationInScope(element: XmlElement, name: string): XmlElement | undefined {
  for (let current = element.parent; current; current = current.parent) {
    const found = child(current, 'ParameterDeclarations')?.children.find((declaration) => attributeValue(declaration, 'name') === name);
    if (found) return found;
  }
  return undefined;
}

/**
 * The parameters an entry's own declarations must take for it to equal `element`, or undefined when
 * it differs elsewhere: same elements, same attributes, equal values except where the entry writes
 * one of its own `$parameters`.
 */
function matchEntry(entry: XmlElement, element: XmlElement, entryName: string): Map<string, string> | undefined {
  const parameters = ownParameters(entry);
  const values = new Map<string, string>();
  const entryElements = selfAndDescendants(entry).filter((item) => !isWithinDeclarations(item, entry));
  const elements = selfAndDescendants(element).filter((item) => !isWithinDeclarations(item, element));
  if (entryElements.length !== elements.length) return undefined;
  for (let i = 0; i < elements.length; i++) {
    const [a, b] = [entryElements[i], elements[i]];
    if (a.name !== b.name || a.attributes.length !== b.attributes.length) return undefined;
    for (const attribute of a.attributes) {
      let value = attributeValue(b, attribute.name);
      if (i === 0 && attribute.name === 'name') value = entryName;
      if (value === undefined) return undefined;
      const parameter = /^\$([A-Za-z_]\w*)$/.exec(attribute.value)?.[1];
      if (parameter && parameters.has(parameter)) {
        const known = values.get(parameter);
        if (known !== undefined && known !== value) return undefined;
        values.set(parameter, value);
      } else if (attribute.value !== value) return undefined;
    }
  }
  return new Map([...values].filter(([name, value]) => parameters.get(name) !== value));
}

function isWithinDeclarations(item: XmlElement, top: XmlElement): boolean {
  for (let current: XmlElement | undefined = item; current && current !== top; current = current.parent)
    if (current.name === 'ParameterDeclarations' && current.parent === top) return true;
  return false;
}

/** The entries of a catalog file, and the text's Catalog element. */
function catalogOf(text: string): { document: XmlDocument; catalog: XmlElement } | undefined {
  const document = parseXml(text);
  const catalog = child(document.root, 'Catalog');
  return catalog ? { document, catalog } : undefined;
}

function lineStart(text: string, offset: number): number {
  return text.lastIndexOf('\n', offset - 1) + 1;
}

/** The indentation one level deeper than `element`'s, judged from its first child or the file. */
function childIndent(text: string, element: XmlElement, unit: string): string {
  const first = element.children[0];
  return first ? indentationAt(text, first.start) : indentationAt(text, element.start) + unit;
}

/**
 * *Extract to catalog*: moves an entity's Vehicle, Pedestrian, MiscObject or Controller, or a
 * Maneuver, into a catalog (the directory `CatalogLocations` names for its kind, else `Catalogs/`
 * beside the file; an existing catalog file there where its name is free, else a new `<Kind>.xosc`;
 * the name never changes, as esmini reads a controller's name as its type and conditions name maneuvers),
 * and leaves a CatalogReference.
 * An entry already there that equals it (up to its own parameters) is reused, with ParameterAssignments
 * for the values that differ from its defaults; a scenario parameter the element uses is passed in.
 * Throws with the reason when it cannot.
 */
export async function extractToCatalog(request: ExtractCatalogRequest): Promise<ExtractedCatalog> {
  const { file, document, element } = request;
  const text = document.text;
  const eol = detectEol(text);
  const root = document.root;
  if (!catalogCandidate(element) || !root)
    throw new RefactoringRefusal("only an entity's Vehicle, Pedestrian, MiscObject or Controller, or a Maneuver, can move into a catalog");
  const kind = CATALOG_KINDS[element.name].kind;
  const locations = child(root, 'CatalogLocations');
  if (!locations) throw new RefactoringRefusal('the scenario has no CatalogLocations');
  const unitMatch = /^([ \t]+)</m.exec(text);
  const unit = unitMatch ? unitMatch[1] : '  ';
  const location = child(locations, kind);
  const directoryPath = location ? attributeValue(child(location, 'Directory') ?? location, 'path') : undefined;
  if (location && directoryPath === undefined) throw new RefactoringRefusal(`the ${kind} location names no directory`);
  if (directoryPath && /[$]/.test(directoryPath)) throw new RefactoringRefusal(`the ${kind} directory is given by a parameter`);
  const directory = path.resolve(path.dirname(file), directoryPath ?? 'Catalogs');

  // Scenario parameters the element uses are declared in the entry and passed in by the reference.
  const own = ownParameters(element);
  const passed: { name: string; declaration: XmlElement }[] = [];
  for (const match of text.slice(element.start, element.end).matchAll(PARAMETER_USE)) {
    const name = match[1];
    if (own.has(name) || passed.some((entry) => entry.name === name)) continue;
    const declaration = declarationInScope(element, name);
    if (!declaration) throw new RefactoringRefusal(`parameter '${name}' is not declared`);
    if ((attributeValue(declaration, 'value') ?? '').includes('$'))
      throw new RefactoringRefusal(`parameter '${name}' has a value computed from others, which a catalog's default cannot hold`);
    passed.push({ name, declaration });
  }

  // A ParameterCondition or ParameterSetAction names a scenario parameter to test or set: inside an entry it would name the entry's own.
  for (const item of selfAndDescendants(element)) {
    const named = item.name === 'ParameterAssignment' ? undefined : attributeValue(item, 'parameterRef')?.replace(/^\$/, '');
    if (named !== undefined && !own.has(named))
      throw new RefactoringRefusal(`its ${item.name} names the scenario parameter '${named}', which a catalog entry cannot reach`);
  }

  const catalogs = (await request.catalogsIn(directory))
    .map((candidate) => ({ ...candidate, read: catalogOf(candidate.text) }))
    .filter(
      (candidate): candidate is CatalogFileText & { read: { document: XmlDocument; catalog: XmlElement } } => candidate.read !== undefined,
    );
  const name = attributeValue(element, 'name') as string;
  const entryName = name;
  const holdsKind = (candidate: (typeof catalogs)[number]) => candidate.read.catalog.children.some((entry) => entry.name === element.name);
  const ordered = [...catalogs.filter(holdsKind), ...catalogs.filter((candidate) => !holdsKind(candidate))];
  let chosen: (typeof catalogs)[number] | undefined;
  let assignments = new Map<string, string>();
  let reused = false;
  if (passed.length === 0) {
    for (const candidate of ordered) {
      const entry = candidate.read.catalog.children.find((item) => item.name === element.name && attributeValue(item, 'name') === name);
      const matched = entry && matchEntry(entry, element, name);
      if (matched) {
        [chosen, assignments, reused] = [candidate, matched, true];
        break;
      }
    }
  }
  // The name stays (esmini takes a controller's name for its type, conditions name maneuvers): a catalog where it is free, else a new one.
  // Files of one catalog name are one catalog: the name must be free in all of them.
  const holdsName = (catalogName: string | undefined) =>
    catalogs.some(
      (other) =>
        attributeValue(other.read.catalog, 'name') === catalogName &&
        other.read.catalog.children.some((entry) => attributeValue(entry, 'name') === name),
    );
  if (!reused) chosen = ordered.find((candidate) => !holdsName(attributeValue(candidate.read.catalog, 'name')));
  for (const { name: parameter } of passed) assignments.set(parameter, `$${parameter}`);
  const catalogNames = new Set(catalogs.map((candidate) => attributeValue(candidate.read.catalog, 'name')));
  let newCatalogName = kind;
  for (let n = 2; catalogNames.has(newCatalogName); n++) newCatalogName = `${kind}_${n}`;
  const catalogName = chosen ? (attributeValue(chosen.read.catalog, 'name') ?? kind) : newCatalogName;
  let catalog: ExtractedCatalog['catalog'];
  if (reused && chosen) catalog = { path: chosen.path, create: false, edits: [] };
  else {
    const entryText = (entryIndent: string, catalogEol: string) => {
      const edits: TextEdit[] = [];
      if (passed.length > 0) {
        const declarations = child(element, 'ParameterDeclarations');
        const inner = childIndent(text, element, unit);
        // One level as the element itself indents its children, so the entry reads as written.
        const outer = indentationAt(text, element.start);
        const step = inner.startsWith(outer) && inner.length > outer.length ? inner.slice(outer.length) : unit;
        const lines = passed.map(({ declaration }) => text.slice(declaration.start, declaration.end));
        if (declarations && !declarations.selfClosing) {
          const at = lineStart(text, endTagStart(text, declarations));
          edits.push({ start: at, end: at, text: lines.map((line) => `${inner}${step}${line}${eol}`).join('') });
        } else if (declarations) {
          edits.push({
            start: declarations.start,
            end: declarations.end,
            text: [`<ParameterDeclarations>`, ...lines.map((line) => `${inner}${step}${line}`), `${inner}</ParameterDeclarations>`].join(
              eol,
            ),
          });
        } else if (element.selfClosing) {
          throw new RefactoringRefusal(`the ${element.name} is empty`);
        } else {
          const at = element.children[0] ? lineStart(text, element.children[0].start) : element.startTagEnd;
          edits.push({
            start: at,
            end: at,
            text: [
              `${inner}<ParameterDeclarations>`,
              ...lines.map((line) => `${inner}${step}${line}`),
              `${inner}</ParameterDeclarations>`,
              '',
            ].join(eol),
          });
        }
      }
      edits.sort((a, b) => a.start - b.start);
      let out = '';
      let position = element.start;
      for (const edit of edits) {
        out += text.slice(position, edit.start) + edit.text;
        position = edit.end;
      }
      out += text.slice(position, element.end);
      return reindent(out, indentationAt(text, element.start), entryIndent, catalogEol);
    };
    if (chosen) {
      const catalogText = chosen.text;
      const catalogEol = detectEol(catalogText);
      const close = endTagStart(catalogText, chosen.read.catalog);
      const catalogUnit = /^([ \t]+)</m.exec(catalogText)?.[1] ?? unit;
      if (chosen.read.catalog.selfClosing) throw new RefactoringRefusal(`the catalog ${chosen.path} is written as an empty element`);
      const entryIndent = childIndent(catalogText, chosen.read.catalog, catalogUnit);
      const at = lineStart(catalogText, close);
      const onOwnLine = /^[ \t]*$/.test(catalogText.slice(at, close));
      const insertAt = onOwnLine ? at : close;
      const entry = `${entryIndent}${entryText(entryIndent, catalogEol)}${catalogEol}`;
      catalog = {
        path: chosen.path,
        create: false,
        edits: [{ start: insertAt, end: insertAt, text: onOwnLine ? entry : catalogEol + entry }],
      };
    } else {
      let target = path.join(directory, `${catalogName}.xosc`);
      for (let n = 2; await request.exists(target); n++) target = path.join(directory, `${catalogName}_${n}.xosc`);
      const header = child(root, 'FileHeader');
      const attributes = [
        ['revMajor', (header && attributeValue(header, 'revMajor')) ?? '1'],
        ['revMinor', (header && attributeValue(header, 'revMinor')) ?? '0'],
        ['date', (header && attributeValue(header, 'date')) ?? '2020-01-01T00:00:00'],
        ['description', `${kind}, extracted from ${path.basename(file)} by modular2simple`],
        ['author', (header && attributeValue(header, 'author')) ?? 'modular2simple'],
      ];
      const catalogText = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<OpenSCENARIO>',
        `${unit}<FileHeader ${attributes.map(([key, value]) => `${key}="${escapeAttributeValue(value)}"`).join(' ')}/>`,
        `${unit}<Catalog name="${escapeAttributeValue(catalogName)}">`,
        `${unit}${unit}${entryText(unit + unit, eol)}`,
        `${unit}</Catalog>`,
        '</OpenSCENARIO>',
        '',
      ].join(eol);
      catalog = { path: target, create: true, text: catalogText, edits: [] };
    }
  }

  // The scenario: the reference in place of the element, the location when it had none.
  const indent = indentationAt(text, element.start);
  const q = (value: string) => `"${escapeAttributeValue(value)}"`;
  const referenceLines =
    assignments.size === 0
      ? [`<CatalogReference catalogName=${q(catalogName)} entryName=${q(entryName)}/>`]
      : [
          `<CatalogReference catalogName=${q(catalogName)} entryName=${q(entryName)}>`,
          `${indent}${unit}<ParameterAssignments>`,
          ...[...assignments].map(
            ([parameter, value]) => `${indent}${unit}${unit}<ParameterAssignment parameterRef=${q(parameter)} value=${q(value)}/>`,
          ),
          `${indent}${unit}</ParameterAssignments>`,
          `${indent}</CatalogReference>`,
        ];
  const reference = referenceLines.join(eol);
  const edits: TextEdit[] = [];
  if (element.name === 'Maneuver') {
    // A group lists its CatalogReferences before its Maneuvers: the element's line goes, the reference follows the last of them (or the Actors).
    const group = element.parent as XmlElement;
    const before = [...group.children].reverse().find((sibling) => sibling.name === 'CatalogReference' || sibling.name === 'Actors');
    const removeFrom = lineStart(text, element.start);
    const onOwnLine = /^[ \t]*$/.test(text.slice(removeFrom, element.start));
    const lineEnd = text.startsWith(eol, element.end) ? element.end + eol.length : element.end;
    if (before && before.end <= element.start) {
      edits.push({ start: before.end, end: before.end, text: `${eol}${indent}${reference}` });
      edits.push(onOwnLine ? { start: removeFrom, end: lineEnd, text: '' } : { start: element.start, end: element.end, text: '' });
    } else edits.push({ start: element.start, end: element.end, text: reference });
  } else edits.push({ start: element.start, end: element.end, text: reference });
  if (!location) {
    const relative = path.relative(path.dirname(file), directory).split(path.sep).join('/') || '.';
    if (locations.selfClosing) {
      const outer = indentationAt(text, locations.start);
      const lines = [
        `<CatalogLocations>`,
        `${outer}${unit}<${kind}>`,
        `${outer}${unit}${unit}<Directory path=${q(relative)}/>`,
        `${outer}${unit}</${kind}>`,
        `${outer}</CatalogLocations>`,
      ];
      edits.push({ start: locations.start, end: locations.end, text: lines.join(eol) });
    } else {
      const inner = childIndent(text, locations, unit);
      const close = endTagStart(text, locations);
      const at = lineStart(text, close);
      const lines = [`${inner}<${kind}>`, `${inner}${unit}<Directory path=${q(relative)}/>`, `${inner}</${kind}>`];
      // A closing tag that shares its line with other text gets the location before it, on lines of their own.
      if (/^[ \t]*$/.test(text.slice(at, close))) edits.push({ start: at, end: at, text: [...lines, ''].join(eol) });
      else edits.push({ start: close, end: close, text: [eol + lines.join(eol), indentationAt(text, locations.start)].join(eol) });
    }
  }
  return { catalogName, entryName, catalog, edits, reused };
}

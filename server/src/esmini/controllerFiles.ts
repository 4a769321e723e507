import * as path from 'node:path';
import { applyEdits, TextEdit } from '../core/flatten/edits';
import type { FlatSource } from '../core/flatten/types';
import { scenarioFolderOf } from '../core/semantics/roadFiles';
import { diskRef, SourceRef } from '../core/sources';
import type { CatalogLoader, CatalogReferenceResolution } from '../core/semantics/catalogs';
import { Evaluator, semanticModelOf } from '../core/semantics/model';
import { attribute, descendants, escapeAttributeValue, parseXml, XmlAttribute, XmlElement } from '../core/xml';

/** Where a run's controller Files are looked up from: the scenario's own folder, and its catalog references resolved. */
export interface ControllerFilesFrom {
  scenarioFolder: string;
  references: readonly CatalogReferenceResolution[];
}

/**
 * Where a run of `main`'s flattening looks its controller Files up from: the main's folder (its package's, for a packaged
 * one), with the catalog references of the main and of every file it imports groups from, whose CatalogReferences the
 * flattened text keeps. Run in esmini and the debugger both hand esmini a flattening, so both take this one.
 */
export function controllerFilesOfFlattening(main: SourceRef, source: FlatSource): ControllerFilesFrom {
  const references: CatalogReferenceResolution[] = [];
  const seen = new Set<FlatSource>();
  const gather = (each: FlatSource) => {
    if (seen.has(each)) return;
    seen.add(each);
    references.push(...(each.semantics?.catalogs.references ?? []));
    for (const link of each.links) if (link.source) gather(link.source);
  };
  gather(source);
  return { scenarioFolder: scenarioFolderOf(main), references };
}

/**
 * A plain scenario's text (a batch's concrete scenario) read as a file in `scenarioFolder`, with its catalog references
 * resolved there as the check resolves them: what `withControllerFilesFrom` needs to hand its controller Files.
 */
export async function controllerFilesFrom(text: string, scenarioFolder: string, catalogs: CatalogLoader): Promise<ControllerFilesFrom> {
  const model = semanticModelOf(parseXml(text));
  const resolution = await catalogs.resolve(diskRef(path.join(scenarioFolder, 'scenario.xosc')), model);
  return { scenarioFolder, references: resolution.references };
}

/**
 * esmini 3.6 looks a controller's `Properties/File` up as written, from its working folder, then from the folder of the
 * scenario it runs, for a catalog entry's controller too (ScenarioReader.cpp parseOSCObjectController). A run's scenario
 * is a copy in a private folder, its working folder: a relative path the flattening left as written (one that names a
 * `$parameter`, or one a catalog entry holds) reaches from there nothing that the scenario itself reaches (SPEC 11.6).
 * `withControllerFilesFrom` gives such a path esmini as the absolute file it names from `scenarioFolder`, in the run's
 * copy only: an inline controller's File takes that path; a catalog entry's File named by a parameter gets it through
 * the CatalogReference's ParameterAssignment. A path that reaches a file from the run folder, or none from the scenario's
 * folder, is left as written (esmini then says what it tried).
 */
export function withControllerFilesFrom(
  text: string,
  scenarioFolder: string,
  runFolder: string,
  references: readonly CatalogReferenceResolution[],
  exists: (file: string) => boolean,
): string {
  /** The absolute file a path esmini misses from the run folder names from the scenario's folder; undefined when none. */
  const reached = (written: string | undefined, handable: boolean): string | undefined => {
    if (!handable || !written || path.isAbsolute(written)) return undefined;
    const original = path.resolve(scenarioFolder, written);
    return !exists(path.resolve(runFolder, written)) && exists(original) ? original : undefined;
  };
  return applyEdits(text, controllerFileEdits(text, references, reached));
}

/**
 * The files on disk that the controller Files of a concrete scenario name from `from.scenarioFolder`, inline or in a
 * catalog entry it references, written as they stand or through a `$parameter`: what a worker on another machine needs
 * beside the scenario to run it as a local batch does.
 */
export function controllerFilesNamed(text: string, from: ControllerFilesFrom, exists: (file: string) => boolean): string[] {
  const files = new Set<string>();
  controllerFileEdits(text, from.references, (written) => {
    const file = written && !path.isAbsolute(written) ? path.resolve(from.scenarioFolder, written) : undefined;
    if (file && exists(file)) files.add(file);
    return undefined;
  });
  return [...files];
}

/**
 * Each controller File of the text shown to `handed` (the path it names, evaluated, and whether the run can hand it: one
 * named through a `$parameter`, or any a catalog entry holds, which the flattening leaves as written), and the edits that
 * write the absolute file `handed` returns.
 */
function controllerFileEdits(
  text: string,
  references: readonly CatalogReferenceResolution[],
  handed: (written: string | undefined, parameterized: boolean) => string | undefined,
): TextEdit[] {
  const document = parseXml(text);
  const root = document.root;
  if (!root) return [];
  const evaluator = new Evaluator(semanticModelOf(document));
  const edits: TextEdit[] = [];
  for (const holder of [root, ...descendants(root)]) {
    if (holder.name !== 'ObjectController' && holder.name !== 'AssignControllerAction') continue;
    for (const child of holder.children) {
      if (child.name === 'Controller') {
        const filepath = fileOf(child);
        if (!filepath) continue;
        const parameterized = filepath.attribute.value.trim().startsWith('$');
        const file = handed(
          parameterized ? evaluator.textOf(filepath.element, filepath.attribute) : filepath.attribute.value.trim(),
          parameterized,
        );
        if (parameterized && file)
          edits.push({
            start: filepath.attribute.valueStart,
            end: filepath.attribute.valueEnd,
            text: escapeAttributeValue(file, filepath.attribute.quote),
          });
      } else if (child.name === 'CatalogReference') {
        const edit = catalogReferenceEdit(child, evaluator, references, handed);
        if (edit) edits.push(edit);
      }
    }
  }
  return edits;
}

/** A Controller's `Properties/File` element and its filepath attribute. */
function fileOf(
  controller: XmlElement | undefined,
): { element: XmlElement; attribute: NonNullable<ReturnType<typeof attribute>> } | undefined {
  const properties = controller?.children.find((child) => child.name === 'Properties');
  const element = properties?.children.find((child) => child.name === 'File');
  const filepath = element ? attribute(element, 'filepath') : undefined;
  return element && filepath ? { element, attribute: filepath } : undefined;
}

/**
 * The edit that assigns a catalog controller's File parameter the absolute file it names from the scenario's folder: the
 * reference's own ParameterAssignment of it rewritten, else one added; undefined when the File needs none.
 */
function catalogReferenceEdit(
  reference: XmlElement,
  evaluator: Evaluator,
  references: readonly CatalogReferenceResolution[],
  handed: (written: string | undefined, parameterized: boolean) => string | undefined,
): TextEdit | undefined {
  const catalogName = evaluator.textOf(reference, attribute(reference, 'catalogName'))?.trim();
  const entryName = evaluator.textOf(reference, attribute(reference, 'entryName'))?.trim();
  const found = references.find((each) => each.catalogName === catalogName && each.entryName === entryName)?.entry;
  const entry = found?.element;
  const filepath = entry?.name === 'Controller' ? fileOf(entry) : undefined;
  const parameter = filepath ? /^\$([A-Za-z_][\w.]*)$/.exec(filepath.attribute.value.trim())?.[1] : undefined;
  if (!entry || !filepath) return undefined;
  if (parameter === undefined) {
    const literal = filepath.attribute.value.trim();
    const file = handed(literal.includes('$') ? undefined : literal, true);
    return file && found
      ? inlinedEntryEdit(reference, found.file.model.document.text, entry, filepath.attribute, file, evaluator)
      : undefined;
  }
  const assignments = reference.children.find((child) => child.name === 'ParameterAssignments');
  const assignment = assignments?.children.find(
    (child) => child.name === 'ParameterAssignment' && attribute(child, 'parameterRef')?.value === parameter,
  );
  const assigned = assignment ? attribute(assignment, 'value') : undefined;
  const declarations = entry.children.find((child) => child.name === 'ParameterDeclarations');
  const declaration = declarations?.children.find(
    (child) => child.name === 'ParameterDeclaration' && attribute(child, 'name')?.value === parameter,
  );
  const fallback = declaration ? attribute(declaration, 'value')?.value : undefined;
  const file = handed(assignment ? evaluator.textOf(assignment, assigned) : fallback?.startsWith('$') ? undefined : fallback, true);
  if (!file) return undefined;
  if (assigned) return { start: assigned.valueStart, end: assigned.valueEnd, text: escapeAttributeValue(file, assigned.quote) };
  const added = `<ParameterAssignment parameterRef="${escapeAttributeValue(parameter, '"')}" value="${escapeAttributeValue(file, '"')}"/>`;
  if (assignments && !assignments.selfClosing) {
    const at = assignments.startTagEnd;
    return { start: at, end: at, text: added };
  }
  if (assignments) return { start: assignments.start, end: assignments.end, text: `<ParameterAssignments>${added}</ParameterAssignments>` };
  if (reference.selfClosing) {
    // `<CatalogReference .../>`: opened, given the assignment, and closed.
    const close = reference.end - 2;
    return { start: close, end: reference.end, text: `><ParameterAssignments>${added}</ParameterAssignments></CatalogReference>` };
  }
  return { start: reference.startTagEnd, end: reference.startTagEnd, text: `<ParameterAssignments>${added}</ParameterAssignments>` };
}

/**
 * The edit that replaces a CatalogReference with its controller entry written inline, its File the absolute `file`: a
 * path written in the entry cannot be assigned through the reference. The entry's declarations take the values the
 * reference assigns them (evaluated), as esmini would give them; on one line, so that the copy's lines stay the source's.
 */
function inlinedEntryEdit(
  reference: XmlElement,
  catalogText: string,
  entry: XmlElement,
  filepath: XmlAttribute,
  file: string,
  evaluator: Evaluator,
): TextEdit {
  const assignments = reference.children.find((child) => child.name === 'ParameterAssignments');
  const assigned = new Map<string, string>();
  for (const assignment of assignments?.children ?? []) {
    const name = attribute(assignment, 'parameterRef')?.value.replace(/^\$/, '');
    const value = evaluator.textOf(assignment, attribute(assignment, 'value'));
    if (assignment.name === 'ParameterAssignment' && name !== undefined && value !== undefined) assigned.set(name, value);
  }
  const edits: TextEdit[] = [{ start: filepath.valueStart, end: filepath.valueEnd, text: escapeAttributeValue(file, filepath.quote) }];
  const declarations = entry.children.find((child) => child.name === 'ParameterDeclarations');
  for (const declaration of declarations?.children ?? []) {
    const name = attribute(declaration, 'name')?.value;
    const value = attribute(declaration, 'value');
    const given = name === undefined ? undefined : assigned.get(name);
    if (declaration.name === 'ParameterDeclaration' && value && given !== undefined)
      edits.push({ start: value.valueStart, end: value.valueEnd, text: escapeAttributeValue(given, value.quote) });
  }
  const text = applyEdits(catalogText, edits, entry.start, entry.end);
  // A line break between tags or inside a value (where XML reads it as a space) is a space here.
  return { start: reference.start, end: reference.end, text: text.replace(/\r\n?|\n/g, ' ') };
}

/**
 * esmini's "Failed to localize controller file F, also tried ..." with what it missed where the user may have meant it: F
 * beside the catalog of an entry the scenario uses whose File names F. esmini never looks there (only its working folder and
 * the scenario's), so the message says so, and to write the path from the scenario's folder.
 */
export function withCatalogFolderNote(
  text: string,
  references: readonly CatalogReferenceResolution[],
  exists: (file: string) => boolean,
): string {
  const missed = /^Failed to localize controller file (.+?), also tried /.exec(text)?.[1];
  if (missed === undefined || path.isAbsolute(missed)) return text;
  const beside = new Set<string>();
  for (const { entry } of references) {
    if (entry?.element.name !== 'Controller' || entry.file.ref.entries.length > 0) continue;
    if (fileOf(entry.element)?.attribute.value.trim() !== missed) continue;
    const file = path.resolve(path.dirname(entry.file.ref.disk), missed);
    if (exists(file)) beside.add(file);
  }
  return beside.size === 0
    ? text
    : `${text} [${[...beside].join(', ')} exists beside the catalog: esmini looks a catalog entry's controller File up from its working folder and from the scenario's folder, not from the catalog's; write the path as it stands from the scenario's folder]`;
}

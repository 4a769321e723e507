import * as fs from 'node:fs';
import * as path from 'node:path';
import { CompletionItem, CompletionItemKind, InsertTextFormat, Range as LspRange } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { FlatSource } from '../core/flatten';
import { keyMatches, OverridableAttribute, overridableAttributes } from '../core/keys';
import { findGroup, ManeuverGroupInfo, PARAMETER_ATTRIBUTES } from '../core/model';
import { displayRef, LIBRARY_PREFIX, SourceRef } from '../core/sources';
import { keyChoices, overridablePlace, sourceForFileName } from '../analysis';
import { ancestor, elementsBetween, lastElementBefore, ValueContext } from '../core/cursor';
import { indexFor } from '../core/schema/query';
import { attribute, elementAt, XmlAttribute, XmlDocument, XmlElement } from '../core/xml';
import { completionTargetAt, currentDocument } from '../target';
import { Workspace } from '../workspace';
import { scenarioSkeletonSnippet, schemaCompletion } from './schemaCompletion';
import { catalogCompletion } from './catalogs';
import { attributeTypeAt, parameterCompletion } from './parameters';
import { distributionCompletion } from './distributions';

const MAX_SNIPPETS = 200;

/** A scenario name that a `scenarioFileName` written in `from` can use, and where it was found. */
export interface FileNameCandidate {
  name: string;
  where: string;
}

function listFolder(directory: string, exclude: string | undefined): string[] {
  let entries: fs.Dirent[];
  try {
    entries = fs.readdirSync(directory, { withFileTypes: true });
  } catch {
    return [];
  }
  const names: string[] = [];
  for (const entry of entries) {
    const full = path.join(directory, entry.name);
    if (entry.isFile() && /\.(xosc|mosc)$/i.test(entry.name) && full !== exclude) names.push(entry.name);
    else if (entry.isDirectory() && fs.existsSync(path.join(full, 'main.xosc')) && full !== (exclude && path.dirname(exclude)))
      names.push(`${entry.name}.mosc`);
  }
  return names.sort();
}

/** Names that resolve from `from`, in the store's lookup order (SPEC 3): its package or folder, SCENARIO_PATH, parent folders. */
export async function fileNameCandidates(workspace: Workspace, from: SourceRef): Promise<FileNameCandidate[]> {
  const seen = new Map<string, FileNameCandidate>();
  const add = (name: string, where: string) => {
    if (!seen.has(name)) seen.set(name, { name, where });
  };
  let packageListed = false;
  for (const place of workspace.store.lookupPlaces(from)) {
    if (place.packageRef) {
      // The whole package is offered once, under its entry names, for its first place.
      if (packageListed) continue;
      packageListed = true;
      const packageRef = place.packageRef;
      const self = from.entries[from.entries.length - 1];
      const contents = await workspace.store.readPackage(packageRef).catch(() => undefined);
      for (const entry of contents ? [...contents.entries.keys()].sort() : []) {
        if (entry === self) continue;
        if (/\.(xosc|mosc)$/i.test(entry) && !entry.endsWith('/main.xosc')) add(entry, displayRef(packageRef, workspace.folders[0]));
        else if (entry.endsWith('/main.xosc'))
          add(`${entry.slice(0, -'/main.xosc'.length)}.mosc`, displayRef(packageRef, workspace.folders[0]));
      }
      continue;
    }
    const where =
      place.via === 'folder'
        ? 'this folder'
        : place.via === 'scenarioPath'
          ? `${place.directory} (scenario path)`
          : `${place.directory} (parent folder)`;
    for (const name of listFolder(place.directory, from.disk)) add(name, where);
  }
  // The library modules last, each as `library:NAME` (SPEC 3 as docs/library.md extends it), the first library's winning.
  for (const library of workspace.store.libraries)
    for (const name of listFolder(library.folder, from.disk))
      if (name.toLowerCase().endsWith('.xosc')) add(`${LIBRARY_PREFIX}${name.slice(0, -'.xosc'.length)}`, `${library.label} library`);
  return [...seen.values()];
}

function replaceRange(document: TextDocument, start: number, end: number): LspRange {
  return { start: document.positionAt(start), end: document.positionAt(end) };
}

/** The enclosing ScenarioReference's source: the last one that starts before `before`. */
async function referencedSource(
  workspace: Workspace,
  ref: SourceRef,
  document: XmlDocument,
  before: number,
): Promise<{ source: FlatSource | undefined; fileName: string }> {
  const reference = lastElementBefore(document, 'ScenarioReference', before);
  if (!reference) return { source: undefined, fileName: '' };
  const fileName = attribute(reference, 'scenarioFileName')?.value ?? '';
  return { source: await sourceForFileName(workspace, ref, fileName), fileName };
}

function coveredBy(keys: string[], target: OverridableAttribute): boolean {
  return keys.some((key) => keyMatches(key, target));
}

/** The group a ParameterReference tag (starting at `tagStart`) overrides, read from the text before it. */
async function groupBefore(workspace: Workspace, ref: SourceRef, document: XmlDocument, tagStart: number) {
  const groupReference = lastElementBefore(document, 'ManeuverGroupReference', tagStart);
  if (!groupReference) return undefined;
  const { source } = await referencedSource(workspace, ref, document, groupReference.start);
  const group = source?.model ? findGroup(source.model, attribute(groupReference, 'maneuverGroupName')?.value ?? '') : undefined;
  if (!source?.model || !group) return undefined;
  return { source, group, groupReference, targets: overridableAttributes(source.model, group) };
}

/** The default values of the attributes that the key written in the same tag reaches. */
async function valueItems(
  workspace: Workspace,
  ref: SourceRef,
  document: TextDocument,
  parsed: XmlDocument,
  context: ValueContext,
): Promise<CompletionItem[]> {
  const key = context.siblings.find((sibling) => sibling.name === 'key')?.value.trim();
  const found = key ? await groupBefore(workspace, ref, parsed, context.tagStart) : undefined;
  if (!found || !key) return [];
  const range = replaceRange(document, context.valueStart, context.valueEnd);
  const defaults = new Map<string, string>();
  for (const target of found.targets) {
    if (target.defaultValue !== undefined && keyMatches(key, target) && !defaults.has(target.defaultValue))
      defaults.set(target.defaultValue, `default of ${target.element.name}.${target.attributeName}`);
  }
  return [...defaults].map(([value, detail]) => ({
    label: value,
    kind: CompletionItemKind.Value,
    detail,
    textEdit: { range, newText: value },
  }));
}

async function keyItems(
  workspace: Workspace,
  ref: SourceRef,
  document: TextDocument,
  parsed: XmlDocument,
  context: ValueContext,
): Promise<CompletionItem[]> {
  const text = document.getText();
  const found = await groupBefore(workspace, ref, parsed, context.tagStart);
  if (!found) return [];
  const { source, group, groupReference, targets } = found;
  const blockEnd = [
    text.indexOf('</ManeuverGroupReference', context.valueEnd),
    text.indexOf('<ManeuverGroupReference', context.valueEnd),
    text.length,
  ]
    .filter((index) => index >= 0)
    .reduce((a, b) => Math.min(a, b));
  const given = elementsBetween(parsed, 'ParameterReference', groupReference.start, blockEnd)
    .map((element) => attribute(element, 'key'))
    .filter((key): key is XmlAttribute => key !== undefined && key.valueStart !== context.valueStart)
    .map((key) => key.value.trim());
  const range = replaceRange(document, context.valueStart, context.valueEnd);
  const items: CompletionItem[] = [];
  const item = (form: string, chosen: OverridableAttribute[], note: string, sortText: string): CompletionItem => {
    const [first] = chosen;
    const declared = overridablePlace(source, first);
    const where = declared ? `${displayRef(declared.ref, workspace.folders[0])}:${declared.range.start.line + 1}` : '';
    const defaults = [...new Set(chosen.map((target) => target.defaultValue ?? '(none)'))].join(' / ');
    return {
      label: form,
      kind: CompletionItemKind.Property,
      detail: `default ${defaults}${where ? ` — ${where}` : ''}${note}`,
      documentation: `Overrides \`${first.attributeName}\` of <${first.element.name}> (${first.path.join(' › ')}) in group ${group.name}.`,
      sortText,
      filterText: form,
      textEdit: { range, newText: form },
    };
  };
  // One row per attribute (or per set of attributes only a positioned key tells apart), in its shortest unambiguous key.
  keyChoices(targets).forEach((choice, index) => {
    const [form] = choice.forms;
    const order = String(index).padStart(5, '0');
    if (form !== undefined && !choice.targets.some((target) => coveredBy(given, target)))
      items.push(item(form, choice.targets, choice.targets.length > 1 ? ` (sets ${choice.targets.length} attributes)` : '', order));
    // Then each of them alone, by its position among its namesakes.
    choice.positioned.forEach(({ target, form: positioned }, member) => {
      if (coveredBy(given, target)) return;
      const note = ` (this one alone of the ${choice.targets.length} the plain key sets)`;
      items.push(item(positioned, [target], note, `${order}.${String(member + 1).padStart(3, '0')}`));
    });
  });
  return items;
}

function parameterAttributeItems(document: TextDocument, context: ValueContext): CompletionItem[] {
  const value = document.getText().slice(context.valueStart, context.valueEnd);
  const cursor = context.prefix.length;
  // The comma-separated segment under the cursor is replaced; names in the other segments are left out.
  const listed = new Set<string>();
  let segmentStart = 0;
  let current = { start: 0, end: value.length };
  for (const segment of value.split(',')) {
    const segmentEnd = segmentStart + segment.length;
    if (cursor >= segmentStart && cursor <= segmentEnd) {
      const leading = segment.length - segment.trimStart().length;
      const trailing = segment.length - segment.trimEnd().length;
      current = { start: segmentStart + leading, end: Math.max(segmentStart + leading, segmentEnd - trailing) };
    } else if (segment.trim()) {
      listed.add(segment.trim());
    }
    segmentStart = segmentEnd + 1;
  }
  const range = replaceRange(document, context.valueStart + current.start, context.valueStart + current.end);
  return context.siblings
    .filter((sibling) => sibling.name !== PARAMETER_ATTRIBUTES && !listed.has(sibling.name))
    .map((sibling) => ({
      label: sibling.name,
      kind: CompletionItemKind.Field,
      detail: `default ${sibling.value}`,
      textEdit: { range, newText: sibling.name },
    }));
}

/**
 * What the ManeuverGroup a ScenarioReference goes into already says: its actor, whom the imported group's
 * actor-valued keys should name (flattening gives the copy's Actors that entity, SPEC 4 step 2, but a key
 * left at its default still names the simple scenario's actor), and a name for it where its own is
 * taken in its Act (or empty): flattening names the copies `OUTER.INNER`, so two outer groups of one
 * name in an Act give copies of one name.
 */
export interface OuterGroupFacts {
  actor: string | undefined;
  rename: { range: LspRange; taken: string; name: string } | undefined;
}

function outerGroupFacts(document: TextDocument, group: XmlElement | undefined, importedName: string): OuterGroupFacts {
  const actors = group?.children.find((child) => child.name === 'Actors');
  const actor = actors?.children.find((child) => child.name === 'EntityRef');
  const actorName = actor ? attribute(actor, 'entityRef')?.value.trim() || undefined : undefined;
  const nameAttribute = group ? attribute(group, 'name') : undefined;
  const act = group?.parent?.name === 'Act' ? group.parent : undefined;
  if (!group || !nameAttribute || !act) return { actor: actorName, rename: undefined };
  const written = nameAttribute.value.trim();
  const others = new Set(
    act.children
      .filter((child) => child.name === 'ManeuverGroup' && child !== group)
      .map((child) => attribute(child, 'name')?.value.trim() ?? ''),
  );
  if (written !== '' && !others.has(written)) return { actor: actorName, rename: undefined };
  const base = (written || importedName.split('.').pop() || 'Group').replace(/\d+$/, '') || 'Group';
  let name = written === '' && !others.has(base) ? base : '';
  for (let counter = 2; name === ''; counter++) if (!others.has(`${base}${counter}`)) name = `${base}${counter}`;
  const range = replaceRange(document, nameAttribute.valueStart, nameAttribute.valueEnd);
  return { actor: actorName, rename: { range, taken: written, name } };
}

/** The entity the group's Actors names in its own file: the value of its actor-valued keys' defaults. */
function ownActor(group: ManeuverGroupInfo): string | undefined {
  return (group.actor && attribute(group.actor, 'entityRef')?.value.trim()) || undefined;
}

/**
 * A whole ScenarioReference block for one group of a file, every key set to its default (tab stops on
 * values), but a key whose default is the group's own actor, which names `actor` (the outer group's).
 */
export function referenceSnippet(
  fileName: string,
  groupName: string,
  targets: OverridableAttribute[],
  indent: string,
  actors?: { own: string | undefined; outer: string | undefined },
): string {
  const escape = (value: string) => value.replace(/[$}\\]/g, (char) => `\\${char}`);
  const lines = [
    `<ScenarioReference scenarioFileName="${escape(fileName)}">`,
    `${indent}<ManeuverGroupReference maneuverGroupName="${escape(groupName)}">`,
  ];
  keyChoices(targets).forEach((choice, index) => {
    const defaultValue = choice.targets[0].defaultValue;
    if (defaultValue === undefined || choice.forms.length === 0) return;
    const value = actors?.own && actors.outer && isActorValued(choice.targets, actors.own) ? actors.outer : defaultValue;
    lines.push(`${indent}${indent}<ParameterReference key="${escape(choice.forms[0])}" value="\${${index + 1}:${escape(value)}}"/>`);
  });
  lines.push(`${indent}</ManeuverGroupReference>`, '</ScenarioReference>$0');
  return lines.join('\n');
}

/** Keys that name the group's own actor: an entity reference whose default is that entity. */
function isActorValued(targets: OverridableAttribute[], ownActor: string): boolean {
  return targets.every((target) => ENTITY_REFERENCE_ATTRIBUTES.has(target.attributeName) && target.defaultValue?.trim() === ownActor);
}

/** Attributes that name an entity (the ones a key of an imported group sets to an actor). */
const ENTITY_REFERENCE_ATTRIBUTES: ReadonlySet<string> = new Set(['entityRef', 'masterEntityRef']);

/**
 * ScenarioReference snippets for each group of each file a name resolves to. Simple scenarios (files
 * without references of their own, whose groups list attributes to override) come first, then the
 * other files in lookup order. Inside a group with an actor, keys that name the imported group's own
 * actor name that actor; where the group's name is taken in its Act, the item renames it.
 */
async function snippetItems(
  workspace: Workspace,
  ref: SourceRef,
  document: TextDocument,
  outerGroup: XmlElement | undefined,
  start: number,
  offset: number,
): Promise<CompletionItem[]> {
  const range = replaceRange(document, start, offset);
  const indent = /^( +|\t)/m.exec(document.getText().slice(0, 4000))?.[1] ?? '    ';
  const ranked: { rank: number; item: CompletionItem }[] = [];
  for (const [fileIndex, candidate] of (await fileNameCandidates(workspace, ref)).entries()) {
    if (ranked.length >= MAX_SNIPPETS) break;
    const source = await sourceForFileName(workspace, ref, candidate.name);
    if (!source?.model) continue;
    const simple = source.links.length === 0 && source.model.declarations.length > 0;
    // The user's own files first, the library's modules after them.
    const kind = candidate.name.startsWith(LIBRARY_PREFIX) ? 2 : simple ? 0 : 1;
    for (const group of source.model.groups) {
      if (ranked.length >= MAX_SNIPPETS) break;
      const targets = overridableAttributes(source.model, group);
      const outer = outerGroupFacts(document, outerGroup, group.name);
      const own = ownActor(group);
      const renamed = outer.rename
        ? `; renames this ManeuverGroup ${outer.rename.name} (${outer.rename.taken ? `${outer.rename.taken} is taken in its Act` : 'it has no name'})`
        : '';
      const actorNote = outer.actor && own && outer.actor !== own ? `; keys naming its actor ${own} name ${outer.actor}` : '';
      ranked.push({
        rank: kind * 1_000_000 + fileIndex * 1000 + ranked.length,
        item: {
          label: `ScenarioReference ${candidate.name} ${group.name}`,
          kind: CompletionItemKind.Snippet,
          detail: `${targets.length} keys with their defaults${actorNote}${renamed}`,
          filterText: `<ScenarioReference ${candidate.name} ${group.name}`,
          insertTextFormat: InsertTextFormat.Snippet,
          textEdit: { range, newText: referenceSnippet(candidate.name, group.name, targets, indent, { own, outer: outer.actor }) },
          ...(outer.rename ? { additionalTextEdits: [{ range: outer.rename.range, newText: outer.rename.name }] } : {}),
        },
      });
    }
  }
  ranked.sort((a, b) => a.rank - b.rank);
  return ranked.map(({ item }, index) => ({ ...item, sortText: `z${String(index).padStart(4, '0')}` }));
}

/** Elements of the modular syntax in a main file: `parameterAttributes` means nothing on them. */
const REFERENCE_ELEMENTS = new Set(['ScenarioReference', 'ManeuverGroupReference', 'ParameterReference']);

/** `parameterAttributes` on an element of a ManeuverGroup (a simple scenario's groups), unless it is written already. */
function parameterAttributesItem(
  parsed: XmlDocument,
  target: { tagStart: number; written: string[]; start: number },
  document: TextDocument,
  offset: number,
): CompletionItem[] {
  if (target.written.includes(PARAMETER_ATTRIBUTES)) return [];
  const found = elementAt(parsed, target.tagStart);
  const element = found && found.start === target.tagStart ? found : undefined;
  if (!ancestor(found, 'ManeuverGroup') || (element && REFERENCE_ELEMENTS.has(element.name))) return [];
  return [
    {
      label: PARAMETER_ATTRIBUTES,
      kind: CompletionItemKind.Field,
      detail: 'the attributes a main file may override (modular scenarios)',
      documentation:
        "A comma-separated list of attributes of this element; each one's own value is its default, and a ParameterReference key of a main file sets it.",
      sortText: '0_999',
      insertTextFormat: InsertTextFormat.Snippet,
      textEdit: { range: replaceRange(document, target.start, offset), newText: `${PARAMETER_ATTRIBUTES}="$1"` },
    },
  ];
}

/** `<ParameterReference .../>` inside a ManeuverGroupReference: an empty one, then one per key not given yet with its default. */
async function parameterReferenceItems(
  workspace: Workspace,
  ref: SourceRef,
  document: TextDocument,
  parsed: XmlDocument,
  start: number,
  offset: number,
): Promise<CompletionItem[]> {
  const range = replaceRange(document, start, offset);
  const typedOpen = document.getText()[start] === '<';
  const filter = (label: string) => (typedOpen ? `<${label}` : label);
  const items: CompletionItem[] = [
    {
      label: 'ParameterReference',
      kind: CompletionItemKind.Property,
      detail: 'sets an overridable attribute of the referenced group',
      sortText: '0_000',
      filterText: filter('ParameterReference'),
      insertTextFormat: InsertTextFormat.Snippet,
      textEdit: { range, newText: '<ParameterReference key="$1" value="$2"/>$0' },
    },
  ];
  const found = await groupBefore(workspace, ref, parsed, start);
  if (!found) return items;
  const given = found.groupReference.children
    .filter((child) => child.name === 'ParameterReference')
    .map((child) => attribute(child, 'key')?.value.trim() ?? '');
  const escape = (value: string) => value.replace(/[$}\\]/g, (char) => `\\${char}`);
  const item = (form: string, defaultValue: string | undefined, sortText: string): CompletionItem => ({
    label: `ParameterReference ${form}`,
    kind: CompletionItemKind.Property,
    detail: `default ${defaultValue ?? '(none)'}`,
    sortText,
    filterText: filter(`ParameterReference ${form}`),
    insertTextFormat: InsertTextFormat.Snippet,
    textEdit: { range, newText: `<ParameterReference key="${escape(form)}" value="\${1:${escape(defaultValue ?? '')}}"/>$0` },
  });
  keyChoices(found.targets).forEach((choice, index) => {
    const [form] = choice.forms;
    const order = `0_${String(index + 1).padStart(3, '0')}`;
    if (form !== undefined && !choice.targets.some((target) => coveredBy(given, target)))
      items.push(item(form, choice.targets[0].defaultValue, order));
    choice.positioned.forEach(({ target, form: positioned }, member) => {
      if (!coveredBy(given, target)) items.push(item(positioned, target.defaultValue, `${order}.${String(member + 1).padStart(3, '0')}`));
    });
  });
  return items;
}

/** A whole scenario for a file that holds no element yet (an XML declaration and comments at most before the cursor). */
function skeletonItems(workspace: Workspace, parsed: XmlDocument, document: TextDocument, start: number, offset: number): CompletionItem[] {
  if (parsed.root && parsed.root.start < start) return [];
  const before = document.getText().slice(0, start);
  if (!/^\s*(?:<\?xml[^>]*\?>\s*)?(?:<!--[\s\S]*?-->\s*)*$/.test(before)) return [];
  const index = indexFor(parsed, workspace.settings.schemaVersion);
  if (!index) return [];
  const typedOpen = document.getText()[start] === '<';
  return [
    {
      label: `OpenSCENARIO ${index.version} scenario`,
      kind: CompletionItemKind.Snippet,
      detail: 'a whole scenario: FileHeader, CatalogLocations, RoadNetwork, Entities, Storyboard',
      sortText: '0_000',
      filterText: typedOpen ? '<OpenSCENARIO' : 'OpenSCENARIO',
      insertTextFormat: InsertTextFormat.Snippet,
      textEdit: { range: replaceRange(document, start, offset), newText: scenarioSkeletonSnippet(index, !before.includes('<?xml')) },
    },
  ];
}

/** Completion from the tolerant parse of the current text, so that it works while the document is not well-formed. */
export async function complete(workspace: Workspace, ref: SourceRef, document: TextDocument, offset: number): Promise<CompletionItem[]> {
  const distribution = await distributionCompletion(workspace, ref, document.getText(), offset);
  if (distribution) return distribution;
  const source = await workspace.source(ref);
  const parsed = await currentDocument(workspace, ref, document);
  const semantics = source.semantics;
  const target = completionTargetAt(parsed, offset, semantics !== undefined);
  const range = 'context' in target ? replaceRange(document, target.context.valueStart, target.context.valueEnd) : undefined;
  switch (target.kind) {
    case 'parameter':
      return semantics
        ? parameterCompletion(
            document,
            semantics,
            target.context,
            offset,
            attributeTypeAt(indexFor(parsed, workspace.settings.schemaVersion), parsed, target.context),
          )
        : [];
    case 'catalogReference':
      return semantics ? catalogCompletion(workspace, semantics, document, target.context, target.part) : [];
    case 'fileReference':
      return (await fileNameCandidates(workspace, ref)).map((candidate, index) => ({
        label: candidate.name,
        kind: candidate.name.endsWith('.mosc') ? CompletionItemKind.Module : CompletionItemKind.File,
        detail: candidate.where,
        sortText: String(index).padStart(5, '0'),
        textEdit: { range: range as LspRange, newText: candidate.name },
      }));
    case 'groupReference': {
      const { source: referenced, fileName } = await referencedSource(workspace, ref, parsed, target.context.tagStart);
      const seen = new Set<string>();
      return (referenced?.model?.groups ?? [])
        .filter((group) => group.name && !seen.has(group.name) && seen.add(group.name))
        .map((group, index) => ({
          label: group.name,
          kind: CompletionItemKind.Class,
          detail: `ManeuverGroup of ${fileName} (${overridableAttributes(referenced?.model as NonNullable<FlatSource['model']>, group).length} overridable attributes)`,
          sortText: String(index).padStart(5, '0'),
          textEdit: { range: range as LspRange, newText: group.name },
        }));
    }
    case 'key':
      return keyItems(workspace, ref, document, parsed, target.context);
    case 'keyValue':
      return valueItems(workspace, ref, document, parsed, target.context);
    case 'listedAttribute':
      return parameterAttributeItems(document, target.context);
    case 'entityReference':
      return (source.original?.entities ?? []).map((entity) => ({
        label: entity.name,
        kind: CompletionItemKind.Variable,
        textEdit: { range: range as LspRange, newText: entity.name },
      }));
    case 'attributeName':
      return [...schemaCompletion(workspace, parsed, target, offset), ...parameterAttributesItem(parsed, target, document, offset)];
    case 'elementName': {
      const schemaItems = schemaCompletion(workspace, parsed, target, offset);
      const skeleton = skeletonItems(workspace, parsed, document, target.start, offset);
      if (skeleton.length > 0) return [...skeleton, ...schemaItems];
      if (target.open?.name === 'ManeuverGroupReference')
        return [...schemaItems, ...(await parameterReferenceItems(workspace, ref, document, parsed, target.start, offset))];
      // A ScenarioReference's parent is the ManeuverGroup it fills (SPEC), so it is offered nowhere else.
      if ('ScenarioReference'.toLowerCase().startsWith(target.prefix.toLowerCase()) && target.open?.name === 'ManeuverGroup') {
        return [...schemaItems, ...(await snippetItems(workspace, ref, document, target.open, target.start, offset))];
      }
      return schemaItems;
    }
    default:
      return schemaCompletion(workspace, parsed, target, offset);
  }
}

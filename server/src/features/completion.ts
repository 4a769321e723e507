import * as fs from 'node:fs';
import * as path from 'node:path';
import { CompletionItem, CompletionItemKind, InsertTextFormat, Range as LspRange } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { FlatSource } from '../core/flatten';
import { keyMatches, OverridableAttribute, overridableAttributes } from '../core/keys';
import { findGroup, PARAMETER_ATTRIBUTES } from '../core/model';
import { displayRef, SourceRef } from '../core/sources';
import { keyChoices, overridablePlace, sourceForFileName } from '../analysis';
import { attributeValuesBetween, elementNameContextAt, lastAttributeValueBefore, openElementsAt, valueContextAt, ValueContext } from '../cursor';
import { Workspace } from '../workspace';
import { schemaCompletion } from './schemaCompletion';
import { catalogCompletion } from './catalogs';
import { dollarPrefix, parameterCompletion } from './parameters';

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
    else if (entry.isDirectory() && fs.existsSync(path.join(full, 'main.xosc')) && full !== (exclude && path.dirname(exclude))) names.push(`${entry.name}.mosc`);
  }
  return names.sort();
}

/** Names that resolve from `from`, in lookup order (SPEC 3): its package or folder, SCENARIO_PATH, parent folders. */
export async function fileNameCandidates(workspace: Workspace, from: SourceRef): Promise<FileNameCandidate[]> {
  const seen = new Map<string, FileNameCandidate>();
  const add = (name: string, where: string) => {
    if (!seen.has(name)) seen.set(name, { name, where });
  };
  if (from.entries.length > 0) {
    const packageRef: SourceRef = { disk: from.disk, entries: from.entries.slice(0, -1) };
    const self = from.entries[from.entries.length - 1];
    const contents = await workspace.store.readPackage(packageRef).catch(() => undefined);
    for (const entry of contents ? [...contents.entries.keys()].sort() : []) {
      if (entry === self) continue;
      if (/\.(xosc|mosc)$/i.test(entry) && !entry.endsWith('/main.xosc')) add(entry, displayRef(packageRef, workspace.folders[0]));
      else if (entry.endsWith('/main.xosc')) add(`${entry.slice(0, -'/main.xosc'.length)}.mosc`, displayRef(packageRef, workspace.folders[0]));
    }
  } else {
    const directory = path.dirname(from.disk);
    for (const name of listFolder(directory, from.disk)) add(name, 'this folder');
  }
  for (const directory of workspace.store.scenarioPathFor(from)) for (const name of listFolder(directory, from.disk)) add(name, `${directory} (scenario path)`);
  const root = workspace.store.rootOf(path.dirname(from.disk));
  if (from.entries.length === 0) {
    for (let parent = path.dirname(path.dirname(from.disk)); parent.startsWith(root); parent = path.dirname(parent)) {
      for (const name of listFolder(parent, from.disk)) add(name, `${parent} (parent folder)`);
      if (parent === root || parent === path.dirname(parent)) break;
    }
  }
  return [...seen.values()];
}

function replaceRange(document: TextDocument, start: number, end: number): LspRange {
  return { start: document.positionAt(start), end: document.positionAt(end) };
}

/** The enclosing ScenarioReference's source and, for keys, the group, read from the text before the cursor. */
async function referencedSource(workspace: Workspace, ref: SourceRef, text: string, before: number): Promise<{ source: FlatSource | undefined; fileName: string }> {
  const reference = lastAttributeValueBefore(text, 'ScenarioReference', 'scenarioFileName', 0, before);
  if (!reference) return { source: undefined, fileName: '' };
  return { source: await sourceForFileName(workspace, ref, reference.value), fileName: reference.value };
}

function coveredBy(keys: string[], target: OverridableAttribute): boolean {
  return keys.some((key) => keyMatches(key, target));
}

/** The group a ParameterReference tag (starting at `tagStart`) overrides, read from the text before it. */
async function groupBefore(workspace: Workspace, ref: SourceRef, text: string, tagStart: number) {
  const groupReference = lastAttributeValueBefore(text, 'ManeuverGroupReference', 'maneuverGroupName', 0, tagStart);
  if (!groupReference) return undefined;
  const { source } = await referencedSource(workspace, ref, text, groupReference.tagStart);
  const group = source?.model ? findGroup(source.model, groupReference.value) : undefined;
  if (!source?.model || !group) return undefined;
  return { source, group, groupReference, targets: overridableAttributes(source.model, group) };
}

/** The default values of the attributes that the key written in the same tag reaches. */
async function valueItems(workspace: Workspace, ref: SourceRef, document: TextDocument, context: ValueContext): Promise<CompletionItem[]> {
  const key = context.siblings.find((sibling) => sibling.name === 'key')?.value.trim();
  const found = key ? await groupBefore(workspace, ref, document.getText(), context.tagStart) : undefined;
  if (!found || !key) return [];
  const range = replaceRange(document, context.valueStart, context.valueEnd);
  const defaults = new Map<string, string>();
  for (const target of found.targets) {
    if (target.defaultValue !== undefined && keyMatches(key, target) && !defaults.has(target.defaultValue)) defaults.set(target.defaultValue, `default of ${target.element.name}.${target.attributeName}`);
  }
  return [...defaults].map(([value, detail]) => ({ label: value, kind: CompletionItemKind.Value, detail, textEdit: { range, newText: value } }));
}

async function keyItems(workspace: Workspace, ref: SourceRef, document: TextDocument, context: ValueContext): Promise<CompletionItem[]> {
  const text = document.getText();
  const found = await groupBefore(workspace, ref, text, context.tagStart);
  if (!found) return [];
  const { source, group, groupReference, targets } = found;
  const blockEnd = [text.indexOf('</ManeuverGroupReference', context.valueEnd), text.indexOf('<ManeuverGroupReference', context.valueEnd), text.length]
    .filter((index) => index >= 0)
    .reduce((a, b) => Math.min(a, b));
  const given = attributeValuesBetween(text, 'ParameterReference', 'key', groupReference.tagStart, blockEnd)
    .filter((entry) => entry.valueStart !== context.valueStart)
    .map((entry) => entry.value.trim());
  const range = replaceRange(document, context.valueStart, context.valueEnd);
  const items: CompletionItem[] = [];
  // One row per attribute (or per set of attributes only settable together), in its shortest unambiguous key.
  keyChoices(targets).forEach((choice, index) => {
    if (choice.targets.some((target) => coveredBy(given, target))) return;
    const [first] = choice.targets;
    const [form] = choice.forms;
    const declared = overridablePlace(source, first);
    const where = declared ? `${displayRef(declared.ref, workspace.folders[0])}:${declared.range.start.line + 1}` : '';
    const defaults = [...new Set(choice.targets.map((target) => target.defaultValue ?? '(none)'))].join(' / ');
    const together = choice.targets.length > 1 ? ` (sets ${choice.targets.length} attributes)` : '';
    items.push({
      label: form,
      kind: CompletionItemKind.Property,
      detail: `default ${defaults}${where ? ` — ${where}` : ''}${together}`,
      documentation: `Overrides \`${first.attributeName}\` of <${first.element.name}> (${first.path.join(' › ')}) in group ${group.name}.`,
      sortText: String(index).padStart(5, '0'),
      filterText: form,
      textEdit: { range, newText: form },
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

/** A whole ScenarioReference block for one group of a file, every key set to its default (tab stops on values). */
export function referenceSnippet(fileName: string, groupName: string, targets: OverridableAttribute[], indent: string): string {
  const escape = (value: string) => value.replace(/[$}\\]/g, (char) => `\\${char}`);
  const lines = [`<ScenarioReference scenarioFileName="${escape(fileName)}">`, `${indent}<ManeuverGroupReference maneuverGroupName="${escape(groupName)}">`];
  keyChoices(targets).forEach((choice, index) => {
    const defaultValue = choice.targets[0].defaultValue;
    if (defaultValue === undefined || choice.forms.length === 0) return;
    lines.push(`${indent}${indent}<ParameterReference key="${escape(choice.forms[0])}" value="\${${index + 1}:${escape(defaultValue)}}"/>`);
  });
  lines.push(`${indent}</ManeuverGroupReference>`, '</ScenarioReference>$0');
  return lines.join('\n');
}

/**
 * ScenarioReference snippets for each group of each file a name resolves to. Simple scenarios (files
 * without references of their own, whose groups list attributes to override) come first, then the
 * other files in lookup order.
 */
async function snippetItems(workspace: Workspace, ref: SourceRef, document: TextDocument, start: number, offset: number): Promise<CompletionItem[]> {
  const range = replaceRange(document, start, offset);
  const indent = /^( +|\t)/m.exec(document.getText().slice(0, 4000))?.[1] ?? '    ';
  const ranked: { rank: number; item: CompletionItem }[] = [];
  for (const [fileIndex, candidate] of (await fileNameCandidates(workspace, ref)).entries()) {
    if (ranked.length >= MAX_SNIPPETS) break;
    const source = await sourceForFileName(workspace, ref, candidate.name);
    if (!source?.model) continue;
    const simple = source.links.length === 0 && source.model.declarations.length > 0;
    for (const group of source.model.groups) {
      if (ranked.length >= MAX_SNIPPETS) break;
      const targets = overridableAttributes(source.model, group);
      ranked.push({
        rank: (simple ? 0 : 1) * 1_000_000 + fileIndex * 1000 + ranked.length,
        item: {
          label: `ScenarioReference ${candidate.name} ${group.name}`,
          kind: CompletionItemKind.Snippet,
          detail: `${targets.length} keys with their defaults`,
          filterText: `<ScenarioReference ${candidate.name} ${group.name}`,
          insertTextFormat: InsertTextFormat.Snippet,
          textEdit: { range, newText: referenceSnippet(candidate.name, group.name, targets, indent) },
        },
      });
    }
  }
  ranked.sort((a, b) => a.rank - b.rank);
  return ranked.map(({ item }, index) => ({ ...item, sortText: `z${String(index).padStart(4, '0')}` }));
}

/** Parameters after `$` and catalog or entry names in a CatalogReference, from the semantic model. */
async function semanticCompletion(workspace: Workspace, ref: SourceRef, document: TextDocument, context: ValueContext, offset: number): Promise<CompletionItem[] | undefined> {
  const semantics = (await workspace.source(ref)).semantics;
  if (!semantics) return undefined;
  if (dollarPrefix(context) !== undefined) return parameterCompletion(document, semantics, context, offset);
  return catalogCompletion(workspace, semantics, document, context);
}

/** Completion from the text around the cursor, so that it works while the document is not well-formed. */
export async function complete(workspace: Workspace, ref: SourceRef, document: TextDocument, offset: number): Promise<CompletionItem[]> {
  const text = document.getText();
  const context = valueContextAt(text, offset);
  if (context) {
    const range = replaceRange(document, context.valueStart, context.valueEnd);
    const semantic = await semanticCompletion(workspace, ref, document, context, offset);
    if (semantic) return semantic;
    if (context.element === 'ScenarioReference' && context.attribute === 'scenarioFileName') {
      return (await fileNameCandidates(workspace, ref)).map((candidate, index) => ({
        label: candidate.name,
        kind: candidate.name.endsWith('.mosc') ? CompletionItemKind.Module : CompletionItemKind.File,
        detail: candidate.where,
        sortText: String(index).padStart(5, '0'),
        textEdit: { range, newText: candidate.name },
      }));
    }
    if (context.element === 'ManeuverGroupReference' && context.attribute === 'maneuverGroupName') {
      const { source, fileName } = await referencedSource(workspace, ref, text, context.tagStart);
      const seen = new Set<string>();
      return (source?.model?.groups ?? [])
        .filter((group) => group.name && !seen.has(group.name) && seen.add(group.name))
        .map((group, index) => ({
          label: group.name,
          kind: CompletionItemKind.Class,
          detail: `ManeuverGroup of ${fileName} (${overridableAttributes(source?.model as NonNullable<FlatSource['model']>, group).length} overridable attributes)`,
          sortText: String(index).padStart(5, '0'),
          textEdit: { range, newText: group.name },
        }));
    }
    if (context.element === 'ParameterReference' && context.attribute === 'key') return keyItems(workspace, ref, document, context);
    if (context.element === 'ParameterReference' && context.attribute === 'value') return valueItems(workspace, ref, document, context);
    if (context.attribute === PARAMETER_ATTRIBUTES) return parameterAttributeItems(document, context);
    if (context.attribute === 'entityRef') {
      const source = await workspace.source(ref);
      return (source.original?.entities ?? []).map((entity) => ({ label: entity.name, kind: CompletionItemKind.Variable, textEdit: { range, newText: entity.name } }));
    }
    return schemaCompletion(workspace, ref, document, offset, context);
  }
  const schemaItems = await schemaCompletion(workspace, ref, document, offset, undefined);
  const elementContext = elementNameContextAt(text, offset);
  // A ScenarioReference's parent is the ManeuverGroup it fills (SPEC), so it is offered nowhere else.
  if (elementContext && 'ScenarioReference'.toLowerCase().startsWith(elementContext.prefix.toLowerCase()) && openElementsAt(text, elementContext.start).at(-1) === 'ManeuverGroup') {
    return [...schemaItems, ...(await snippetItems(workspace, ref, document, elementContext.start, offset))];
  }
  return schemaItems;
}

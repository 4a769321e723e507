import * as path from 'node:path';
import { Location, LSPErrorCodes, ResponseError, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { FlatSource, originOf } from '../core/flatten';
import { refId, SourceRef } from '../core/sources';
import { Range } from '../core/text';
import { XmlElement } from '../core/xml';
import { listedPlace, placeIn, Place, resolvedTarget } from '../analysis';
import { declarationOf, SyntacticTarget, syntacticTarget, targetAt } from '../target';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';
import { entryParameterOf, entryParameterReferences, entryParameterRenameRange, renameEntryParameter } from './catalogParameters';
import { parameterReferences, parameterRenameRange, renameParameter } from './parameters';
import { distributionRenameEdits } from './distributions';

/** A group or an overridable attribute, identified by the file and element it is written in. */
export type NameTarget =
  | { kind: 'group'; ref: SourceRef; elementStart: number; name: string; declaration: Place }
  | { kind: 'attribute'; ref: SourceRef; elementStart: number; name: string; declaration: Place };

function sameElement(source: FlatSource, element: XmlElement, ref: SourceRef, elementStart: number): boolean {
  const origin = originOf(source, element);
  return refId(origin.source.ref) === refId(ref) && origin.element.start === elementStart;
}

/** The group or attribute a target names: at its declaration, or at a reference or key that reaches it. */
export function nameTargetOf(source: FlatSource, target: SyntacticTarget): NameTarget | undefined {
  const ref = source.ref;
  const place = (start: number, end: number) => placeIn(source, start, end) as Place;
  switch (target.kind) {
    case 'groupDeclaration': {
      const { element, attribute } = target.hit;
      return {
        kind: 'group',
        ref,
        elementStart: element.start,
        name: attribute.value,
        declaration: place(attribute.valueStart, attribute.valueEnd),
      };
    }
    case 'listedAttribute':
      return {
        kind: 'attribute',
        ref,
        elementStart: target.hit.element.start,
        name: target.name,
        declaration: place(target.start, target.end),
      };
    case 'groupReference': {
      const { link, group } = target.linked ?? {};
      if (!link?.source || !group?.target) return undefined;
      const origin = originOf(link.source, group.target.element);
      const name = origin.element.attributes.find((candidate) => candidate.name === 'name');
      const declaration = name
        ? placeIn(origin.source, name.valueStart, name.valueEnd)
        : placeIn(origin.source, origin.element.start, origin.element.nameEnd);
      return declaration
        ? { kind: 'group', ref: origin.source.ref, elementStart: origin.element.start, name: name?.value ?? '', declaration }
        : undefined;
    }
    case 'key': {
      const { link, group } = target.linked ?? {};
      if (!link?.source || !group?.target) return undefined;
      const first = target.match?.targets[0];
      if (!first) return undefined;
      const origin = originOf(link.source, first.element);
      const declaration = listedPlace(origin.source, origin.element, first.attributeName);
      return declaration
        ? { kind: 'attribute', ref: origin.source.ref, elementStart: origin.element.start, name: first.attributeName, declaration }
        : undefined;
    }
    default:
      return undefined;
  }
}

/** References of what the cursor names: a catalog entry's parameter, a parameter, a group or an overridable attribute. */
export async function referencesAt(
  workspace: Workspace,
  ref: SourceRef,
  offset: number,
  includeDeclaration: boolean,
  checkCancelled: () => void,
): Promise<Place[]> {
  const source = await workspace.source(ref);
  const target = targetAt(source, offset);
  const semantics = source.semantics;
  // A catalog entry's parameter is also set from other files (CatalogReference ParameterAssignments).
  const entryParameter = semantics ? await entryParameterOf(workspace, semantics, target) : undefined;
  if (entryParameter) return entryParameterReferences(workspace, entryParameter, includeDeclaration);
  const declaration = declarationOf(target);
  if (semantics && declaration) return parameterReferences(semantics, declaration, includeDeclaration);
  const subject = nameTargetOf(source, syntacticTarget(source, target, offset));
  if (!subject) return [];
  checkCancelled();
  const places = (await usagesOf(workspace, subject)).map((usage) => usage.place);
  checkCancelled();
  if (includeDeclaration) places.unshift(subject.declaration);
  return places;
}

/** The range a rename at the cursor replaces, and its current text; null where nothing renameable stands. */
export async function prepareRenameAt(
  workspace: Workspace,
  ref: SourceRef,
  offset: number,
): Promise<{ range: Range; placeholder: string } | null> {
  const source = await workspace.source(ref);
  const target = targetAt(source, offset);
  const lines = source.original?.document.lines;
  const semantics = source.semantics;
  const assigned = entryParameterRenameRange(target);
  const parameter = semantics
    ? (parameterRenameRange(target) ?? (assigned && (await entryParameterOf(workspace, semantics, target)) ? assigned : undefined))
    : undefined;
  if (parameter && lines) return { range: lines.range(parameter.start, parameter.end), placeholder: parameter.name };
  const subject = nameTargetOf(source, syntacticTarget(source, target, offset));
  if (!subject || subject.kind !== 'group') return null;
  if (refId(subject.ref) === refId(ref)) return { range: subject.declaration.range, placeholder: subject.name };
  const text = source.original?.document.text ?? '';
  // The reference under the cursor: the whole maneuverGroupName value.
  let start = offset;
  let end = offset;
  while (start > 0 && !/["']/.test(text[start - 1])) start--;
  while (end < text.length && !/["']/.test(text[end])) end++;
  return lines ? { range: lines.range(start, end), placeholder: text.slice(start, end) } : null;
}

/** Renames what the cursor names: a catalog entry's parameter, a parameter, or a ManeuverGroup with every reference to it. */
export async function renameAt(
  workspace: Workspace,
  ref: SourceRef,
  offset: number,
  newName: string,
  checkCancelled: () => void,
): Promise<WorkspaceEdit> {
  const source = await workspace.source(ref);
  const target = targetAt(source, offset);
  const semantics = source.semantics;
  const entryParameter = semantics ? await entryParameterOf(workspace, semantics, target) : undefined;
  if (entryParameter) return renameEntryParameter(workspace, entryParameter, newName);
  const declaration = declarationOf(target);
  const parameterEdit = semantics ? renameParameter(workspace, semantics, declaration, newName) : undefined;
  if (parameterEdit && semantics && declaration && declaration.kind === 'parameter' && declaration.scope.parent === undefined) {
    // A root parameter: the distribution files that vary it name it too.
    const renamed = newName.startsWith('$') ? newName.slice(1) : newName;
    Object.assign(parameterEdit.changes ?? {}, await distributionRenameEdits(workspace, semantics.ref, declaration.name, renamed));
  }
  if (parameterEdit) return parameterEdit;
  const subject = nameTargetOf(source, syntacticTarget(source, target, offset));
  if (!subject || subject.kind !== 'group')
    throw new ResponseError(LSPErrorCodes.RequestFailed, 'only ManeuverGroup and parameter names can be renamed');
  if (subject.ref.entries.length > 0 && !workspace.editablePackages) {
    throw new ResponseError(LSPErrorCodes.RequestFailed, 'the group is inside a .mosc package, and this editor cannot write into packages');
  }
  checkCancelled();
  return renameGroup(workspace, subject, newName.includes('.') ? newName.slice(newName.lastIndexOf('.') + 1) : newName);
}

export interface Usage {
  place: Place;
  /** The text written at the place (a maneuverGroupName or a key). */
  text: string;
}

/** Every maneuverGroupName or key in the workspace that reaches the target, through packages too. */
export async function usagesOf(workspace: Workspace, target: NameTarget): Promise<Usage[]> {
  const found = new Map<string, Usage>();
  const visited = new Set<string>();
  const visit = (source: FlatSource) => {
    if (visited.has(refId(source.ref))) return;
    visited.add(refId(source.ref));
    for (const link of source.links) {
      if (!link.source) continue;
      for (const linked of link.groups) {
        if (!linked.target) continue;
        if (target.kind === 'group') {
          const nameAttribute = linked.info.nameAttribute;
          if (nameAttribute && sameElement(link.source, linked.target.element, target.ref, target.elementStart)) {
            const place = placeIn(source, nameAttribute.valueStart, nameAttribute.valueEnd);
            if (place) found.set(`${refId(place.ref)}:${nameAttribute.valueStart}`, { place, text: nameAttribute.value });
          }
          continue;
        }
        for (const match of linked.plan?.matches ?? []) {
          const keyAttribute = match.parameter.keyAttribute;
          if (!keyAttribute) continue;
          const reaches = match.targets.some(
            (candidate) =>
              candidate.attributeName === target.name &&
              sameElement(link.source as FlatSource, candidate.element, target.ref, target.elementStart),
          );
          if (!reaches) continue;
          const place = placeIn(source, keyAttribute.valueStart, keyAttribute.valueEnd);
          if (place) found.set(`${refId(place.ref)}:${keyAttribute.valueStart}`, { place, text: keyAttribute.value });
        }
      }
      visit(link.source);
    }
  };
  for (const ref of await workspace.referringFiles()) {
    try {
      visit(await workspace.source(ref));
    } catch {
      // A file that cannot be analysed holds no usable reference.
    }
  }
  return [...found.values()];
}

export function placesToLocations(workspace: Workspace, places: Place[]): Location[] {
  return places.map((place) => ({ uri: workspace.uriOf(place.ref), range: place.range }));
}

function addEdit(edit: WorkspaceEdit, workspace: Workspace, ref: SourceRef, range: Range, newText: string): void {
  // Files inside a .mosc are written only by a client that opens packages as file systems (mosc: URIs).
  if (ref.entries.length > 0 && !workspace.editablePackages) return;
  const uri = workspace.uriOf(ref);
  const changes = (edit.changes ??= {});
  (changes[uri] ??= []).push(TextEdit.replace(range, newText));
}

/** Renames a group and every maneuverGroupName reaching it, dotted names keeping their prefix. */
export async function renameGroup(workspace: Workspace, target: NameTarget, newName: string): Promise<WorkspaceEdit> {
  const edit: WorkspaceEdit = { changes: {} };
  addEdit(edit, workspace, target.ref, target.declaration.range, newName);
  for (const usage of await usagesOf(workspace, target)) {
    const replaced =
      usage.text === target.name
        ? newName
        : usage.text.endsWith(`.${target.name}`)
          ? `${usage.text.slice(0, -target.name.length)}${newName}`
          : undefined;
    if (replaced !== undefined) addEdit(edit, workspace, usage.place.ref, usage.place.range, replaced);
  }
  return edit;
}

/** Edits to every scenarioFileName that resolves to a renamed file or unpacked folder. */
export async function fileRenameEdits(workspace: Workspace, renames: { oldUri: string; newUri: string }[]): Promise<WorkspaceEdit | null> {
  const moves = renames
    .map((rename) => ({ from: filePathOf(rename.oldUri), to: filePathOf(rename.newUri) }))
    .filter((move): move is { from: string; to: string } => move.from !== undefined && move.to !== undefined);
  if (moves.length === 0) return null;
  const edit: WorkspaceEdit = { changes: {} };
  for (const ref of await workspace.referringFiles()) {
    if (ref.entries.length > 0) continue;
    let source: FlatSource;
    try {
      source = await workspace.source(ref);
    } catch {
      continue;
    }
    for (const link of source.links) {
      const fileAttribute = link.info.fileAttribute;
      const resolved = link.resolution.kind === 'package' ? link.resolution.packageRef : resolvedTarget(link.resolution);
      if (!fileAttribute || !resolved || resolved.entries.length > 0) continue;
      const move = moves.find((candidate) => candidate.from === resolved.disk);
      if (!move) continue;
      const folderPackage = link.resolution.kind === 'package' && link.resolution.folder;
      const newBase = folderPackage ? `${path.basename(move.to)}.mosc` : path.basename(move.to);
      const written = fileAttribute.value;
      const slash = written.lastIndexOf('/');
      const sameFolder = path.dirname(move.from) === path.dirname(move.to);
      const newValue = sameFolder
        ? `${written.slice(0, slash + 1)}${newBase}`
        : path
            .relative(path.dirname(ref.disk), folderPackage ? `${move.to}.mosc` : move.to)
            .split(path.sep)
            .join('/');
      const place = placeIn(source, fileAttribute.valueStart, fileAttribute.valueEnd);
      if (place) addEdit(edit, workspace, ref, place.range, newValue);
    }
  }
  return Object.keys(edit.changes ?? {}).length > 0 ? edit : null;
}

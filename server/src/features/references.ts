import * as path from 'node:path';
import { Location, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { FlatSource, originOf } from '../core/flatten';
import { PARAMETER_ATTRIBUTES, parseParameterAttributeNames } from '../core/model';
import { refId, SourceRef } from '../core/sources';
import { Range } from '../core/text';
import { XmlElement } from '../core/xml';
import { groupLinkOf, linkOf, listedPlace, placeIn, Place, resolvedTarget } from '../analysis';
import { ancestor, attributeAt } from '../cursor';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';

/** A group or an overridable attribute, identified by the file and element it is written in. */
export type Target =
  | { kind: 'group'; ref: SourceRef; elementStart: number; name: string; declaration: Place }
  | { kind: 'attribute'; ref: SourceRef; elementStart: number; name: string; declaration: Place };

function sameElement(source: FlatSource, element: XmlElement, ref: SourceRef, elementStart: number): boolean {
  const origin = originOf(source, element);
  return refId(origin.source.ref) === refId(ref) && origin.element.start === elementStart;
}

/** The group or attribute under the cursor: at its declaration, or at a reference or key that reaches it. */
export async function targetAt(workspace: Workspace, ref: SourceRef, offset: number): Promise<Target | undefined> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return undefined;
  const hit = attributeAt(model.document, offset);
  if (!hit) return undefined;
  const { element, attribute } = hit;
  const place = (start: number, end: number) => placeIn(source, start, end) as Place;
  if (element.name === 'ManeuverGroup' && attribute.name === 'name') {
    return { kind: 'group', ref, elementStart: element.start, name: attribute.value, declaration: place(attribute.valueStart, attribute.valueEnd) };
  }
  if (attribute.name === PARAMETER_ATTRIBUTES) {
    const listed = parseParameterAttributeNames(element, attribute).find((name) => offset >= name.start && offset <= name.end);
    if (listed) return { kind: 'attribute', ref, elementStart: element.start, name: listed.name, declaration: place(listed.start, listed.end) };
    return undefined;
  }
  const declarationAttribute = element.attributes.find((candidate) => candidate.name === PARAMETER_ATTRIBUTES);
  const declaredHere = declarationAttribute && parseParameterAttributeNames(element, declarationAttribute).some((name) => name.name === attribute.name);
  if (declaredHere && offset <= attribute.nameEnd) {
    return { kind: 'attribute', ref, elementStart: element.start, name: attribute.name, declaration: place(attribute.nameStart, attribute.nameEnd) };
  }
  const groupReference = element.name === 'ManeuverGroupReference' ? element : ancestor(element.parent, 'ManeuverGroupReference');
  const reference = ancestor(groupReference?.parent, 'ScenarioReference');
  const link = reference ? linkOf(source, reference) : undefined;
  const linked = link && groupReference ? groupLinkOf(link, groupReference) : undefined;
  if (!link?.source || !linked?.target) return undefined;
  if (element.name === 'ManeuverGroupReference' && attribute.name === 'maneuverGroupName') {
    const origin = originOf(link.source, linked.target.element);
    const name = origin.element.attributes.find((candidate) => candidate.name === 'name');
    const declaration = name ? placeIn(origin.source, name.valueStart, name.valueEnd) : placeIn(origin.source, origin.element.start, origin.element.nameEnd);
    return declaration ? { kind: 'group', ref: origin.source.ref, elementStart: origin.element.start, name: name?.value ?? '', declaration } : undefined;
  }
  if (element.name === 'ParameterReference' && attribute.name === 'key') {
    const match = linked.plan?.matches.find((candidate) => candidate.parameter.element === element);
    const first = match?.targets[0];
    if (!first) return undefined;
    const origin = originOf(link.source, first.element);
    const declaration = listedPlace(origin.source, origin.element, first.attributeName);
    return declaration ? { kind: 'attribute', ref: origin.source.ref, elementStart: origin.element.start, name: first.attributeName, declaration } : undefined;
  }
  return undefined;
}

export interface Usage {
  place: Place;
  /** The text written at the place (a maneuverGroupName or a key). */
  text: string;
}

/** Every maneuverGroupName or key in the workspace that reaches the target, through packages too. */
export async function usagesOf(workspace: Workspace, target: Target): Promise<Usage[]> {
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
          const reaches = match.targets.some((candidate) => candidate.attributeName === target.name && sameElement(link.source as FlatSource, candidate.element, target.ref, target.elementStart));
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
export async function renameGroup(workspace: Workspace, target: Target, newName: string): Promise<WorkspaceEdit> {
  const edit: WorkspaceEdit = { changes: {} };
  addEdit(edit, workspace, target.ref, target.declaration.range, newName);
  for (const usage of await usagesOf(workspace, target)) {
    const replaced = usage.text === target.name ? newName : usage.text.endsWith(`.${target.name}`) ? `${usage.text.slice(0, -target.name.length)}${newName}` : undefined;
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
      const newValue = sameFolder ? `${written.slice(0, slash + 1)}${newBase}` : path.relative(path.dirname(ref.disk), folderPackage ? `${move.to}.mosc` : move.to).split(path.sep).join('/');
      const place = placeIn(source, fileAttribute.valueStart, fileAttribute.valueEnd);
      if (place) addEdit(edit, workspace, ref, place.range, newValue);
    }
  }
  return Object.keys(edit.changes ?? {}).length > 0 ? edit : null;
}

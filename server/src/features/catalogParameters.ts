import { LSPErrorCodes, ResponseError, TextEdit, WorkspaceEdit } from 'vscode-languageserver/node';
import { Declaration, DocumentSemantics, referencedName, referencesOf } from '../core/semantics';
import { displayRef, refId } from '../core/sources';
import { Place } from '../analysis';
import { declarationOf, Target } from '../target';
import { Workspace } from '../workspace';
import { PARAMETER_NAME } from './parameters';

/**
 * A catalog entry's parameter across files (ASAM OpenSCENARIO 1.x section 9.4): declared in the
 * entry, set from scenario files by `CatalogReference` -> `ParameterAssignment parameterRef="NAME"`.
 * References and rename cover the declaration, its uses inside the entry and every such assignment.
 */

/** A parameter declared directly by a catalog entry, with the semantics of the catalog file. */
export interface EntryParameter {
  catalog: DocumentSemantics;
  declaration: Declaration;
}

/** One place to change: offsets of the name in a file. */
interface NamePlace {
  semantics: DocumentSemantics;
  start: number;
  end: number;
}

function isEntryParameter(declaration: Declaration | undefined): declaration is Declaration {
  return declaration !== undefined && declaration.scope.catalogEntry && declaration.nameAttribute !== undefined;
}

/** The entry parameter the target names: by its declaration or a use inside the entry, or by an assignment's parameterRef. */
export async function entryParameterOf(
  workspace: Workspace,
  semantics: DocumentSemantics,
  target: Target,
): Promise<EntryParameter | undefined> {
  const declaration = declarationOf(target);
  if (isEntryParameter(declaration)) return { catalog: semantics, declaration };
  if (target.kind !== 'catalogReference' || target.part !== 'parameterRef' || !target.resolution.entry) return undefined;
  const { entry } = target.resolution;
  const catalog = (await workspace.source(entry.file.ref)).semantics;
  const entryStart = entry.element.start;
  const scope = catalog?.model.scopes.find((candidate) => candidate.catalogEntry && candidate.element.start === entryStart);
  const named = scope?.byName.get(referencedName(target.attribute).name);
  return catalog && isEntryParameter(named) ? { catalog, declaration: named } : undefined;
}

/** The declaration, its uses inside the entry, then every ParameterAssignment naming it through a CatalogReference to that entry. */
async function placesOf(workspace: Workspace, parameter: EntryParameter): Promise<NamePlace[]> {
  const { catalog, declaration } = parameter;
  const name = declaration.nameAttribute;
  const places: NamePlace[] = name ? [{ semantics: catalog, start: name.valueStart, end: name.valueEnd }] : [];
  // A use's offsets cover `$name`, or only the name for a parameterRef; the name is its tail either way.
  for (const use of referencesOf(catalog, declaration)) places.push({ semantics: catalog, start: use.end - use.name.length, end: use.end });
  const catalogId = refId(catalog.ref);
  const entryStart = declaration.scope.element.start;
  for (const ref of await workspace.catalogReferrers()) {
    const text = await workspace.text(ref);
    if (text === undefined || !/<CatalogReference\b/.test(text)) continue;
    const semantics = (await workspace.source(ref)).semantics;
    for (const resolution of semantics?.catalogs.references ?? []) {
      const entry = resolution.entry;
      if (!semantics || !entry || refId(entry.file.ref) !== catalogId || entry.element.start !== entryStart) continue;
      for (const assignment of resolution.reference.assignments) {
        if (!assignment.parameterRef) continue;
        const named = referencedName(assignment.parameterRef);
        if (named.name === declaration.name) places.push({ semantics, start: named.start, end: named.end });
      }
    }
  }
  return places;
}

function toPlace(place: NamePlace): Place {
  return { ref: place.semantics.ref, range: place.semantics.model.document.lines.range(place.start, place.end) };
}

/** References of a catalog entry's parameter across the workspace. */
export async function entryParameterReferences(
  workspace: Workspace,
  parameter: EntryParameter,
  includeDeclaration: boolean,
): Promise<Place[]> {
  const places = (await placesOf(workspace, parameter)).map(toPlace);
  return includeDeclaration ? places : places.slice(1);
}

/** The assignment's parameterRef name the target stands on, for prepareRename (the declaration side is the one-file case). */
export function entryParameterRenameRange(target: Target): { start: number; end: number; name: string } | undefined {
  return target.kind === 'catalogReference' && target.part === 'parameterRef' ? referencedName(target.attribute) : undefined;
}

/** Renames a catalog entry's parameter in the entry and in every assignment that sets it. */
export async function renameEntryParameter(workspace: Workspace, parameter: EntryParameter, newName: string): Promise<WorkspaceEdit> {
  const name = newName.startsWith('$') ? newName.slice(1) : newName;
  if (!PARAMETER_NAME.test(name))
    throw new ResponseError(
      LSPErrorCodes.RequestFailed,
      `'${newName}' is not a parameter name (letters, digits and _, not starting with a digit)`,
    );
  const places = await placesOf(workspace, parameter);
  const inPackage = places.find((place) => place.semantics.ref.entries.length > 0);
  if (inPackage && !workspace.editablePackages) {
    throw new ResponseError(
      LSPErrorCodes.RequestFailed,
      `the parameter is set in ${displayRef(inPackage.semantics.ref, workspace.folders[0])}, inside a .mosc package, and this editor cannot write into packages`,
    );
  }
  const changes: Record<string, TextEdit[]> = {};
  for (const place of places) {
    const uri = workspace.uriOf(place.semantics.ref);
    (changes[uri] ??= []).push(TextEdit.replace(toPlace(place).range, name));
  }
  return { changes };
}

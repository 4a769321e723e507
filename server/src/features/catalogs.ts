import { CompletionItem, CompletionItemKind } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import { CatalogFile, CatalogLoader, catalogReferenceAt, Declaration, DocumentSemantics, entryParameterValue, formatValue } from '../core/semantics';
import { displayRef, refId } from '../core/sources';
import { XmlElement } from '../core/xml';
import { Place } from '../analysis';
import { ValueContext } from '../cursor';
import { Workspace } from '../workspace';

/** Catalogs in the editor: definition from a CatalogReference and completion of catalog and entry names, from the core's resolution. */

function namePlace(file: CatalogFile, element: XmlElement): Place {
  const name = element.attributes.find((attr) => attr.name === 'name');
  const lines = file.model.document.lines;
  return { ref: file.ref, range: name ? lines.range(name.valueStart, name.valueEnd) : lines.range(element.start, element.nameEnd) };
}

/** The declarations an entry holds itself (the parameters a ParameterAssignment may set). */
export function entryDeclarations(file: CatalogFile, entry: XmlElement): Declaration[] {
  return file.model.declarations.filter((declaration) => declaration.scope.element === entry && declaration.kind === 'parameter');
}

/**
 * Definition in a CatalogReference: `entryName` goes to the entry, `catalogName` to each catalog file
 * of that name, a ParameterAssignment's `parameterRef` to the entry's declaration. Undefined when the
 * offset is in none of them.
 */
export function catalogDefinition(semantics: DocumentSemantics, offset: number): Place[] | undefined {
  const resolution = catalogReferenceAt(semantics, offset);
  if (!resolution) return undefined;
  const within = (attr: { valueStart: number; valueEnd: number } | undefined) => attr !== undefined && offset >= attr.valueStart && offset <= attr.valueEnd;
  const { reference, entry } = resolution;
  if (within(reference.entryNameAttribute)) return entry ? [namePlace(entry.file, entry.element)] : [];
  if (within(reference.catalogNameAttribute)) return resolution.catalogs.map((file) => namePlace(file, file.catalog));
  const assignment = reference.assignments.find((candidate) => within(candidate.parameterRef));
  if (assignment?.parameterRef && entry) {
    const name = assignment.parameterRef.value.trim().replace(/^\$/, '');
    const declaration = entryDeclarations(entry.file, entry.element).find((candidate) => candidate.name === name);
    return declaration ? [namePlace(entry.file, declaration.element)] : [];
  }
  return undefined;
}

/** Every catalog file the document's CatalogLocations reach, each once. */
async function reachableCatalogs(workspace: Workspace, semantics: DocumentSemantics): Promise<CatalogFile[]> {
  const loader = new CatalogLoader(workspace.store);
  const files = new Map<string, CatalogFile>();
  for (const location of semantics.catalogs.locations) {
    for (const directory of location.directories) for (const file of await loader.allCatalogsIn(directory)) if (!files.has(refId(file.ref))) files.set(refId(file.ref), file);
  }
  return [...files.values()];
}

/** Completion of `catalogName` and `entryName` in a CatalogReference; undefined when the cursor is in neither. */
export async function catalogCompletion(workspace: Workspace, semantics: DocumentSemantics, document: TextDocument, context: ValueContext): Promise<CompletionItem[] | undefined> {
  if (context.element !== 'CatalogReference' || (context.attribute !== 'catalogName' && context.attribute !== 'entryName')) return undefined;
  const range = { start: document.positionAt(context.valueStart), end: document.positionAt(context.valueEnd) };
  const catalogs = await reachableCatalogs(workspace, semantics);
  const where = (file: CatalogFile) => displayRef(file.ref, workspace.folders[0]);
  if (context.attribute === 'catalogName') {
    const seen = new Set<string>();
    return catalogs
      .filter((file) => file.name && !seen.has(file.name) && seen.add(file.name))
      .map((file) => ({ label: file.name, kind: CompletionItemKind.Module, detail: `${file.entries.length} entries — ${where(file)}`, textEdit: { range, newText: file.name } }));
  }
  const catalogName = context.siblings.find((sibling) => sibling.name === 'catalogName')?.value.trim();
  return catalogs
    .filter((file) => catalogName === undefined || file.name === catalogName)
    .flatMap((file) =>
      file.entries.map((entry) => ({
        label: entry.name,
        kind: CompletionItemKind.Class,
        detail: `${entry.element.name} of ${file.name} — ${where(file)}`,
        documentation: entryDeclarations(file, entry.element).map((declaration) => `${declaration.name} = ${declaration.value}`).join('\n') || undefined,
        textEdit: { range, newText: entry.name },
      })),
    );
}

/** Hover on a ParameterAssignment's `parameterRef`: the entry's parameter, its default and the value this reference gives it. */
export function assignmentHover(workspace: Workspace, semantics: DocumentSemantics, offset: number): { markdown: string; start: number; end: number } | undefined {
  const resolution = catalogReferenceAt(semantics, offset);
  const assignment = resolution?.reference.assignments.find((candidate) => candidate.parameterRef && offset >= candidate.parameterRef.valueStart && offset <= candidate.parameterRef.valueEnd);
  const entry = resolution?.entry;
  if (!resolution || !assignment?.parameterRef || !entry) return undefined;
  const name = assignment.parameterRef.value.trim().replace(/^\$/, '');
  const declaration = entryDeclarations(entry.file, entry.element).find((candidate) => candidate.name === name);
  if (!declaration) return undefined;
  const value = entryParameterValue(semantics, resolution, declaration);
  const line = entry.file.model.document.lines.positionAt(declaration.element.start).line + 1;
  return {
    markdown: [
      `parameter **${name}** of ${entry.element.name} **${entry.name}** (catalog ${entry.file.name}): ${declaration.writtenType ?? 'untyped'}, default \`${declaration.value}\``,
      '',
      `this reference sets it to **${value.ok ? formatValue(value.value) : 'a value that cannot be evaluated'}**; declared in \`${displayRef(entry.file.ref, workspace.folders[0])}\` on line ${line}`,
    ].join('\n'),
    start: assignment.parameterRef.valueStart,
    end: assignment.parameterRef.valueEnd,
  };
}

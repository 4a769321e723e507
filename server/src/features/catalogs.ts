import { CompletionItem, CompletionItemKind } from 'vscode-languageserver/node';
import { TextDocument } from 'vscode-languageserver-textdocument';
import {
  CatalogEntry,
  CatalogFile,
  CatalogLoader,
  Declaration,
  DocumentSemantics,
  entryParameterValue,
  formatValue,
} from '../core/semantics';
import { displayRef, refId } from '../core/sources';
import { XmlAttribute, XmlElement } from '../core/xml';
import { Place } from '../analysis';
import { ValueContext } from '../core/cursor';
import { Target } from '../target';
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

/** The entry's declaration an assignment's `parameterRef` names. */
function assignedDeclaration(entry: CatalogEntry, parameterRef: XmlAttribute): Declaration | undefined {
  const name = parameterRef.value.trim().replace(/^\$/, '');
  return entryDeclarations(entry.file, entry.element).find((candidate) => candidate.name === name);
}

type CatalogReferenceTarget = Extract<Target, { kind: 'catalogReference' }>;

/**
 * Definition in a CatalogReference: `entryName` goes to the entry, `catalogName` to each catalog file
 * of that name, a ParameterAssignment's `parameterRef` to the entry's declaration. Undefined for an
 * assignment whose entry does not resolve.
 */
export function catalogDefinition(target: CatalogReferenceTarget): Place[] | undefined {
  const { resolution } = target;
  const { entry } = resolution;
  if (target.part === 'entryName') return entry ? [namePlace(entry.file, entry.element)] : [];
  if (target.part === 'catalogName') return resolution.catalogs.map((file) => namePlace(file, file.catalog));
  if (!entry) return undefined;
  const declaration = assignedDeclaration(entry, target.attribute);
  return declaration ? [namePlace(entry.file, declaration.element)] : [];
}

/** Every catalog file the document's CatalogLocations reach, each once. */
async function reachableCatalogs(workspace: Workspace, semantics: DocumentSemantics): Promise<CatalogFile[]> {
  const loader = new CatalogLoader(workspace.store);
  const files = new Map<string, CatalogFile>();
  for (const location of semantics.catalogs.locations) {
    for (const directory of location.directories)
      for (const file of await loader.allCatalogsIn(directory)) if (!files.has(refId(file.ref))) files.set(refId(file.ref), file);
  }
  return [...files.values()];
}

/** Completion of `catalogName` or `entryName` in a CatalogReference. */
export async function catalogCompletion(
  workspace: Workspace,
  semantics: DocumentSemantics,
  document: TextDocument,
  context: ValueContext,
  part: 'catalogName' | 'entryName',
): Promise<CompletionItem[]> {
  const range = { start: document.positionAt(context.valueStart), end: document.positionAt(context.valueEnd) };
  const catalogs = await reachableCatalogs(workspace, semantics);
  const where = (file: CatalogFile) => displayRef(file.ref, workspace.folders[0]);
  if (part === 'catalogName') {
    const seen = new Set<string>();
    return catalogs
      .filter((file) => file.name && !seen.has(file.name) && seen.add(file.name))
      .map((file) => ({
        label: file.name,
        kind: CompletionItemKind.Module,
        detail: `${file.entries.length} entries — ${where(file)}`,
        textEdit: { range, newText: file.name },
      }));
  }
  const catalogName = context.siblings.find((sibling) => sibling.name === 'catalogName')?.value.trim();
  return catalogs
    .filter((file) => catalogName === undefined || file.name === catalogName)
    .flatMap((file) =>
      file.entries.map((entry) => ({
        label: entry.name,
        kind: CompletionItemKind.Class,
        detail: `${entry.element.name} of ${file.name} — ${where(file)}`,
        documentation:
          entryDeclarations(file, entry.element)
            .map((declaration) => `${declaration.name} = ${declaration.value}`)
            .join('\n') || undefined,
        textEdit: { range, newText: entry.name },
      })),
    );
}

/** Hover on a ParameterAssignment's `parameterRef`: the entry's parameter, its default and the value this reference gives it. */
export function assignmentHover(
  workspace: Workspace,
  semantics: DocumentSemantics,
  target: CatalogReferenceTarget,
): { markdown: string; start: number; end: number } | undefined {
  const { resolution, attribute: parameterRef } = target;
  const entry = resolution.entry;
  if (target.part !== 'parameterRef' || !entry) return undefined;
  const name = parameterRef.value.trim().replace(/^\$/, '');
  const declaration = assignedDeclaration(entry, parameterRef);
  if (!declaration) return undefined;
  const value = entryParameterValue(semantics, resolution, declaration);
  const line = entry.file.model.document.lines.positionAt(declaration.element.start).line + 1;
  return {
    markdown: [
      `parameter **${name}** of ${entry.element.name} **${entry.name}** (catalog ${entry.file.name}): ${declaration.writtenType ?? 'untyped'}, default \`${declaration.value}\``,
      '',
      `this reference sets it to **${value.ok ? formatValue(value.value) : 'a value that cannot be evaluated'}**; declared in \`${displayRef(entry.file.ref, workspace.folders[0])}\` on line ${line}`,
    ].join('\n'),
    start: parameterRef.valueStart,
    end: parameterRef.valueEnd,
  };
}

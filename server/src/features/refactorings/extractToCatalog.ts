import * as fs from 'node:fs/promises';
import * as path from 'node:path';
import { CodeActionKind } from 'vscode-languageserver/node';
import { CatalogFileText, catalogCandidate, extractToCatalog } from '../../core/refactor/extractCatalog';
import { RefactoringRefusal } from '../../core/refactor/refusal';
import { diskRef, nodeFileSystem, refId } from '../../core/sources';
import { elementAt, XmlElement } from '../../core/xml';
import { fileUri } from '../../uris';
import { Workspace } from '../../workspace';
import { cannotCreateFiles, createAndEdit, FileChange, Refactoring } from './refactoring';

export const EXTRACT_TO_CATALOG_KIND = `${CodeActionKind.RefactorExtract}.catalog`;

/** The catalog files of a directory as the editor has them (open documents' text, else the disk's). */
async function catalogsIn(workspace: Workspace, directory: string): Promise<(CatalogFileText & { version?: number; uri: string })[]> {
  let names: string[];
  try {
    names = (await fs.readdir(directory)).filter((name) => name.toLowerCase().endsWith('.xosc')).sort();
  } catch {
    return [];
  }
  const files: (CatalogFileText & { version?: number; uri: string })[] = [];
  for (const name of names) {
    const file = path.join(directory, name);
    const open = workspace.documents.get(refId(diskRef(file)));
    const text = open ? open.document.getText() : await fs.readFile(file, 'utf8').catch(() => undefined);
    if (text !== undefined && /<Catalog[\s>]/.test(text))
      files.push({ path: file, text, version: open?.document.version, uri: open?.uri ?? fileUri(file).toString() });
  }
  return files;
}

/** The element whose start tag holds the offset, when it can move into a catalog. */
function candidateAt(element: XmlElement | undefined, start: number, end: number): XmlElement | undefined {
  return catalogCandidate(element) && start >= element.start && end <= element.startTagEnd ? element : undefined;
}

/**
 * *Extract to catalog…* on the start tag of an entity's Vehicle, Pedestrian, MiscObject or Controller,
 * or of a Maneuver: the entry into a catalog file (existing or new), a CatalogReference in its place.
 */
export const extractToCatalogRefactoring: Refactoring = {
  kind: EXTRACT_TO_CATALOG_KIND,
  async actions(target) {
    if (target.ref.entries.length > 0) return [];
    const element = candidateAt(elementAt(target.model.document, target.start), target.start, target.end);
    if (!element) return [];
    const title = `Extract '${element.name}' to a catalog…`;
    const refused = cannotCreateFiles(target.client);
    if (refused) return [{ title, kind: EXTRACT_TO_CATALOG_KIND, disabled: { reason: refused } }];
    const found = new Map<string, CatalogFileText & { version?: number; uri: string }>();
    let extracted;
    try {
      extracted = await extractToCatalog({
        file: target.ref.disk,
        document: target.model.document,
        element,
        catalogsIn: async (directory) => {
          const files = await catalogsIn(target.workspace, directory);
          for (const file of files) found.set(file.path, file);
          return files;
        },
        exists: async (file) => (await nodeFileSystem.kind(file)) !== undefined || target.workspace.documents.has(refId(diskRef(file))),
      });
    } catch (error) {
      if (error instanceof RefactoringRefusal) return [{ title, kind: EXTRACT_TO_CATALOG_KIND, disabled: { reason: error.message } }];
      throw error;
    }
    const known = found.get(extracted.catalog.path);
    const catalogFile: FileChange = {
      uri: known?.uri ?? fileUri(extracted.catalog.path).toString(),
      create: extracted.catalog.create,
      text: extracted.catalog.create ? (extracted.catalog.text ?? '') : (known?.text ?? ''),
      edits: extracted.catalog.edits,
      version: known?.version,
    };
    const where = `${path.basename(extracted.catalog.path)}${extracted.reused ? ', an entry there already' : ''}`;
    return [
      {
        title: `${title.slice(0, -1)} (${extracted.catalogName}/${extracted.entryName} in ${where})`,
        kind: EXTRACT_TO_CATALOG_KIND,
        edit: createAndEdit(target, [catalogFile], extracted.edits),
      },
    ];
  },
};

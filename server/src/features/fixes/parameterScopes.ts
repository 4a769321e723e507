import { ParameterScopes, ParameterTemplate } from '../../core/diagnostics';
import { FlatSource } from '../../core/flatten';
import { Declaration, DocumentSemantics, scopeAt } from '../../core/semantics';
import { displayRef } from '../../core/sources';
import { XmlElement } from '../../core/xml';
import { Workspace } from '../../workspace';
import { FixDocument } from './fix';

/*
 * What a fix that declares a parameter reads of the file's analysis (core/diagnostics/undeclaredParameter.ts
 * computes the edit): the scopes around the problem, and a same-named declaration of a source the file
 * imports, or of this file's other scopes.
 */

function templateOf(declaration: Declaration, from: string): ParameterTemplate {
  return { type: declaration.writtenType ?? 'string', value: declaration.value, from };
}

/** The source's declaration of a name: a simple scenario the file imports, else another scope of the file. */
function sourceTemplate(
  source: FlatSource,
  semantics: DocumentSemantics,
  name: string,
  folder: string | undefined,
): ParameterTemplate | undefined {
  for (const link of source.links) {
    const declaration = link.source?.semantics?.model.root?.byName.get(name);
    if (declaration && link.source) return templateOf(declaration, displayRef(link.source.ref, folder));
  }
  const elsewhere = semantics.model.declarations.find((declaration) => declaration.name === name && declaration.kind === 'parameter');
  return elsewhere
    ? templateOf(elsewhere, `line ${semantics.model.document.lines.positionAt(elsewhere.element.start).line + 1}`)
    : undefined;
}

/** The parameter scopes around the diagnostic, from the analysis of its file; undefined where the file has none. */
export async function parameterScopesOf(workspace: Workspace, target: FixDocument): Promise<ParameterScopes | undefined> {
  const source = await workspace.source(target.ref);
  const semantics = source.semantics;
  if (!semantics) return undefined;
  const scopes: XmlElement[] = [];
  for (let scope = scopeAt(semantics, target.document.offsetAt(target.diagnostic.range.start)); scope; scope = scope.parent)
    scopes.push(scope.element);
  const folder = workspace.folders[0];
  return {
    scopes,
    root: semantics.model.root?.element,
    declarationOf: (name) => sourceTemplate(source, semantics, name, folder),
  };
}

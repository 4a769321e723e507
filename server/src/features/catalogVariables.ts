import { Diagnostic, DiagnosticRelatedInformation } from 'vscode-languageserver/node';
import { Problem, problemData } from '../core/problems';
import { resolveName } from '../core/semantics';
import { refId, SourceRef } from '../core/sources';
import { Workspace } from '../workspace';

/**
 * A variable a catalog entry uses resolves against the scenarios that reference the entry (issue 18):
 * the catalog's note lists each of them, at its CatalogReference, saying whether it declares the variable.
 */
export async function referencingScenarios(
  workspace: Workspace,
  catalogRef: SourceRef,
  problem: Problem,
): Promise<DiagnosticRelatedInformation[]> {
  const data = problemData(problem, 'undeclared-variable');
  if (problem.severity !== 'information' || data?.entry === undefined) return [];
  const catalogId = refId(catalogRef);
  const related: DiagnosticRelatedInformation[] = [];
  // The reverse index names the candidates: no file of the workspace is read only to be ruled out.
  for (const ref of await workspace.catalogReferrers(data.entry)) {
    if (refId(ref) === catalogId) continue;
    const text = await workspace.text(ref);
    if (text === undefined || !text.includes(data.entry) || !/<CatalogReference\b/.test(text)) continue;
    const semantics = (await workspace.source(ref)).semantics;
    if (!semantics) continue;
    for (const resolution of semantics.catalogs.references) {
      const entry = resolution.entry;
      if (!entry || entry.name !== data.entry || refId(entry.file.ref) !== catalogId) continue;
      const element = resolution.reference.element;
      const declares =
        semantics.model.variables.has(data.variable) ||
        resolveName(semantics.model.scopeOf(element), data.variable, undefined) !== undefined;
      const place = resolution.reference.entryNameAttribute;
      const range = semantics.model.document.lines.range(place?.valueStart ?? element.start, place?.valueEnd ?? element.nameEnd);
      related.push({
        location: { uri: workspace.uriOf(ref), range },
        message: declares ? `declares variable '${data.variable}'` : `does not declare variable '${data.variable}' (an error there)`,
      });
    }
  }
  return related;
}

/** Adds the referencing scenarios to the notes of a catalog's entry variables. */
export async function addReferencingScenarios(
  workspace: Workspace,
  catalogRef: SourceRef,
  problem: Problem,
  diagnostic: Diagnostic,
): Promise<void> {
  const related = await referencingScenarios(workspace, catalogRef, problem);
  if (related.length > 0) diagnostic.relatedInformation = [...(diagnostic.relatedInformation ?? []), ...related];
}

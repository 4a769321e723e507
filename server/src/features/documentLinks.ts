import { DocumentLink } from 'vscode-languageserver/node';
import { resolvedTarget } from '../analysis';
import { displayRef, SourceRef } from '../core/sources';
import { Workspace } from '../workspace';

/**
 * A link on each scenarioFileName that resolves, to the file it names: the editor underlines a
 * link below the text, so the underscores of a name stay visible (a grammar's underline hid them).
 */
export async function documentLinks(workspace: Workspace, ref: SourceRef): Promise<DocumentLink[]> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return [];
  const links: DocumentLink[] = [];
  for (const link of source.links) {
    const value = link.info.fileAttribute;
    const target = resolvedTarget(link.resolution);
    if (!value || !target || value.valueEnd <= value.valueStart) continue;
    links.push({
      range: model.document.lines.range(value.valueStart, value.valueEnd),
      target: workspace.uriOf(target),
      tooltip: `Open ${displayRef(target, workspace.folders[0])}`,
    });
  }
  return links;
}

import { refId } from '../core/sources';
import { parameterRenameRange } from '../features/parameters';
import { entryParameterRenameRange } from '../features/catalogParameters';
import { targetAt } from '../features/references';
import { openDocument, request, ServerContext } from './context';

/** `textDocument/prepareRename`: ManeuverGroup names (declarations or references) and parameters can be renamed. */
export function register(context: ServerContext): void {
  const { workspace } = context;
  context.connection.onPrepareRename(
    request(context, 'textDocument/prepareRename', async (params) => {
      const open = await openDocument(context, params.textDocument.uri);
      if (!open) return null;
      const offset = open.document.offsetAt(params.position);
      const semantics = (await workspace.source(open.ref)).semantics;
      const parameter = semantics ? (parameterRenameRange(semantics, offset) ?? (await entryParameterRenameRange(workspace, semantics, offset))) : undefined;
      if (parameter) return { range: { start: open.document.positionAt(parameter.start), end: open.document.positionAt(parameter.end) }, placeholder: parameter.name };
      const subject = await targetAt(workspace, open.ref, offset);
      if (!subject || subject.kind !== 'group') return null;
      if (refId(subject.ref) === refId(open.ref)) return { range: subject.declaration.range, placeholder: subject.name };
      const source = await workspace.source(open.ref);
      const lines = source.original?.document.lines;
      const text = source.original?.document.text ?? '';
      // The reference under the cursor: the whole maneuverGroupName value.
      let start = offset;
      let end = offset;
      while (start > 0 && !/["']/.test(text[start - 1])) start--;
      while (end < text.length && !/["']/.test(text[end])) end++;
      return lines ? { range: lines.range(start, end), placeholder: text.slice(start, end) } : null;
    }),
  );
}

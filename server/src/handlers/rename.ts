import { LSPErrorCodes, ResponseError } from 'vscode-languageserver/node';
import { renameGroup, targetAt } from '../features/references';
import { renameParameter } from '../features/parameters';
import { renameEntryParameter } from '../features/catalogParameters';
import { checkCancelled, openDocument, request, ServerContext } from './context';

const METHOD = 'textDocument/rename';

/** `textDocument/rename`: renames a ManeuverGroup with every reference to it, across files. */
export function register(context: ServerContext): void {
  const { workspace } = context;
  context.connection.onRenameRequest(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      checkCancelled(token, METHOD);
      const open = await openDocument(context, params.textDocument.uri);
      const semantics = open ? (await workspace.source(open.ref)).semantics : undefined;
      const entryEdit = open && semantics ? await renameEntryParameter(workspace, semantics, open.document.offsetAt(params.position), params.newName) : undefined;
      if (entryEdit) return entryEdit;
      const parameterEdit = open && semantics ? renameParameter(workspace, semantics, open.document.offsetAt(params.position), params.newName) : undefined;
      if (parameterEdit) return parameterEdit;
      const subject = open ? await targetAt(workspace, open.ref, open.document.offsetAt(params.position)) : undefined;
      if (!subject || subject.kind !== 'group') throw new ResponseError(LSPErrorCodes.RequestFailed, 'only ManeuverGroup and parameter names can be renamed');
      if (subject.ref.entries.length > 0 && !workspace.editablePackages) {
        throw new ResponseError(LSPErrorCodes.RequestFailed, 'the group is inside a .mosc package, and this editor cannot write into packages');
      }
      checkCancelled(token, METHOD);
      const newName = params.newName.includes('.') ? params.newName.slice(params.newName.lastIndexOf('.') + 1) : params.newName;
      return renameGroup(workspace, subject, newName);
    }),
  );
}

import { placesToLocations, targetAt, usagesOf } from '../features/references';
import { checkCancelled, openDocument, request, ServerContext } from './context';

const METHOD = 'textDocument/references';

/** `textDocument/references`: every use of a group or file across the indexed workspace. */
export function register(context: ServerContext): void {
  context.connection.onReferences(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      checkCancelled(token, METHOD);
      const open = await openDocument(context, params.textDocument.uri);
      const subject = open ? await targetAt(context.workspace, open.ref, open.document.offsetAt(params.position)) : undefined;
      if (!subject) return [];
      checkCancelled(token, METHOD);
      const places = (await usagesOf(context.workspace, subject)).map((usage) => usage.place);
      checkCancelled(token, METHOD);
      if (params.context.includeDeclaration) places.unshift(subject.declaration);
      return placesToLocations(context.workspace, places);
    }),
  );
}

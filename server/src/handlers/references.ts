import { placesToLocations, targetAt, usagesOf } from '../features/references';
import { parameterReferences } from '../features/parameters';
import { entryParameterReferences } from '../features/catalogParameters';
import { toLocations } from '../features/definition';
import { checkCancelled, openDocument, request, ServerContext } from './context';

const METHOD = 'textDocument/references';

/** `textDocument/references`: every use of a group or file across the indexed workspace. */
export function register(context: ServerContext): void {
  context.connection.onReferences(
    request(context, METHOD, async (params, token) => {
      await context.indexed;
      checkCancelled(token, METHOD);
      const open = await openDocument(context, params.textDocument.uri);
      const semantics = open ? (await context.workspace.source(open.ref)).semantics : undefined;
      const offset = open?.document.offsetAt(params.position) ?? 0;
      // A catalog entry's parameter is also set from other files (CatalogReference ParameterAssignments).
      const entryPlaces = open && semantics ? await entryParameterReferences(context.workspace, semantics, offset, params.context.includeDeclaration) : undefined;
      if (entryPlaces) return toLocations(context.workspace, entryPlaces);
      const parameterPlaces = open && semantics ? parameterReferences(semantics, open.document.offsetAt(params.position), params.context.includeDeclaration) : undefined;
      if (parameterPlaces) return toLocations(context.workspace, parameterPlaces);
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

import { CodeActionKind } from 'vscode-languageserver/node';
import { INSERT_LIBRARY_MODULE_COMMAND, InsertHereArguments } from '../../../../common/src/libraryProtocol';
import { insertionPointAt } from '../../core/libraryInsert';
import { Refactoring } from './refactoring';

export const INSERT_LIBRARY_MODULE_KIND = `${CodeActionKind.Refactor}.insertLibraryModule`;

const TITLE = 'Insert library module here…';

/**
 * *Insert library module here…* on an Act or one of its ManeuverGroups: a command of the client's, which picks the
 * module and asks `modular2simple/libraryInsert` for the edit at this position, as *Insert into Main* does.
 */
export const insertLibraryModuleRefactoring: Refactoring = {
  kind: INSERT_LIBRARY_MODULE_KIND,
  async actions(target) {
    // A file inside a package is edited through its package, which the insert does not write.
    // A client without the command (another editor) has nothing to run: it gets no action.
    if (target.ref.entries.length > 0 || !target.client.libraryPicker) return [];
    if (!insertionPointAt(target.model.document, target.start)) return [];
    const args: InsertHereArguments = { main: target.uri, position: target.document.positionAt(target.start) };
    return [
      {
        title: TITLE,
        kind: INSERT_LIBRARY_MODULE_KIND,
        command: { title: TITLE, command: INSERT_LIBRARY_MODULE_COMMAND, arguments: [args] },
      },
    ];
  },
};

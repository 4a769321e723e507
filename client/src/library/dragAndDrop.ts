import * as vscode from 'vscode';
import type { LibraryModuleSummary } from '../../../common/src/libraryProtocol';
import type { CommandReporter } from '../commands';
import type { ServerCommandClient } from '../languageClient';
import { MainTracker, prepareInsert } from './insert';
import type { LibraryNode } from './view';

/** What a module dragged from the Scenario Library view carries: its name, `library:NAME`. */
export const LIBRARY_MODULE_MIME = 'application/vnd.modular2simple.library-module';

const TITLE = 'Drop library module';

/** The Scenario Library view's drag: a module node puts its `library:NAME` in the drag's data (groups and problems carry nothing). */
export class LibraryDragController implements vscode.TreeDragAndDropController<LibraryNode> {
  readonly dragMimeTypes = [LIBRARY_MODULE_MIME];
  readonly dropMimeTypes: readonly string[] = [];

  handleDrag(source: readonly LibraryNode[], dataTransfer: vscode.DataTransfer): void {
    const module = source.find((node) => node.kind === 'module');
    if (module) dataTransfer.set(LIBRARY_MODULE_MIME, new vscode.DataTransferItem(`library:${module.module.name}`));
  }
}

/**
 * A module dropped onto an Act or a ManeuverGroup of an open main: the same request and questions as *Insert library
 * module here…* at the drop position (every key at its default, the roles played by the main's entities of their
 * names, or asked), given to VS Code as the drop's edit. A drop elsewhere in the main is refused with the server's
 * reason; a drop whose module the view no longer lists, likewise.
 */
export class LibraryDropProvider implements vscode.DocumentDropEditProvider {
  constructor(
    private readonly server: ServerCommandClient,
    private readonly reporter: CommandReporter,
    private readonly tracker: MainTracker,
    private readonly moduleNamed: (name: string) => Promise<LibraryModuleSummary | undefined>,
  ) {}

  async provideDocumentDropEdits(
    document: vscode.TextDocument,
    position: vscode.Position,
    dataTransfer: vscode.DataTransfer,
    token: vscode.CancellationToken,
  ): Promise<vscode.DocumentDropEdit | undefined> {
    const item = dataTransfer.get(LIBRARY_MODULE_MIME);
    if (!item) return undefined;
    const name = (await item.asString()).trim().replace(/^library:/, '');
    try {
      const module = await this.moduleNamed(name);
      if (!module) throw new Error(`the Scenario Library lists no module '${name}' (Refresh the view?)`);
      const inserted = await prepareInsert(
        this.server,
        this.tracker,
        module,
        { main: document.uri, position: { line: position.line, character: position.character } },
        TITLE,
      );
      if (!inserted || token.isCancellationRequested) return undefined;
      // The group goes where the server says (after the group dropped on), not at the mouse: the whole edit is the additional one.
      const edit = new vscode.DocumentDropEdit('');
      edit.additionalEdit = inserted.edit;
      // VS Code applies it after this returns (or not, when another drop handler is picked): say what was offered.
      this.reporter.log(
        `${TITLE}: library:${module.name} as ${inserted.groupName} at line ${inserted.line + 1} of ${document.uri.toString()} (${inserted.cast})`,
      );
      return edit;
    } catch (error) {
      void this.reporter.failure(`${TITLE} library:${name}`, error);
      return undefined;
    }
  }
}

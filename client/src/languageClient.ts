import * as vscode from 'vscode';
import {
  CloseAction,
  LanguageClient,
  TransportKind,
  type ErrorHandler,
  type LanguageClientOptions,
  type ServerOptions,
} from 'vscode-languageclient/node';
import serverProcess from '../../common/src/languageServerProcess.json';
import type { WorkspaceEdit as LspWorkspaceEdit } from 'vscode-languageserver-protocol';
import {
  CheckInScenarioRunnerRequest,
  ExtractGroupRequest,
  ExportForCarlaRequest,
  FlattenToFileRequest,
  FlattenToTextRequest,
  NewScenarioRequest,
  PACKAGE_SCHEME,
  PackRequest,
  PreviewRequest,
  StructureRequest,
  type CheckInScenarioRunnerParams,
  type CheckInScenarioRunnerResult,
  type ExtractGroupParams,
  type ExtractGroupResult,
  type FlattenOptions,
  type FlattenTextResult,
  type NewScenarioResult,
  type PreviewResult,
  type StructureNode,
  type WriteResult,
} from '../../common/src/protocol';
import {
  LibraryInsertRequest,
  LibraryCollisionsRequest,
  type LibraryCollisionsParams,
  type LibraryCollisionsResult,
  LibraryModulesRequest,
  NewFromTemplateRequest,
  TemplatesRequest,
  type NewFromTemplateResult,
  type TemplateSummary,
  type LibraryInsertParams,
  type LibraryInsertResult,
  type LibraryListingResult,
} from '../../common/src/libraryProtocol';
import { resolveScenarioPaths } from './configuration';
import { formattingMiddleware } from './formatEdits';
import { whileRunning } from './requestGate';
import type { ServerLifecycle } from './serverLifecycle';

export const LANGUAGE_ID = 'xosc';
export const CONFIGURATION_SECTION = 'modular2simple';

/**
 * Starts the bundled language server (dist/server.js) over node IPC for `.xosc` files, on disk and inside packages.
 * `closing`: whether the window is closing, when the connection ending is expected and the server is not restarted.
 */
export function createLanguageClient(
  context: vscode.ExtensionContext,
  afterChangeSent: () => void = () => undefined,
  closing: () => boolean = () => false,
): LanguageClient {
  const module = context.asAbsolutePath('dist/server.js');
  // V8's young generation capped at 4 MB per semi-space (16 by default): it never shrinks once grown, and at rest
  // after big edits it was 32 of the server's 164 MB; edits cost no more CPU (docs/benchmarks.md). The benches read the same file.
  const { execArgv } = serverProcess;
  const serverOptions: ServerOptions = {
    run: { module, transport: TransportKind.ipc, options: { execArgv } },
    debug: { module, transport: TransportKind.ipc, options: { execArgv: [...execArgv, '--nolazy', '--inspect=6019'] } },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [
      { scheme: 'file', language: LANGUAGE_ID },
      { scheme: PACKAGE_SCHEME, language: LANGUAGE_ID },
      { scheme: 'untitled', language: LANGUAGE_ID },
    ],
    // No `synchronize`: the server registers for configuration changes and file events itself.
    // Files inside packages open and save through the mosc: file system, so edits may reach them.
    // Extract to a simple scenario runs our command, which shows a pick list of attributes first.
    initializationOptions: { packageFileSystem: true, extractPicker: true, libraryPicker: true },
    // The client's own handler restarts a server whose connection closed; not while the window closes with it.
    errorHandler: {
      error: (error, message, count) => defaultHandler().error(error, message, count),
      closed: () => (closing() ? { action: CloseAction.DoNotRestart, handled: true } : defaultHandler().closed()),
    },
    middleware: {
      ...whileRunning(() => client.isRunning() && !closing()),
      ...formattingMiddleware,
      // Views that show the server's answers (the preview, the structure) ask again once the server has the edit.
      didChange: async (event, next) => {
        await next(event);
        afterChangeSent();
      },
      workspace: {
        // The setting is resource-scoped: relative entries are resolved against the folder asked about.
        configuration: async (params, token, next) => {
          const answers = await next(params, token);
          if (!Array.isArray(answers)) return answers;
          return answers.map((answer: unknown, index) => {
            const scope = params.items[index]?.scopeUri;
            const folder = scope ? vscode.workspace.getWorkspaceFolder(vscode.Uri.parse(scope)) : vscode.workspace.workspaceFolders?.[0];
            return folder?.uri.scheme === 'file' ? resolveScenarioPaths(answer, folder.uri.fsPath) : answer;
          });
        },
        didChangeWatchedFile: async (event, next) => {
          await next(event);
          afterChangeSent();
        },
      },
    },
  };
  const client = new LanguageClient(CONFIGURATION_SECTION, 'Modular2Simple Language Server', serverOptions, clientOptions);
  let fallback: ErrorHandler | undefined;
  const defaultHandler = (): ErrorHandler => (fallback ??= client.createDefaultErrorHandler());
  return client;
}

/** The server's custom requests (common/src/protocol.ts), starting the client first when needed. */
export class ServerCommandClient {
  constructor(
    private readonly client: LanguageClient,
    private readonly lifecycle: ServerLifecycle,
  ) {}

  /** The client once its server runs (started again after a crash; refused while the window closes). */
  async running(): Promise<LanguageClient> {
    await this.lifecycle.running();
    return this.client;
  }

  async flattenToText(uri: vscode.Uri, options: FlattenOptions = {}): Promise<FlattenTextResult> {
    return (await this.running()).sendRequest(FlattenToTextRequest, { uri: uri.toString(), options });
  }

  /** The scenario exported and loaded by ScenarioRunner's own code (the harness shipped with the extension). */
  async checkInScenarioRunner(params: CheckInScenarioRunnerParams, token?: vscode.CancellationToken): Promise<CheckInScenarioRunnerResult> {
    return (await this.running()).sendRequest(CheckInScenarioRunnerRequest, params, token);
  }

  /** Writes the flattened scenario; an existing output is replaced (the caller asked the user first). */
  /** `outsideWorkspace`: the user agreed to write outside the workspace (the server asks for that first). */
  async exportForCarla(
    input: vscode.Uri,
    outputPath: string,
    token?: vscode.CancellationToken,
    outsideWorkspace = false,
  ): Promise<WriteResult> {
    return (await this.running()).sendRequest(
      ExportForCarlaRequest,
      { uri: input.toString(), outputPath, ...(outsideWorkspace ? { outsideWorkspace } : {}) },
      token,
    );
  }

  async flattenToFile(
    input: vscode.Uri,
    outputPath: string,
    options: FlattenOptions,
    token?: vscode.CancellationToken,
    outsideWorkspace = false,
  ): Promise<WriteResult> {
    return (await this.running()).sendRequest(
      FlattenToFileRequest,
      { uri: input.toString(), outputPath, options, ...(outsideWorkspace ? { outsideWorkspace } : {}) },
      token,
    );
  }

  /** The live preview's text and line map, from the server's flattener. */
  async preview(uri: vscode.Uri): Promise<PreviewResult> {
    return (await this.running()).sendRequest(PreviewRequest, { uri: uri.toString() });
  }

  async pack(inputs: vscode.Uri[], outputPath: string, token?: vscode.CancellationToken, selfContained = false): Promise<WriteResult> {
    return (await this.running()).sendRequest(
      PackRequest,
      { inputs: inputs.map((input) => input.toString()), outputPath, ...(selfContained ? { selfContained } : {}) },
      token,
    );
  }

  /** Extract to a simple scenario with the attributes chosen: the edit to apply. */
  async extractGroup(params: ExtractGroupParams): Promise<ExtractGroupResult> {
    return (await this.running()).sendRequest(ExtractGroupRequest, params);
  }

  /** A server's WorkspaceEdit as the editor's. */
  async workspaceEdit(edit: LspWorkspaceEdit): Promise<vscode.WorkspaceEdit> {
    return (await this.running()).protocol2CodeConverter.asWorkspaceEdit(edit);
  }

  async structure(uri: vscode.Uri, token?: vscode.CancellationToken): Promise<StructureNode | null> {
    return (await this.running()).sendRequest(StructureRequest, { uri: uri.toString() }, token);
  }

  /** The text of a new main scenario at `scenario` with an ego on `roadNetwork`; the caller writes it. */
  async newScenario(scenario: vscode.Uri, roadNetwork: vscode.Uri): Promise<NewScenarioResult> {
    return (await this.running()).sendRequest(NewScenarioRequest, { scenario: scenario.toString(), roadNetwork: roadNetwork.toString() });
  }

  /** The modules of the scenario libraries (the user's folders, then the built-in one) and what could not be read. */
  async libraryModules(): Promise<LibraryListingResult> {
    return (await this.running()).sendRequest(LibraryModulesRequest, {});
  }

  /** Insert into main: the questions to ask, or the edit once they are answered. */
  async libraryInsert(params: LibraryInsertParams): Promise<LibraryInsertResult> {
    return (await this.running()).sendRequest(LibraryInsertRequest, params);
  }

  /** After an insert: the main run headless in esmini, and which of its scripted actors touch. */
  async libraryCollisions(params: LibraryCollisionsParams): Promise<LibraryCollisionsResult> {
    return (await this.running()).sendRequest(LibraryCollisionsRequest, params);
  }

  /** The built-in templates, for New Scenario from Template. */
  async templates(): Promise<TemplateSummary[]> {
    return (await this.running()).sendRequest(TemplatesRequest, {});
  }

  /** The files of a new scenario from a template; the caller writes them. */
  async newFromTemplate(template: string, scenario: vscode.Uri): Promise<NewFromTemplateResult> {
    return (await this.running()).sendRequest(NewFromTemplateRequest, { template, scenario: scenario.toString() });
  }
}

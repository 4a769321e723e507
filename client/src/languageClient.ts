import * as vscode from 'vscode';
import { LanguageClient, TransportKind, type LanguageClientOptions, type ServerOptions } from 'vscode-languageclient/node';
import {
  FlattenToFileRequest,
  FlattenToTextRequest,
  PACKAGE_SCHEME,
  PackRequest,
  StructureRequest,
  type FlattenTextResult,
  type StructureNode,
  type WriteResult,
} from '../../server/src/protocol';

export const LANGUAGE_ID = 'xosc';
export const CONFIGURATION_SECTION = 'modular2simple';

/** Starts the bundled language server (dist/server.js) over node IPC for `.xosc` files, on disk and inside packages. */
export function createLanguageClient(context: vscode.ExtensionContext): LanguageClient {
  const module = context.asAbsolutePath('dist/server.js');
  const serverOptions: ServerOptions = {
    run: { module, transport: TransportKind.ipc },
    debug: { module, transport: TransportKind.ipc, options: { execArgv: ['--nolazy', '--inspect=6019'] } },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [
      { scheme: 'file', language: LANGUAGE_ID },
      { scheme: PACKAGE_SCHEME, language: LANGUAGE_ID },
      { scheme: 'untitled', language: LANGUAGE_ID },
    ],
    // No `synchronize`: the server registers for configuration changes and file events itself.
    // Files inside packages open and save through the mosc: file system, so edits may reach them.
    initializationOptions: { packageFileSystem: true },
  };
  return new LanguageClient(CONFIGURATION_SECTION, 'Modular2Simple Language Server', serverOptions, clientOptions);
}

/** The server's custom requests (server/src/protocol.ts), starting the client first when needed. */
export class ServerCommandClient {
  constructor(private readonly client: LanguageClient) {}

  private async started(): Promise<LanguageClient> {
    if (!this.client.isRunning()) await this.client.start();
    return this.client;
  }

  async flattenToText(uri: vscode.Uri): Promise<FlattenTextResult> {
    return (await this.started()).sendRequest(FlattenToTextRequest, { uri: uri.toString() });
  }

  /** Writes the flattened scenario; an existing output is replaced (the caller asked the user first). */
  /** `outsideWorkspace`: the user agreed to write outside the workspace (the server asks for that first). */
  async flattenToFile(input: vscode.Uri, outputPath: string, token?: vscode.CancellationToken, outsideWorkspace = false): Promise<WriteResult> {
    return (await this.started()).sendRequest(FlattenToFileRequest, { uri: input.toString(), outputPath, ...(outsideWorkspace ? { outsideWorkspace } : {}) }, token);
  }

  async pack(inputs: vscode.Uri[], outputPath: string, token?: vscode.CancellationToken): Promise<WriteResult> {
    return (await this.started()).sendRequest(PackRequest, { inputs: inputs.map((input) => input.toString()), outputPath }, token);
  }

  async structure(uri: vscode.Uri, token?: vscode.CancellationToken): Promise<StructureNode | null> {
    return (await this.started()).sendRequest(StructureRequest, { uri: uri.toString() }, token);
  }
}

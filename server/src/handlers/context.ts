import { CancellationToken, Connection, ErrorCodes, LSPErrorCodes, ResponseError } from 'vscode-languageserver/node';
import { OpenDocument } from '../documents';
import { DiagnosticsScheduler } from '../features/diagnostics';
import { EsminiRuns } from '../features/esminiRun';
import { ClientEdits } from '../features/refactorings';
import { RoadNetworkCache } from '../features/scene';
import { IdleCollector } from '../idleCollector';
import { OutsideFolderWatchers } from '../features/outsideFolderWatchers';
import { Workspace } from '../workspace';

/** What every handler module shares: the workspace and its services, created once per connection. */
export interface ServerContext {
  readonly connection: Connection;
  readonly workspace: Workspace;
  readonly diagnostics: DiagnosticsScheduler;
  readonly idle: IdleCollector;
  /** Watchers for the folders outside the workspace that open documents read from. */
  readonly outsideWatchers: OutsideFolderWatchers;
  /** The sampled road networks the bird's-eye view drew last. */
  readonly roads: RoadNetworkCache;
  /** This server's esmini runs, whose folders it removes. */
  readonly esminiRuns: EsminiRuns;
  /** What the client said it can do, filled in by `initialize`. */
  readonly client: { canConfigure: boolean; canWatch: boolean; foldersChange: boolean; edits: ClientEdits };
  /** Resolves once the first workspace index is built (immediately before `initialized`). */
  indexed: Promise<void>;
}

/** The open scenario document a request is about; undefined when the URI is not open or not a scenario. */
export function openDocument(context: ServerContext, uri: string): Promise<OpenDocument | undefined> {
  return context.workspace.documents.atUri(uri);
}

/** The error a cancelled request answers with (LSP RequestCancelled). */
export function cancelled(method: string): ResponseError<void> {
  return new ResponseError(LSPErrorCodes.RequestCancelled, `${method} was cancelled`);
}

/** Throws the RequestCancelled error when the client gave up on the request; call it between awaits. */
export function checkCancelled(token: CancellationToken | undefined, method: string): void {
  if (token?.isCancellationRequested) throw cancelled(method);
}

function describe(error: unknown): string {
  return error instanceof Error ? (error.stack ?? `${error.name}: ${error.message}`) : String(error);
}

/**
 * Wraps a request handler: a deliberate ResponseError reaches the client unchanged; any other
 * exception is logged with its stack and answered as an InternalError naming the method. A request
 * cancelled before it starts or while it runs is answered with RequestCancelled, except one that
 * `writes` files: its answer says what was written.
 */
export function request<P, R>(
  context: ServerContext,
  method: string,
  handler: (params: P, token: CancellationToken) => Promise<R>,
  options: { writes?: boolean } = {},
): (params: P, token: CancellationToken) => Promise<R> {
  return async (params, token) => {
    checkCancelled(token, method);
    try {
      const result = await handler(params, token);
      if (!options.writes) checkCancelled(token, method);
      return result;
    } catch (error) {
      if (error instanceof ResponseError) throw error;
      context.connection.console.error(`${method} failed: ${describe(error)}`);
      throw new ResponseError(ErrorCodes.InternalError, `${method} failed: ${error instanceof Error ? error.message : String(error)}`);
    }
  };
}

/** Runs the work of a notification, which has nobody to answer: a failure is logged with its stack. */
export function notification(context: ServerContext, method: string, run: () => Promise<void>): Promise<void> {
  return run().catch((error: unknown) => context.connection.console.error(`${method} failed: ${describe(error)}`));
}

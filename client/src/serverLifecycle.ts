/**
 * What of vscode-languageclient's LanguageClient the start and the shutdown use. Its contract (client.js, 10.x):
 * `start()` while starting or running joins that start; `stop()` while starting throws ("Client is not running
 * and can't be stopped"), and a request sent while it stops fails with "Starting server failed".
 */
export interface StartableClient {
  start(): Promise<void>;
  stop(timeout?: number): Promise<void>;
  isRunning(): boolean;
}

/** Refused: the window is closing, so no server is started for the request. */
export class WindowClosingError extends Error {
  constructor() {
    super('the window is closing: the language server is not started again');
    this.name = 'WindowClosingError';
  }
}

/** Where the lifecycle tells what happened: `failed` loudly (a stack, a message to the user), `note` in one line. */
export interface LifecycleReport {
  failed(error: unknown): void;
  note(message: string): void;
}

/**
 * The language server's start and its stop at window close, in one place: a start that fails because the window
 * closed meanwhile, a stop raced with a start under way, and a request that would start the server again while
 * the window closes are no failures; a start that fails otherwise is reported loudly.
 */
export class ServerLifecycle {
  private closingWindow = false;
  private startup: Promise<void> | undefined;

  constructor(
    private readonly client: StartableClient,
    private readonly report: LifecycleReport,
  ) {}

  /** Whether the window is closing (the extension deactivates): the connection closing then is expected. */
  get closing(): boolean {
    return this.closingWindow;
  }

  /** The start at activation: its failure is reported loudly, unless the window closed while the server started. */
  startAtActivation(): Promise<void> {
    return this.start().catch((error: unknown) => {
      if (this.closingWindow) this.report.note(`the window closed while the language server was starting (${messageOf(error)})`);
      else this.report.failed(error);
    });
  }

  /** Starts the server, or joins the start under way; refused once the window is closing. */
  start(): Promise<void> {
    if (this.closingWindow) return Promise.reject(new WindowClosingError());
    const startup = this.client.start();
    this.startup = startup;
    return startup;
  }

  /** Resolves once the server runs, starting it when it does not (after a crash); refused once the window is closing. */
  async running(): Promise<void> {
    if (this.closingWindow) throw new WindowClosingError();
    if (!this.client.isRunning()) await this.start();
  }

  /**
   * Stops the server as the window closes: a start under way is let finish first (stopping it then throws), a
   * server that never ran is left alone, and a stop that fails or times out is one line, not an error.
   */
  async close(): Promise<void> {
    this.closingWindow = true;
    await this.startup?.catch(() => undefined);
    // Requests VS Code sent in the batch that closes the window are past sendRequest's check of the state, between its
    // awaits: a stop now would fail each with "Starting server failed". A turn of the event loop lets them be sent.
    await new Promise<void>((resolve) => setImmediate(resolve));
    if (!this.client.isRunning()) return;
    try {
      await this.client.stop();
    } catch (error) {
      this.report.note(`stopping the language server as the window closed: ${messageOf(error)}`);
    }
  }
}

function messageOf(error: unknown): string {
  return error instanceof Error ? error.message : String(error);
}

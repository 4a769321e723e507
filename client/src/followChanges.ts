import * as vscode from 'vscode';

/**
 * Runs `refresh` shortly after the last of a burst of changes (edits the server has been sent,
 * saves, file events), and again once when changes arrive while it runs: a view that shows the
 * server's answers, such as the structure, follows them without a Refresh.
 */
export class ChangeFollower implements vscode.Disposable {
  private timer: NodeJS.Timeout | undefined;
  private running: Promise<void> | undefined;
  private again = false;

  constructor(
    private readonly refresh: () => Promise<void>,
    private readonly log: (message: string) => void,
    private readonly delayMs = 150,
  ) {}

  schedule(): void {
    if (this.timer) clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      this.timer = undefined;
      void this.run();
    }, this.delayMs);
  }

  private async run(): Promise<void> {
    if (this.running) {
      this.again = true;
      return;
    }
    this.running = (async () => {
      do {
        this.again = false;
        try {
          await this.refresh();
        } catch (error) {
          this.log(`refreshing after a change: ${(error as Error).stack ?? String(error)}`);
        }
      } while (this.again);
    })();
    await this.running;
    this.running = undefined;
  }

  dispose(): void {
    if (this.timer) clearTimeout(this.timer);
  }
}

import * as vscode from 'vscode';

/**
 * How long VS Code keeps a progress notification on screen at the least, counted in the window from its start
 * (src/vs/workbench/services/progress/browser/progressService.ts: `await Promise.all([timeout(800), promise])`
 * before it closes the notification).
 */
const WINDOW_SHOWS_PROGRESS_AT_LEAST_MS = 800;
/** Added to it for the window's timer, which fires late on a busy machine. */
const LATE_TIMER_MARGIN_MS = 200;

/**
 * A cancellable progress notification around `task` that has closed when the returned promise settles, so that the
 * message a command shows next (its result) is never shown beside a progress still offering Cancel. VS Code keeps a
 * progress on screen for 800 ms from when the window started it and an extension cannot see it close, so a task
 * that ends sooner ends the progress once that time has passed: a round trip to the window made after the progress
 * was started answers no earlier than the window started counting.
 */
export function withNotificationProgress<T>(
  title: string,
  task: (progress: vscode.Progress<{ message?: string; increment?: number }>, token: vscode.CancellationToken) => Promise<T>,
): Thenable<T> {
  return vscode.window.withProgress(
    { location: vscode.ProgressLocation.Notification, title, cancellable: true },
    async (progress, token) => {
      // Any request the window answers will do: its answer comes after the window has handled the progress's start.
      const windowStarted = Promise.resolve(vscode.commands.getCommands(true)).then(
        () => Date.now(),
        () => Date.now(),
      );
      try {
        return await task(progress, token);
      } finally {
        const closesAt = (await windowStarted) + WINDOW_SHOWS_PROGRESS_AT_LEAST_MS + LATE_TIMER_MARGIN_MS;
        const wait = closesAt - Date.now();
        if (wait > 0) await new Promise((resolve) => setTimeout(resolve, wait));
      }
    },
  );
}

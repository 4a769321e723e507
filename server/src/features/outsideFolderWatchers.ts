import * as path from 'node:path';
import { Connection, DidChangeWatchedFilesNotification, Disposable, FileSystemWatcher } from 'vscode-languageserver/node';
import { URI } from 'vscode-uri';
import { FlatSource } from '../core/flatten';
import { Workspace } from '../workspace';
import { insideFolders } from '../../../common/src/paths';

/** At most this many folders outside the workspace get watchers: a scenario reading from thousands of folders must not flood the client. */
export const MAX_OUTSIDE_FOLDERS = 256;
/** The files read from a folder that can change an analysis: scenarios and catalogs, packages, road files. Not recursive: the folder itself is what was read. */
export const OUTSIDE_FOLDER_PATTERN = '*.{xosc,mosc,xodr}';

/**
 * The disk folders an analysis read from: the folder of every file it depends on, and every catalog `Directory`
 * written in the file that exists on disk (it may hold no catalog yet: one appearing there changes the analysis).
 */
export function foldersRead(source: FlatSource): string[] {
  const folders = new Set(source.dependencies.map((dependency) => path.dirname(dependency.disk)));
  for (const location of source.semantics?.catalogs.locations ?? [])
    for (const directory of location.directories) if (!directory.packageRef) folders.add(directory.directory);
  return [...folders];
}

/** The folders read that no watched root holds, sorted, at most `limit` of them. */
export function foldersToWatch(read: Iterable<string>, roots: readonly string[], limit = MAX_OUTSIDE_FOLDERS): string[] {
  const outside = new Set<string>();
  for (const folder of read) if (!insideFolders(folder, roots)) outside.add(folder);
  return [...outside].sort().slice(0, limit);
}

/**
 * The watchers for files an analysis looked up outside its dependencies (an imported group's controller File, whose
 * existence decides a warning): any kind of file, which the workspace's registration of scenarios, packages and road
 * files does not cover. Each is watched from the nearest watched root holding it (a folder that exists, where the
 * file's own folder may not yet), else from its own folder; sorted, at most `limit`.
 */
export function filesToWatch(
  files: Iterable<string>,
  roots: readonly string[],
  limit = MAX_OUTSIDE_FOLDERS,
): { base: string; pattern: string }[] {
  const watched = new Map<string, { base: string; pattern: string }>();
  for (const file of files) {
    const root = roots.find((each) => insideFolders(file, [each]));
    const base = root ?? path.dirname(file);
    watched.set(file, { base, pattern: path.relative(base, file).split(path.sep).join('/') });
  }
  return [...watched.keys()]
    .sort()
    .slice(0, limit)
    .map((file) => watched.get(file) as { base: string; pattern: string });
}

/** Quiet time after the last analysis before the watched folders are worked out again: typing is not held up by it. */
const UPDATE_DELAY_MS = 300;

/**
 * Watchers for the folders outside the workspace that open scenarios read from (a catalog `Directory` such as
 * `../../shared/Catalogs`, an imported scenario, a catalog file there): the server's own registration covers the
 * workspace and the client's (`client/src/scenarioPathWatchers.ts`) the searched folders, so a catalog edited or
 * created there would otherwise leave stale diagnostics. Registered with relative patterns (LSP 3.17), replaced
 * as a whole when the set of folders changes; each event reaches `workspace/didChangeWatchedFiles` as any other.
 */
export class OutsideFolderWatchers {
  /** What is watched now (or being registered): each folder's and each file's pattern, sorted. */
  private watched: string[] = [];
  /** Whether the client registers watchers dynamically with relative patterns; set by `initialize`. */
  supported = false;
  private registration: Promise<Disposable | undefined> = Promise.resolve(undefined);
  private timer: NodeJS.Timeout | undefined;
  private disposed = false;
  /** The update running or last run: one at a time. */
  private queue: Promise<void> = Promise.resolve();

  constructor(
    private readonly connection: Connection,
    private readonly workspace: Workspace,
  ) {}

  /** Works the folders out again once analyses have been quiet for a moment: after diagnostics, after a close. */
  schedule(): void {
    if (!this.supported || this.disposed) return;
    if (this.timer) clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      this.timer = undefined;
      // Each update replaces the registration the one before made.
      this.queue = this.queue.then(() => this.update().catch((error: unknown) => this.failed(error)));
    }, UPDATE_DELAY_MS);
    this.timer.unref();
  }

  /** Watches exactly the folders outside the watched roots that the open documents' analyses read from, and the files they looked up. */
  private async update(): Promise<void> {
    if (this.disposed) return;
    const read = new Set<string>();
    const lookedUp = new Set<string>();
    for (const [, open] of this.workspace.documents) {
      const analysis = await this.workspace.analyze(open.ref);
      for (const folder of foldersRead(analysis.source)) read.add(folder);
      for (const file of analysis.lookedUp) lookedUp.add(file);
    }
    const folders = foldersToWatch(read, this.workspace.watchedRoots);
    const files = filesToWatch(lookedUp, this.workspace.watchedRoots);
    const watched = [
      ...folders.map((folder) => `${folder}/${OUTSIDE_FOLDER_PATTERN}`),
      ...files.map((file) => `${file.base}/${file.pattern}`),
    ];
    if (watched.length === this.watched.length && watched.every((each, index) => each === this.watched[index])) return;
    this.watched = watched;
    const previous = await this.registration;
    previous?.dispose();
    const watchers: FileSystemWatcher[] = [
      ...folders.map((folder) => ({ globPattern: { baseUri: URI.file(folder).toString(), pattern: OUTSIDE_FOLDER_PATTERN } })),
      ...files.map((file) => ({ globPattern: { baseUri: URI.file(file.base).toString(), pattern: file.pattern } })),
    ];
    this.registration =
      watchers.length === 0
        ? Promise.resolve(undefined)
        : this.connection.client.register(DidChangeWatchedFilesNotification.type, { watchers }).catch((error: unknown) => {
            // Registered again on the next update rather than believed watched.
            this.watched = [];
            this.failed(error);
            return undefined;
          });
    await this.registration;
  }

  /** On shutdown: no update starts any more, and one still running logs nothing to the closed connection. */
  dispose(): void {
    this.disposed = true;
    if (this.timer) clearTimeout(this.timer);
    this.timer = undefined;
  }

  private failed(error: unknown): void {
    if (this.disposed) return;
    this.connection.console.error(`watching folders outside the workspace failed: ${(error as Error).stack ?? String(error)}`);
  }
}

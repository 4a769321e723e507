import * as path from 'node:path';
import * as vscode from 'vscode';
import { PACKAGE_SCHEME } from '../../common/src/protocol';
import * as archive from './packageArchive';

/** `mosc:/abs/pkg.mosc/main.xosc` for an entry of the package stored at `/abs/pkg.mosc`. */
export function packageEntryUri(packageFile: vscode.Uri, entry: string): vscode.Uri {
  return vscode.Uri.from({ scheme: PACKAGE_SCHEME, path: path.posix.join(packageFile.path, entry) });
}

function toFileSystemError(error: unknown, uri: vscode.Uri): Error {
  if (!(error instanceof archive.PackageError)) return error instanceof Error ? error : new Error(String(error));
  switch (error.code) {
    case 'not-found':
      return vscode.FileSystemError.FileNotFound(uri);
    case 'exists':
      return vscode.FileSystemError.FileExists(uri);
    case 'broken':
      // Unavailable rather than NotFound: the archive exists but cannot be read, and must not be replaced.
      return vscode.FileSystemError.Unavailable(`${error.message}. Repair or rebuild the package (Pack into .mosc); it was not changed.`);
    case 'invalid':
      return vscode.FileSystemError.NoPermissions(error.message);
  }
}

/** The files inside `.mosc` packages as a file system, so that they open, edit and save in place. */
export class PackageFileSystem implements vscode.FileSystemProvider, vscode.Disposable {
  private readonly changes = new vscode.EventEmitter<vscode.FileChangeEvent[]>();
  readonly onDidChangeFile = this.changes.event;
  private readonly watchers = new Map<string, { watcher: vscode.FileSystemWatcher; uris: Set<string> }>();

  constructor(private readonly log: (message: string) => void) {}

  private async run<T>(uri: vscode.Uri, operation: () => Promise<T>): Promise<T> {
    try {
      return await operation();
    } catch (error) {
      if (error instanceof archive.PackageError && error.code === 'broken') this.log(`${uri.toString()}: ${error.message}`);
      throw toFileSystemError(error, uri);
    }
  }

  watch(uri: vscode.Uri): vscode.Disposable {
    // The archive on disk is what changes; report a change of it as a change of every watched entry.
    let disk: string | undefined;
    const key = uri.toString();
    void archive.locate(uri.path).then(
      (location) => {
        disk = location.disk;
        let entry = this.watchers.get(disk);
        if (!entry) {
          const folder = vscode.Uri.file(path.dirname(disk));
          const watcher = vscode.workspace.createFileSystemWatcher(new vscode.RelativePattern(folder, path.basename(disk)));
          const fire = (): void => {
            const current = this.watchers.get(location.disk);
            if (current)
              this.changes.fire(
                [...current.uris].map((watched) => ({ type: vscode.FileChangeType.Changed, uri: vscode.Uri.parse(watched) })),
              );
          };
          watcher.onDidChange(fire);
          watcher.onDidCreate(fire);
          watcher.onDidDelete(fire);
          entry = { watcher, uris: new Set() };
          this.watchers.set(disk, entry);
        }
        entry.uris.add(key);
      },
      () => undefined,
    );
    return new vscode.Disposable(() => {
      const entry = disk ? this.watchers.get(disk) : undefined;
      if (!entry || !disk) return;
      entry.uris.delete(key);
      if (entry.uris.size === 0) {
        entry.watcher.dispose();
        this.watchers.delete(disk);
      }
    });
  }

  stat(uri: vscode.Uri): Promise<vscode.FileStat> {
    return this.run(uri, async () => {
      const location = await archive.locate(uri.path);
      const entry = await archive.stat(location);
      return {
        type: entry.kind === 'file' ? vscode.FileType.File : vscode.FileType.Directory,
        ctime: entry.mtime,
        mtime: entry.mtime,
        size: entry.size,
      };
    });
  }

  readDirectory(uri: vscode.Uri): Promise<[string, vscode.FileType][]> {
    return this.run(uri, async () => {
      const children = await archive.listFolder(await archive.locate(uri.path));
      return children.map(([name, kind]): [string, vscode.FileType] => [
        name,
        kind === 'file' ? vscode.FileType.File : vscode.FileType.Directory,
      ]);
    });
  }

  readFile(uri: vscode.Uri): Promise<Uint8Array> {
    return this.run(uri, async () => archive.readEntry(await archive.locate(uri.path)));
  }

  writeFile(uri: vscode.Uri, content: Uint8Array, options: { readonly create: boolean; readonly overwrite: boolean }): Promise<void> {
    return this.run(uri, async () => {
      await archive.writeEntry(await archive.locate(uri.path), content, options);
      this.changes.fire([{ type: vscode.FileChangeType.Changed, uri }]);
    });
  }

  delete(uri: vscode.Uri): Promise<void> {
    return this.run(uri, async () => {
      await archive.deleteEntry(await archive.locate(uri.path));
      this.changes.fire([{ type: vscode.FileChangeType.Deleted, uri }]);
    });
  }

  rename(oldUri: vscode.Uri, newUri: vscode.Uri, options: { readonly overwrite: boolean }): Promise<void> {
    return this.run(oldUri, async () => {
      await archive.renameEntry(await archive.locate(oldUri.path), await archive.locate(newUri.path), options.overwrite);
      this.changes.fire([
        { type: vscode.FileChangeType.Deleted, uri: oldUri },
        { type: vscode.FileChangeType.Created, uri: newUri },
      ]);
    });
  }

  createDirectory(uri: vscode.Uri): void {
    throw vscode.FileSystemError.NoPermissions(
      `${uri.path}: a folder inside a package exists through its files; create a file in it instead`,
    );
  }

  dispose(): void {
    for (const { watcher } of this.watchers.values()) watcher.dispose();
    this.watchers.clear();
    this.changes.dispose();
  }
}

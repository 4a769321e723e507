import { URI } from 'vscode-uri';
import { PACKAGE_SCHEME } from '../../common/src/protocol';
import { isWindowsPath, pathsFor } from './core/paths';
import { diskRef, ScenarioStore, SourceRef } from './core/sources';

/**
 * The `file:` URI of a disk path, spelled as VS Code spells it (`file:///c%3A/scenarios/a.mosc`,
 * `file://server/share/a.mosc`). Windows forms get their separators turned on any platform.
 */
export function fileUri(diskPath: string): URI {
  return URI.file(isWindowsPath(diskPath) ? diskPath.replace(/\\/g, '/') : diskPath);
}

/**
 * The disk path a `file:`-like URI names: Windows forms (a drive letter, a UNC host) with backslashes
 * and an upper-case drive letter, as node writes them (`process.cwd()`, `path.resolve`), else POSIX.
 */
export function diskPathOf(uri: URI): string {
  const fsPath = uri.fsPath;
  const windows = uri.authority.length > 0 || isWindowsPath(fsPath);
  const diskPath = windows ? fsPath.replace(/\//g, '\\').replace(/^[a-z](?=:)/, (drive) => drive.toUpperCase()) : fsPath;
  return pathsFor(diskPath).resolve(diskPath);
}

/** The URI of a scenario file: `file:` on disk, `mosc:/abs/pkg.mosc/inner.mosc/main.xosc` inside packages. */
export function refToUri(ref: SourceRef): string {
  const file = fileUri(ref.disk);
  if (ref.entries.length === 0) return file.toString();
  // Entries of a package are POSIX names whatever the platform: they continue the URI's path as they are.
  return file.with({ scheme: PACKAGE_SCHEME, path: `${file.path}/${ref.entries.join('/')}` }).toString();
}

/**
 * The path a `mosc:` URI names, package file and entries in one (`/abs/pkg.mosc/main.xosc`,
 * `C:\abs\pkg.mosc\main.xosc`), whatever authority form the client wrote (`mosc:/a`, `mosc:///a`).
 */
export function packageUriPath(uri: string): string | undefined {
  if (!uri.toLowerCase().startsWith(`${PACKAGE_SCHEME}:`)) return undefined;
  try {
    return diskPathOf(URI.parse(uri).with({ scheme: 'file' }));
  } catch {
    return undefined;
  }
}

/** The disk path of a `file:` URI, or undefined for any other URI (and for plain paths, which callers use as they are). */
export function filePathOf(uri: string): string | undefined {
  if (!uri.toLowerCase().startsWith('file:')) return undefined;
  try {
    return diskPathOf(URI.parse(uri));
  } catch {
    return undefined;
  }
}

/**
 * An unsaved new document (`untitled:Untitled-1`) stands for a file in `folder` that does not exist
 * on disk: its text comes from the editor, and names it references resolve from that folder.
 */
export function untitledRef(uri: string, folder: string): SourceRef | undefined {
  if (!uri.toLowerCase().startsWith('untitled:')) return undefined;
  const name = decodeURIComponent(uri.slice('untitled:'.length)).replace(/[^\w.-]+/g, '_') || 'untitled';
  // A hidden name: never the name of a real file beside it, never listed as one.
  return diskRef(pathsFor(folder).join(folder, `.untitled-${name}${/\.xosc$/i.test(name) ? '' : '.xosc'}`));
}

/** Reads URIs back into source references; `mosc:` URIs need the store to find where the disk file ends. */
export class UriResolver {
  private readonly known = new Map<string, SourceRef>();

  constructor(private store: () => ScenarioStore) {}

  /** Remembers the exact URI a client used, so that what the server sends back matches it. */
  remember(uri: string, ref: SourceRef): void {
    this.known.set(uri, ref);
  }

  async toRef(uri: string): Promise<SourceRef | undefined> {
    const known = this.known.get(uri);
    if (known) return known;
    const disk = filePathOf(uri);
    if (disk) return diskRef(disk);
    const untitled = untitledRef(uri, this.store().root ?? process.cwd());
    if (untitled) return untitled;
    const packagePath = packageUriPath(uri);
    if (!packagePath) return undefined;
    const ref = await this.store()
      .refFromPackagePath(packagePath)
      .catch(() => undefined);
    if (ref) this.known.set(uri, ref);
    return ref;
  }

  forget(uri: string): void {
    this.known.delete(uri);
  }
}

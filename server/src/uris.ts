import * as path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { PACKAGE_SCHEME } from './protocol';
import { diskRef, refId, ScenarioStore, SourceRef } from './core/sources';

/** The URI of a scenario file: `file:` on disk, `mosc:/abs/pkg.mosc/inner.mosc/main.xosc` inside packages. */
export function refToUri(ref: SourceRef): string {
  if (ref.entries.length === 0) return pathToFileURL(ref.disk).href;
  const encoded = refId(ref)
    .split('/')
    .map((segment) => encodeURIComponent(segment))
    .join('/');
  return `${PACKAGE_SCHEME}:${encoded}`;
}

/** The path part of a `mosc:` URI, whatever authority form the client wrote (`mosc:/a`, `mosc:///a`). */
export function packageUriPath(uri: string): string | undefined {
  const prefix = `${PACKAGE_SCHEME}:`;
  if (!uri.toLowerCase().startsWith(prefix)) return undefined;
  let rest = uri.slice(prefix.length);
  const query = rest.search(/[?#]/);
  if (query >= 0) rest = rest.slice(0, query);
  if (rest.startsWith('//')) rest = rest.slice(rest.indexOf('/', 2));
  try {
    return path.posix.normalize(decodeURIComponent(rest));
  } catch {
    return undefined;
  }
}

/** The disk path of a `file:` URI, or undefined for any other URI. */
export function filePathOf(uri: string): string | undefined {
  if (!uri.toLowerCase().startsWith('file:')) return undefined;
  try {
    return path.resolve(fileURLToPath(uri));
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
  return diskRef(path.join(folder, `.untitled-${name}${/\.xosc$/i.test(name) ? '' : '.xosc'}`));
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
    const ref = await this.store().refFromPackagePath(packagePath).catch(() => undefined);
    if (ref) this.known.set(uri, ref);
    return ref;
  }

  forget(uri: string): void {
    this.known.delete(uri);
  }
}

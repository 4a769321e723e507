import { pathsFor } from '../paths';
import { coreMemo } from '../memos';

/**
 * Where a scenario file lives: a path on disk, then zero or more entry names, each inside the
 * package named before it. `{ disk: '/a/p.mosc', entries: ['inner.mosc', 'main.xosc'] }` is the
 * `main.xosc` of the package `inner.mosc` stored in `/a/p.mosc`.
 */
export interface SourceRef {
  disk: string;
  entries: string[];
}

export function diskRef(filePath: string): SourceRef {
  return { disk: pathsFor(filePath).resolve(filePath), entries: [] };
}

export function childRef(packageRef: SourceRef, entry: string): SourceRef {
  return { disk: packageRef.disk, entries: [...packageRef.entries, entry] };
}

/** A package's `.mosc` file (or an entry holding one) is read as a folder: `/a/p.mosc/inner.mosc/main.xosc`. */
export function refId(ref: SourceRef): string {
  if (ref.entries.length === 0) return ref.disk;
  // Remembered per ref: deep chains of nested packages compare ids often, and each is as long as the chain.
  let id = refIds.get(ref);
  if (id === undefined) {
    id = `${ref.disk}/${ref.entries.join('/')}`;
    refIds.set(ref, id);
  }
  return id;
}

const refIds = coreMemo<SourceRef, string>('refIds');

export function sameRef(a: SourceRef, b: SourceRef): boolean {
  return refId(a) === refId(b);
}

/**
 * A short form for messages: relative to `base` (the caller's working directory or workspace folder)
 * when the file lies below it; without a base, the whole path.
 */
export function displayRef(ref: SourceRef, base: string | undefined): string {
  const paths = pathsFor(ref.disk);
  // A base of the other platform's form (a POSIX working directory, a Windows file) never contains it.
  const relative = base !== undefined && pathsFor(base) === paths ? paths.relative(base, ref.disk) : '';
  const disk = relative && !relative.startsWith('..') && !paths.isAbsolute(relative) ? relative : ref.disk;
  return ref.entries.length === 0 ? disk : `${disk}/${ref.entries.join('/')}`;
}

export function baseName(ref: SourceRef): string {
  const last = ref.entries.length > 0 ? ref.entries[ref.entries.length - 1] : ref.disk;
  return last.split(/[\\/]/).pop() ?? last;
}

export class SourceError extends Error {
  constructor(
    message: string,
    readonly ref: SourceRef,
    readonly hint?: string,
    /** Zero-based line of the problem in the file, when known. */
    readonly line?: number,
    /** What failed: reading the file (`io`), or the package it lies in (`bad-package`), as the problem's code says. */
    readonly code: 'io' | 'bad-package' = 'io',
  ) {
    super(message);
  }
}

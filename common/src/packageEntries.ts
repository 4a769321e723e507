import { extractEntry, InflateBudget, readCentralDirectory, ZipEntryRecord } from './zip';

/** Bounds on reading one package: its entry count, any one entry, and all it unpacks. */
export interface PackageLimits {
  maxEntries: number;
  /** Any one scenario file, on disk or unpacked from a package. */
  maxEntryBytes: number;
  /** Bytes unpacked from packages in one run, all packages together. */
  maxTotalBytes: number;
}

export const DEFAULT_PACKAGE_LIMITS: PackageLimits = {
  maxEntries: 10_000,
  maxEntryBytes: 32 * 1024 * 1024,
  maxTotalBytes: 128 * 1024 * 1024,
};

export interface PackageContents {
  /** Entry names (with `/` for sub-folders) to their bytes; folders are not listed. */
  entries: Map<string, Uint8Array>;
}

/** Normalizes a ZIP entry or reference name; undefined when it would leave the package. */
export function normalizeEntryName(name: string): string | undefined {
  const parts: string[] = [];
  for (const part of name.replace(/\\/g, '/').split('/')) {
    if (part === '' || part === '.') continue;
    if (part === '..') return undefined;
    parts.push(part);
  }
  if (/^[A-Za-z]:/.test(name) || name.startsWith('/')) return undefined;
  return parts.length > 0 ? parts.join('/') : undefined;
}

/**
 * Reads a `.mosc` in memory. Nothing is extracted to disk; unsafe or duplicate names, overlapping
 * entries and oversized entries are refused; what is unpacked is charged to `budget`.
 */
export async function readPackageBytes(
  bytes: Uint8Array,
  label: string,
  limits: PackageLimits = DEFAULT_PACKAGE_LIMITS,
  budget: InflateBudget = { remaining: limits.maxTotalBytes, limit: limits.maxTotalBytes },
): Promise<PackageContents> {
  let records: ZipEntryRecord[];
  try {
    records = readCentralDirectory(bytes, limits.maxEntries);
  } catch (error) {
    throw new Error(`${label} is not a readable ZIP archive (${(error as Error).message}); a .mosc must be a ZIP file`);
  }
  const entries = new Map<string, Uint8Array>();
  const stored = new Map<string, string>();
  for (const record of records) {
    if (record.name.endsWith('/') || record.name.endsWith('\\')) continue;
    const name = normalizeEntryName(record.name);
    if (name === undefined)
      throw new Error(`${label} holds an entry named '${record.name}' that points outside the package; it was refused`);
    const first = stored.get(name);
    if (first !== undefined) {
      throw new Error(
        `${label} holds the entry '${name}' twice` +
          (first === record.name ? '' : ` (as '${first}' and '${record.name}')`) +
          '; it was refused',
      );
    }
    stored.set(name, record.name);
  }
  for (const record of records) {
    const name = normalizeEntryName(record.name);
    if (name === undefined || record.name.endsWith('/') || record.name.endsWith('\\')) continue;
    try {
      entries.set(name, extractEntry(bytes, record, limits.maxEntryBytes, budget, `${label}/${name}`));
    } catch (error) {
      throw new Error((error as Error).message);
    }
  }
  return { entries };
}

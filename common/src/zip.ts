import type * as Zlib from 'node:zlib';

let zlibModule: typeof Zlib | undefined;
/** node:zlib, loaded when a package is first read or written: loading it was 3% of a short CLI run that reads none. */
function zlib(): typeof Zlib {
  return (zlibModule ??= require('node:zlib') as typeof Zlib);
}

/**
 * A ZIP reader that reads the central directory itself, so that what a package holds is decided
 * here and not by a library that merges or renames entries: duplicate names, entries whose data
 * overlap (one compressed stream shared by many entries) and encrypted or ZIP64 archives are refused,
 * and every entry is inflated with a byte budget that stops the work, not just the result.
 */

export interface ZipEntryRecord {
  /** The name as stored in the archive. */
  name: string;
  method: number;
  flags: number;
  crc32: number;
  compressedSize: number;
  uncompressedSize: number;
  localHeaderOffset: number;
  /** Offset of the entry's data, after its local header. */
  dataStart: number;
  /** The last-modified date and time as MS-DOS stores them: time in the low 16 bits, date in the high (entryDate). */
  dosDateTime: number;
}

/** An entry's date, read as JSZip reads and writes it (the DOS fields as UTC), so that a date written by one reads back unchanged. */
export function entryDate(entry: ZipEntryRecord): Date {
  const value = entry.dosDateTime;
  return new Date(
    Date.UTC(
      ((value >>> 25) & 0x7f) + 1980,
      ((value >>> 21) & 0x0f) - 1,
      (value >>> 16) & 0x1f,
      (value >>> 11) & 0x1f,
      (value >>> 5) & 0x3f,
      (value & 0x1f) << 1,
    ),
  );
}

export class ZipFormatError extends Error {}

/** Bytes that inflating may still produce; shared by every package read in one run. */
export interface InflateBudget {
  remaining: number;
  readonly limit: number;
}

const END_OF_CENTRAL_DIRECTORY = 0x06054b50;
const CENTRAL_HEADER = 0x02014b50;
const LOCAL_HEADER = 0x04034b50;
const ZIP64_LOCATOR = 0x07064b50;

function view(bytes: Uint8Array): DataView {
  return new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
}

function findEndOfCentralDirectory(bytes: Uint8Array, data: DataView): number {
  // The record is 22 bytes plus a comment of at most 65,535 bytes, at the very end.
  const lowest = Math.max(0, bytes.length - 22 - 0xffff);
  for (let offset = bytes.length - 22; offset >= lowest; offset--) {
    if (data.getUint32(offset, true) === END_OF_CENTRAL_DIRECTORY && offset + 22 + data.getUint16(offset + 20, true) <= bytes.length)
      return offset;
  }
  throw new ZipFormatError('no ZIP end-of-central-directory record was found');
}

/** Lists the entries of an archive from its central directory, refusing what a safe reader must not accept. */
export function readCentralDirectory(bytes: Uint8Array, maxEntries: number): ZipEntryRecord[] {
  if (bytes.length < 22) throw new ZipFormatError('the file is too short to be a ZIP archive');
  const data = view(bytes);
  const end = findEndOfCentralDirectory(bytes, data);
  const disk = data.getUint16(end + 4, true);
  const directoryDisk = data.getUint16(end + 6, true);
  const count = data.getUint16(end + 10, true);
  const directorySize = data.getUint32(end + 12, true);
  const directoryOffset = data.getUint32(end + 16, true);
  if (end >= 20 && data.getUint32(end - 20, true) === ZIP64_LOCATOR) throw new ZipFormatError('ZIP64 archives are not supported');
  if (count === 0xffff || directoryOffset === 0xffffffff || directorySize === 0xffffffff)
    throw new ZipFormatError('ZIP64 archives are not supported');
  if (disk !== 0 || directoryDisk !== 0 || data.getUint16(end + 8, true) !== count)
    throw new ZipFormatError('archives split over several disks are not supported');
  if (count > maxEntries) throw new ZipFormatError(`it holds ${count} entries, more than the ${maxEntries} allowed`);
  if (directoryOffset + directorySize > end) throw new ZipFormatError('the central directory lies outside the archive');
  const entries: ZipEntryRecord[] = [];
  let offset = directoryOffset;
  const decoder = new TextDecoder('utf-8', { fatal: true });
  for (let index = 0; index < count; index++) {
    if (offset + 46 > end || data.getUint32(offset, true) !== CENTRAL_HEADER)
      throw new ZipFormatError(`central directory entry ${index + 1} is damaged`);
    const flags = data.getUint16(offset + 8, true);
    const method = data.getUint16(offset + 10, true);
    const dosDateTime = data.getUint32(offset + 12, true);
    const crc32 = data.getUint32(offset + 16, true);
    const compressedSize = data.getUint32(offset + 20, true);
    const uncompressedSize = data.getUint32(offset + 24, true);
    const nameLength = data.getUint16(offset + 28, true);
    const extraLength = data.getUint16(offset + 30, true);
    const commentLength = data.getUint16(offset + 32, true);
    const localHeaderOffset = data.getUint32(offset + 42, true);
    if (offset + 46 + nameLength > end) throw new ZipFormatError(`central directory entry ${index + 1} is damaged`);
    let name: string;
    try {
      name = decoder.decode(bytes.subarray(offset + 46, offset + 46 + nameLength));
    } catch {
      // Names without the UTF-8 flag may be in the old DOS code page; bytes above 127 are shown as they are.
      name = Buffer.from(bytes.subarray(offset + 46, offset + 46 + nameLength)).toString('latin1');
    }
    if (compressedSize === 0xffffffff || uncompressedSize === 0xffffffff || localHeaderOffset === 0xffffffff)
      throw new ZipFormatError('ZIP64 archives are not supported');
    if (flags & 1) throw new ZipFormatError(`the entry '${name}' is encrypted`);
    if (localHeaderOffset + 30 > directoryOffset || data.getUint32(localHeaderOffset, true) !== LOCAL_HEADER)
      throw new ZipFormatError(`the entry '${name}' has no valid local header`);
    const dataStart = localHeaderOffset + 30 + data.getUint16(localHeaderOffset + 26, true) + data.getUint16(localHeaderOffset + 28, true);
    if (dataStart + compressedSize > directoryOffset)
      throw new ZipFormatError(`the data of entry '${name}' runs past the end of the archive`);
    entries.push({ name, method, flags, crc32, compressedSize, uncompressedSize, localHeaderOffset, dataStart, dosDateTime });
    offset += 46 + nameLength + extraLength + commentLength;
  }
  // Each entry owns its bytes: overlapping entries are how one compressed stream is inflated many times.
  const ordered = [...entries].sort((a, b) => a.localHeaderOffset - b.localHeaderOffset);
  for (let i = 1; i < ordered.length; i++) {
    const previous = ordered[i - 1];
    if (previous.dataStart + previous.compressedSize > ordered[i].localHeaderOffset) {
      throw new ZipFormatError(`the entries '${previous.name}' and '${ordered[i].name}' overlap in the archive (a ZIP bomb pattern)`);
    }
  }
  return entries;
}

let crcTable: Uint32Array | undefined;

export function crc32(bytes: Uint8Array): number {
  // Node's own where it has one (20.15 on): this byte loop runs in V8's interpreter in a short CLI run, most of unpacking a package.
  const { crc32: nativeCrc32 } = zlib();
  if (typeof nativeCrc32 === 'function') return nativeCrc32(bytes);
  if (!crcTable) {
    crcTable = new Uint32Array(256);
    for (let n = 0; n < 256; n++) {
      let c = n;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[n] = c >>> 0;
    }
  }
  let crc = 0xffffffff;
  for (let i = 0; i < bytes.length; i++) crc = crcTable[(crc ^ bytes[i]) & 0xff] ^ (crc >>> 8);
  return (crc ^ 0xffffffff) >>> 0;
}

/**
 * The bytes of one entry. Inflating stops as soon as it would produce more than the entry's
 * declared size, `maxEntryBytes` or what the budget has left, so a bomb costs no more than the bound.
 */
export function extractEntry(
  bytes: Uint8Array,
  entry: ZipEntryRecord,
  maxEntryBytes: number,
  budget: InflateBudget,
  label: string,
): Uint8Array {
  const bound = Math.min(entry.uncompressedSize, maxEntryBytes, budget.remaining);
  const exceeded = (): ZipFormatError => {
    if (bound === budget.remaining && bound < Math.min(entry.uncompressedSize, maxEntryBytes)) {
      return new ZipFormatError(
        `${label} would exceed the ${budget.limit} bytes that one run may unpack from all packages together; it was refused (raise the bound with --max-unpacked-size)`,
      );
    }
    if (bound === maxEntryBytes && bound < entry.uncompressedSize)
      return new ZipFormatError(
        `${label} unpacks to more than ${maxEntryBytes} bytes; it was refused (raise the bound with --max-file-size)`,
      );
    return new ZipFormatError(`${label} unpacks to more than its declared ${entry.uncompressedSize} bytes`);
  };
  if (entry.uncompressedSize > bound) throw exceeded();
  const raw = bytes.subarray(entry.dataStart, entry.dataStart + entry.compressedSize);
  let content: Uint8Array;
  if (entry.method === 0) {
    if (raw.length !== entry.uncompressedSize)
      throw new ZipFormatError(`the stored ${label} has ${raw.length} bytes, not the declared ${entry.uncompressedSize}`);
    content = raw;
  } else if (entry.method === 8) {
    try {
      // maxOutputLength must be positive; an empty entry may produce at most one byte, which is then refused.
      content = zlib().inflateRawSync(raw, { maxOutputLength: Math.max(1, bound) });
    } catch (error) {
      if ((error as NodeJS.ErrnoException).code === 'ERR_BUFFER_TOO_LARGE') throw exceeded();
      throw new ZipFormatError(`${label} cannot be inflated (${(error as Error).message})`);
    }
    if (content.length > bound) throw exceeded();
    if (content.length !== entry.uncompressedSize)
      throw new ZipFormatError(`${label} unpacks to ${content.length} bytes, not the declared ${entry.uncompressedSize}`);
  } else {
    throw new ZipFormatError(`${label} uses compression method ${entry.method}; only stored and deflated entries are supported`);
  }
  budget.remaining -= content.length;
  if (crc32(content) !== entry.crc32) throw new ZipFormatError(`${label} is damaged (CRC mismatch)`);
  return content;
}

/**
 * Decodes a scenario file as its byte-order mark and XML declaration say (XML 1.0, appendix F),
 * or refuses it with a message: bytes are never silently replaced by U+FFFD.
 */
import { isUtf8 } from 'node:buffer';

export class DecodeError extends Error {
  constructor(
    message: string,
    /** Offset of the offending byte in the file. */
    readonly byteOffset: number,
    /** Zero-based line of that byte, counted in the bytes before it. */
    readonly line: number,
  ) {
    super(message);
  }
}

type Decoder = (bytes: Uint8Array) => string;

function whatwg(label: string): Decoder {
  return (bytes) => new TextDecoder(label, { fatal: true }).decode(bytes);
}

/** ISO-8859-1 maps every byte to the code point of the same value (WHATWG's label means windows-1252 instead). */
const latin1: Decoder = (bytes) => Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength).toString('latin1');

/** Encodings a declaration may name, by lower-case name; the standard's names and common aliases. */
const DECLARED: Record<string, Decoder> = {
  'utf-8': whatwg('utf-8'),
  utf8: whatwg('utf-8'),
  'us-ascii': whatwg('utf-8'),
  ascii: whatwg('utf-8'),
  'iso-8859-1': latin1,
  'iso_8859-1': latin1,
  latin1: latin1,
  'latin-1': latin1,
  'windows-1252': whatwg('windows-1252'),
  cp1252: whatwg('windows-1252'),
  'iso-8859-15': whatwg('iso-8859-15'),
};

function lineOf(bytes: Uint8Array, offset: number): number {
  let line = 0;
  for (let i = 0; i < offset && i < bytes.length; i++) if (bytes[i] === 10) line++;
  return line;
}

/** Offset of the first byte that does not start or continue a valid UTF-8 sequence. */
function firstInvalidUtf8(bytes: Uint8Array): number {
  let i = 0;
  while (i < bytes.length) {
    const b = bytes[i];
    if (b < 0x80) {
      i++;
      continue;
    }
    const length = b >= 0xc2 && b <= 0xdf ? 2 : b >= 0xe0 && b <= 0xef ? 3 : b >= 0xf0 && b <= 0xf4 ? 4 : 0;
    if (length === 0 || i + length > bytes.length) return i;
    for (let k = 1; k < length; k++) if ((bytes[i + k] & 0xc0) !== 0x80) return i;
    const second = bytes[i + 1];
    if ((b === 0xe0 && second < 0xa0) || (b === 0xed && second > 0x9f) || (b === 0xf0 && second < 0x90) || (b === 0xf4 && second > 0x8f))
      return i;
    i += length;
  }
  return -1;
}

/** The `encoding` of an XML declaration at the start of ASCII-compatible bytes. */
function declaredEncoding(bytes: Uint8Array): string | undefined {
  const head = Buffer.from(bytes.buffer, bytes.byteOffset, Math.min(bytes.byteLength, 256)).toString('latin1');
  const declaration = /^<\?xml\s[^?]*?\bencoding\s*=\s*(["'])([^"']*)\1/.exec(head);
  return declaration ? declaration[2] : undefined;
}

/**
 * The text of a scenario file. UTF-8 with or without a byte-order mark, UTF-16 with one, and the
 * encodings listed above when the XML declaration names them; anything else is refused.
 */
export function decodeScenario(bytes: Uint8Array): string {
  if (bytes[0] === 0xff && bytes[1] === 0xfe) return decodeChecked(bytes.subarray(2), 'UTF-16LE', whatwg('utf-16le'));
  if (bytes[0] === 0xfe && bytes[1] === 0xff) return decodeChecked(bytes.subarray(2), 'UTF-16BE', whatwg('utf-16be'));
  if (bytes[0] === 0xef && bytes[1] === 0xbb && bytes[2] === 0xbf) return decodeUtf8Strict(bytes.subarray(3), 3);
  if ((bytes[0] === 0x3c && bytes[1] === 0 && bytes[2] === 0x3f) || (bytes[0] === 0 && bytes[1] === 0x3c && bytes[2] === 0)) {
    throw new DecodeError('the file is in UTF-16 without a byte-order mark; save it as UTF-8 (or UTF-16 with a byte-order mark)', 0, 0);
  }
  const declared = declaredEncoding(bytes);
  if (declared === undefined) return decodeUtf8Strict(bytes, 0);
  const key = declared.toLowerCase();
  if (key === 'utf-16' || key === 'utf-16le' || key === 'utf-16be') {
    throw new DecodeError(
      `the XML declaration says encoding="${declared}" but the file has no UTF-16 byte-order mark; save it as UTF-8`,
      0,
      0,
    );
  }
  const decoder = DECLARED[key];
  if (!decoder) throw new DecodeError(`the file declares encoding="${declared}", which cannot be read; save it as UTF-8`, 0, 0);
  if (key === 'us-ascii' || key === 'ascii') {
    const high = bytes.findIndex((byte) => byte >= 0x80);
    if (high >= 0)
      throw new DecodeError(
        `byte 0x${bytes[high].toString(16)} at offset ${high} is not ASCII, which the XML declaration promises; save the file as UTF-8`,
        high,
        lineOf(bytes, high),
      );
  }
  return key === 'utf-8' || key === 'utf8' ? decodeUtf8Strict(bytes, 0) : decodeChecked(bytes, declared, decoder);
}

function decodeUtf8Strict(bytes: Uint8Array, shift: number): string {
  // Node's native check first: the byte loop, run only to place the error, is slow before V8 has compiled it.
  const invalid = isUtf8(bytes) ? -1 : firstInvalidUtf8(bytes);
  if (invalid >= 0) {
    const at = invalid + shift;
    throw new DecodeError(
      `byte 0x${bytes[invalid].toString(16).padStart(2, '0')} at offset ${at} is not valid UTF-8; save the file as UTF-8, or declare its encoding (for example <?xml version="1.0" encoding="ISO-8859-1"?>)`,
      at,
      lineOf(bytes, invalid),
    );
  }
  return new TextDecoder('utf-8', { fatal: true }).decode(bytes);
}

function decodeChecked(bytes: Uint8Array, name: string, decoder: Decoder): string {
  try {
    return decoder(bytes);
  } catch {
    throw new DecodeError(`the file is not valid ${name}; save it as UTF-8`, 0, 0);
  }
}

/** The text with the encoding of its XML declaration set to UTF-8, as every output is written. */
export function declareUtf8(text: string): string {
  const declaration = /^(\uFEFF?<\?xml\s[^?]*?\bencoding\s*=\s*)(["'])([^"']*)\2/.exec(text);
  if (!declaration || declaration[3].toLowerCase() === 'utf-8') return text;
  return declaration[1] + declaration[2] + 'UTF-8' + declaration[2] + text.slice(declaration[0].length);
}

/** The character classes and fixed tables of XML 1.0 that the scanner and the re-parse share. */

/** A raw attribute value that decodes to itself: no references, no white space to normalize. */
export const PLAIN_VALUE = /^[^&\x00-\x1F\uD800-\uDFFF\uFFFE\uFFFF]*$/;

export const LINE_END = /[\r\n>]/g;

export const PREDEFINED_ENTITIES: Record<string, string> = { lt: '<', gt: '>', amp: '&', quot: '"', apos: "'" };

export function isNameStart(code: number): boolean {
  return (code >= 65 && code <= 90) || (code >= 97 && code <= 122) || code === 95 || code === 58 || code >= 0xc0;
}

/** A character a name may hold after its first (NaN, past the end, is none). */
export function isNameChar(code: number): boolean {
  return isNameStart(code) || (code >= 48 && code <= 57) || code === 45 || code === 46 || code === 0xb7;
}

/** Whether a code point is a Char of XML 1.0: no NUL, no other C0 control but tab and line ends, no U+FFFE/U+FFFF. */
export function isXmlChar(code: number): boolean {
  return (
    code === 9 ||
    code === 10 ||
    code === 13 ||
    (code >= 0x20 && code <= 0xd7ff) ||
    (code >= 0xe000 && code <= 0xfffd) ||
    (code >= 0x10000 && code <= 0x10ffff)
  );
}

/** Characters that may not occur in an XML document, lone surrogates included. */
export const NOT_XML_CHAR = /[\x00-\x08\x0B\x0C\x0E-\x1F\uFFFE\uFFFF\uD800-\uDFFF]/g;

export function codePointName(code: number): string {
  return `U+${code.toString(16).toUpperCase().padStart(4, '0')}`;
}

export function isSpace(code: number): boolean {
  return code === 32 || code === 9 || code === 10 || code === 13;
}

import { codePointName, isXmlChar, PREDEFINED_ENTITIES } from './characters';

export type ReportProblem = (message: string, start: number, end?: number, severity?: 'error' | 'warning') => void;

/**
 * Decodes entity and character references of one document. Internal entities are those of its
 * DOCTYPE; external ones are reported, never resolved; expansion is bounded by `maxExpansion`.
 */
export class EntityDecoder {
  /** The internal general entities declared by the DOCTYPE, unexpanded. */
  readonly entities = new Map<string, string>();
  readonly externalEntities = new Set<string>();
  private expanded = 0;
  private expansionReported = false;

  constructor(
    private readonly maxExpansion: number,
    private readonly report: ReportProblem,
  ) {}

  expandEntity(name: string, start: number, end: number, depth: number): string {
    const predefined = PREDEFINED_ENTITIES[name];
    if (predefined !== undefined) return predefined;
    if (this.externalEntities.has(name)) {
      this.report(`external entity '&${name};' is never resolved; its reference is left empty`, start, end);
      return '';
    }
    const replacement = this.entities.get(name);
    if (replacement === undefined) {
      this.report(`undefined entity '&${name};' (escape a literal '&' as '&amp;')`, start, end);
      return '';
    }
    // Each expansion costs at least one unit, so that empty or failing entities cannot recurse without bound.
    this.expanded++;
    if (depth > 16) {
      this.report(`entity '&${name};' nests too deeply; expansion stopped`, start, end);
      return '';
    }
    if (this.expanded > this.maxExpansion) {
      this.reportExpansionOnce(start, end);
      return '';
    }
    const value = this.decodeReferences(replacement, start, end, depth + 1);
    if (depth === 0) this.expanded += value.length;
    if (this.expanded > this.maxExpansion) {
      this.reportExpansionOnce(start, end);
      return '';
    }
    return value;
  }

  private reportExpansionOnce(start: number, end: number): void {
    if (!this.expansionReported) this.report(`entity expansion exceeds ${this.maxExpansion} characters; expansion stopped`, start, end);
    this.expansionReported = true;
  }

  /** Decodes references in raw text; offsets are those of the raw text in the document, for messages. */
  decodeReferences(raw: string, rawStart: number, rawEnd: number, depth: number): string {
    if (raw.indexOf('&') < 0) return raw;
    let out = '';
    let i = 0;
    while (i < raw.length) {
      const amp = raw.indexOf('&', i);
      if (amp < 0) {
        out += raw.slice(i);
        if (depth > 0) this.expanded += raw.length - i;
        break;
      }
      out += raw.slice(i, amp);
      if (depth > 0) {
        this.expanded += amp - i;
        if (this.expanded > this.maxExpansion) return out;
      }
      const semicolon = raw.indexOf(';', amp);
      const at = depth === 0 ? rawStart + amp : rawStart;
      const refEnd = depth === 0 && semicolon >= 0 ? rawStart + semicolon + 1 : rawEnd;
      if (semicolon < 0 || semicolon - amp > 40) {
        this.report(`'&' must start an entity reference; write '&amp;' for a literal '&'`, at, at + 1);
        out += '&';
        i = amp + 1;
        continue;
      }
      const reference = raw.slice(amp + 1, semicolon);
      if (reference.startsWith('#')) {
        const code = reference.startsWith('#x') ? parseInt(reference.slice(2), 16) : parseInt(reference.slice(1), 10);
        if (!Number.isFinite(code) || !/^#(x[0-9a-fA-F]+|[0-9]+)$/.test(reference)) {
          this.report(`invalid character reference '&${reference};'`, at, refEnd);
        } else if (!isXmlChar(code)) {
          this.report(
            `the character reference '&${reference};' names ${code > 0x10ffff ? 'no character' : codePointName(code)}, which XML does not allow`,
            at,
            refEnd,
          );
        } else {
          out += String.fromCodePoint(code);
        }
      } else if (/^[A-Za-z_:][\w.:-]*$/.test(reference)) {
        out += this.expandEntity(reference, at, refEnd, depth);
      } else {
        this.report(`'&' must start an entity reference; write '&amp;' for a literal '&'`, at, at + 1);
        out += '&' + reference + ';';
      }
      i = semicolon + 1;
    }
    return out;
  }
}

import { parseXml, reparseXml, XmlDocument } from '../xml';
import { refId, SourceRef } from './ref';

/**
 * Unsaved texts that replace files' stored content (an editor's buffers), with the last parse of
 * each, from which the next edit is re-parsed.
 */
export class Overlays {
  private readonly texts = new Map<string, string>();
  /** The last parse of each file being edited. */
  private readonly editedParses = new Map<string, XmlDocument>();
  /** The last parse of the flattened text of each file being edited. */
  private readonly flattenedParses = new Map<string, XmlDocument>();

  set(ref: SourceRef, text: string | undefined): void {
    if (text === undefined) {
      this.texts.delete(refId(ref));
      this.editedParses.delete(refId(ref));
      this.flattenedParses.delete(refId(ref));
    } else {
      this.texts.set(refId(ref), text);
    }
  }

  get(ref: SourceRef): string | undefined {
    return this.texts.get(refId(ref));
  }

  parse(ref: SourceRef, text: string): XmlDocument {
    return this.parseEdited(this.editedParses, ref, text);
  }

  /** The last parse of a file being edited when it is of `text`; nothing is parsed. */
  lastParse(ref: SourceRef, text: string): XmlDocument | undefined {
    const last = this.editedParses.get(refId(ref));
    return last?.text === text ? last : undefined;
  }

  parseFlattened(ref: SourceRef, text: string): XmlDocument {
    return this.parseEdited(this.flattenedParses, ref, text);
  }

  private parseEdited(previousParses: Map<string, XmlDocument>, ref: SourceRef, text: string): XmlDocument {
    const id = refId(ref);
    if (!this.texts.has(id)) return parseXml(text);
    const previous = previousParses.get(id);
    const document = previous ? reparseXml(previous, text) : parseXml(text);
    previousParses.set(id, document);
    return document;
  }
}

import { TextDocument } from 'vscode-languageserver-textdocument';
import { refId, SourceRef } from './core/sources';

export interface OpenDocument {
  uri: string;
  ref: SourceRef;
  document: TextDocument;
}

export interface DocumentEntry {
  document: TextDocument;
  /** Resolving a URI to a file may read the disk (packages), so the ref arrives later than the text. */
  ref: Promise<SourceRef | undefined>;
  resolved?: OpenDocument;
}

/**
 * The one registry of documents the client has open: their current text by URI, and, once the URI
 * is resolved to a scenario file, the same entry by file id.
 */
export class OpenDocuments {
  private readonly byUri = new Map<string, DocumentEntry>();
  private readonly byId = new Map<string, OpenDocument>();

  /** Starts tracking a document; its ref is looked up while the text is already current. */
  add(uri: string, document: TextDocument, ref: Promise<SourceRef | undefined>): void {
    this.byUri.set(uri, { document, ref });
  }

  /** Attaches the resolved file to an open URI; false when the URI was closed meanwhile. */
  resolve(uri: string, ref: SourceRef): OpenDocument | undefined {
    const entry = this.byUri.get(uri);
    if (!entry) return undefined;
    entry.resolved = { uri, ref, document: entry.document };
    this.byId.set(refId(ref), entry.resolved);
    return entry.resolved;
  }

  /** Replaces the text of an open URI (the caller applied the client's changes). */
  setText(uri: string, document: TextDocument): void {
    const entry = this.byUri.get(uri);
    if (!entry) return;
    entry.document = document;
    if (entry.resolved) entry.resolved.document = document;
  }

  /** Stops tracking a URI; returns what it was. */
  remove(uri: string): DocumentEntry | undefined {
    const entry = this.byUri.get(uri);
    this.byUri.delete(uri);
    if (entry?.resolved && this.byId.get(refId(entry.resolved.ref)) === entry.resolved) this.byId.delete(refId(entry.resolved.ref));
    return entry;
  }

  /** The text the client has for a URI, whether or not it names a scenario file. */
  text(uri: string): TextDocument | undefined {
    return this.byUri.get(uri)?.document;
  }

  /** The open document at a URI once its file is known; undefined when not open or not a scenario file. */
  async atUri(uri: string): Promise<OpenDocument | undefined> {
    const entry = this.byUri.get(uri);
    if (!entry) return undefined;
    await entry.ref;
    return this.byUri.get(uri)?.resolved;
  }

  get(id: string): OpenDocument | undefined {
    return this.byId.get(id);
  }

  has(id: string): boolean {
    return this.byId.has(id);
  }

  keys(): IterableIterator<string> {
    return this.byId.keys();
  }

  values(): IterableIterator<OpenDocument> {
    return this.byId.values();
  }

  [Symbol.iterator](): IterableIterator<[string, OpenDocument]> {
    return this.byId.entries();
  }
}

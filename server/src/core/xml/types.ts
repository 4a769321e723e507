import { LineIndex } from '../text';

/** An attribute with the offsets of its name and of its raw value (inside the quotes). */
export interface XmlAttribute {
  name: string;
  /** The value with entity and character references decoded. */
  value: string;
  nameStart: number;
  nameEnd: number;
  valueStart: number;
  valueEnd: number;
  quote: '"' | "'";
}

export interface XmlElement {
  name: string;
  /** Offset of `<`. */
  start: number;
  nameEnd: number;
  /** Offset just after the start tag's `>` (or where the broken tag ends). */
  startTagEnd: number;
  /** Offset just after the end tag's `>`, or after `/>`. */
  end: number;
  selfClosing: boolean;
  /** False when the element was never closed (the document is not well-formed). */
  closed: boolean;
  attributes: XmlAttribute[];
  children: XmlElement[];
  parent: XmlElement | undefined;
}

export interface XmlProblem {
  message: string;
  start: number;
  end: number;
  severity: 'error' | 'warning';
}

export interface XmlDocument {
  text: string;
  root: XmlElement | undefined;
  problems: XmlProblem[];
  lines: LineIndex;
  /** The internal general entities of the DOCTYPE, expanded; absent when none is declared. */
  entities?: ReadonlyMap<string, string>;
}

export interface XmlParseOptions {
  /** Upper bound on characters produced by expanding internal entities, per document. */
  maxEntityExpansion?: number;
  /** Upper bound on element nesting; deeper content is reported and skipped. */
  maxDepth?: number;
}

import { Problem, ProblemCode, Severity } from '../problems';
import { displayRef, SourceRef } from '../sources';
import { XmlAttribute, XmlDocument, XmlElement } from '../xml';

/** What a problem says, and the offsets it covers in the document it is reported in. */
export interface ProblemWords {
  start: number;
  end: number;
  severity: Severity;
  code: ProblemCode;
  message: string;
  hint?: string;
}

export interface ProblemPlace extends ProblemWords {
  source: SourceRef;
  document: XmlDocument;
}

/** A problem at offsets of a document. */
export function problemAt({ source, document, start, end, severity, code, message, hint }: ProblemPlace): Problem {
  return { source, range: document.lines.range(start, end), severity, code, message, hint };
}

/** Offsets of an attribute's value, or of the element's name when the attribute is missing. */
export function valueRange(attributeNode: XmlAttribute | undefined, element: XmlElement): [number, number] {
  return attributeNode ? [attributeNode.valueStart, attributeNode.valueEnd] : [element.start, element.nameEnd];
}

/** A chain of files for a message: all of a short one, the ends of a long one. */
export function describeChain(chain: SourceRef[], base: string | undefined): string {
  const names = chain.map((entry) => displayRef(entry, base));
  return (names.length <= 12 ? names : [...names.slice(0, 5), `... (${names.length - 10} more)`, ...names.slice(-5)]).join(' -> ');
}

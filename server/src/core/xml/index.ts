/** The tolerant, offset-keeping XML parser of the core: tree types, scanner, incremental re-parse. */
export type { XmlAttribute, XmlDocument, XmlElement, XmlParseOptions, XmlProblem } from './types';
export { isXmlChar } from './characters';
export { parseXml } from './scanner';
export { markupFreeEdit, reparseValueEdit, reparseXml } from './reparse';
export { attribute, attributeValue, descendants, elementAt, elementStartingAt, escapeAttributeValue, firstDescendant, isWellFormed, isWithin, selfAndDescendants } from './tree';

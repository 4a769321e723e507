/** The tolerant, offset-keeping XML parser of the core: tree types, scanner, incremental re-parse. */
export type { XmlAttribute, XmlDocument, XmlElement, XmlParseOptions, XmlProblem } from './types';
export { isXmlChar } from './characters';
export { parseXml } from './scanner';
export { forgetValueEdit, markupFreeEdit, reparseValueEdit, reparseXml, valueEditOf } from './reparse';
export type { ValueEdit } from './reparse';
export { parseTextMatches, textMatches } from './textSearch';
export type { TextSearch } from './textSearch';
export {
  attribute,
  attributeValue,
  descendants,
  forEachElement,
  elementAt,
  elementStartingAt,
  endTagStart,
  escapeAttributeValue,
  firstDescendant,
  isWellFormed,
  isWithin,
  selfAndDescendants,
} from './tree';

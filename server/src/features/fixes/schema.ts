import { elementAt, XmlDocument, XmlElement } from '../../core/xml';

/** The element whose start tag's name holds `offset` (where the schema places its findings about an element). */
export function elementAtRange(document: XmlDocument, offset: number): XmlElement | undefined {
  const found = elementAt(document, offset);
  return found && found.start + 1 <= offset && offset <= found.nameEnd ? found : undefined;
}

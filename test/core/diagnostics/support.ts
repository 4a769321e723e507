import { TextDocument } from 'vscode-languageserver-textdocument';
import { FixContext, RelatedPlace } from '../../../server/src/core/diagnostics';
import { parseXml } from '../../../server/src/core/xml';

export const RANGE = { start: { line: 0, character: 1 }, end: { line: 0, character: 4 } };

/** What a module's fix is given: `data`, a document of `text` with the problem at `range`, and a related place where one is given. */
export function fixContext(data: unknown, related?: Partial<RelatedPlace>, text = '<a/>', range = RANGE): FixContext<unknown> {
  const document = TextDocument.create('file:///main.xosc', 'xml', 0, text);
  return {
    data,
    document,
    range,
    parsed: async () => parseXml(document.getText()),
    related: related && {
      range: RANGE,
      sameDocument: false,
      fileName: 'simple.xosc',
      editable: async () => true,
      text: async () => undefined,
      ...related,
    },
  };
}

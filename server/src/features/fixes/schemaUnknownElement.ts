import { TextEdit } from 'vscode-languageserver/node';
import { problemFix, quickFix } from './fix';
import { elementAtRange } from './schema';

/** An element the schema does not know here: the closest name, in the start tag and the end tag. */
export const schemaUnknownElementFix = problemFix(['schema-unknown-element'], async (data, { uri, document, diagnostic, parsed }) => {
  const text = document.getText();
  const element = elementAtRange(await parsed(), document.offsetAt(diagnostic.range.start));
  if (!data?.suggestion || !element) return [];
  const edits = [TextEdit.replace(diagnostic.range, data.suggestion)];
  const closing = element.selfClosing || !element.closed ? -1 : text.lastIndexOf(`</${element.name}`, element.end);
  if (closing > element.start)
    edits.push(
      TextEdit.replace(
        { start: document.positionAt(closing + 2), end: document.positionAt(closing + 2 + element.name.length) },
        data.suggestion,
      ),
    );
  return [quickFix(`Change to <${data.suggestion}>`, diagnostic, { changes: { [uri]: edits } }, true)];
});

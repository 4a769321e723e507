import { TextEdit } from 'vscode-languageserver/node';
import { problemFix, quickFix } from './fix';

/** An attribute name or a value the schema does not know: the closest one it does; a deprecated one: the standard's form. */
export const schemaSuggestionFix = problemFix(
  ['schema-unknown-attribute', 'schema-value', 'schema-deprecated'],
  (data, { uri, diagnostic }) =>
    data?.suggestion
      ? [
          quickFix(
            `Change to '${data.suggestion}'`,
            diagnostic,
            { changes: { [uri]: [TextEdit.replace(diagnostic.range, data.suggestion)] } },
            true,
          ),
        ]
      : [],
);

import { TextEdit } from 'vscode-languageserver/node';
import { indexFor, typeOfElement } from '../../core/schema/query';
import { placeholderValue } from '../../core/schema/skeleton';
import { problemFix, quickFix } from './fix';
import { elementAtRange } from './schema';

/** Required attributes the element lacks: added after its last attribute, each with a placeholder of its type. */
export const schemaMissingAttributeFix = problemFix(
  ['schema-missing-attribute'],
  async (data, { uri, document, diagnostic, parsed }, workspace) => {
    const tree = await parsed();
    const index = indexFor(tree, workspace.settings.schemaVersion);
    const element = elementAtRange(tree, document.offsetAt(diagnostic.range.start));
    const typeName = index && element ? typeOfElement(index, element) : undefined;
    if (!index || !element || !typeName || !data || data.missing.length === 0) return [];
    const names = data.missing;
    const inserted = names.map((name) => ` ${name}="${placeholderValue(index, index.attribute(typeName, name)?.type ?? '')}"`).join('');
    const last = element.attributes[element.attributes.length - 1];
    const at = last ? last.valueEnd + 1 : element.nameEnd;
    return [
      quickFix(
        `Add ${names.map((name) => `'${name}'`).join(', ')}`,
        diagnostic,
        { changes: { [uri]: [TextEdit.insert(document.positionAt(at), inserted)] } },
        true,
      ),
    ];
  },
);

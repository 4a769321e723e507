import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import fc from 'fast-check';
import { canonicalTree, CanonicalElement } from '../../server/src/core/equivalence';
import { Flattener } from '../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { escapeAttributeValue, isWellFormed, parseXml } from '../../server/src/core/xml';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

/** Characters XML 1.0 allows in content: random text must survive, not be "fixed". */
const xmlChar = fc.oneof(
  fc.constantFrom('<', '&', '"', "'", '>', ' ', ';', '#', 'é', 'ß', '東', '✓', '😀'),
  fc.string({ unit: 'grapheme', maxLength: 3 }),
);
const xmlText = fc.array(xmlChar, { maxLength: 12 }).map((parts) =>
  parts
    .join('')
    .replace(/[\u0000-\u0008\u000B\u000C\u000E-\u001F\uFFFE\uFFFF]/g, '')
    .replace(/[\uD800-\uDFFF]/g, (c, i, s) =>
      /[\uD800-\uDBFF][\uDC00-\uDFFF]/.test(s.slice(i, i + 2)) || /[\uD800-\uDBFF][\uDC00-\uDFFF]/.test(s.slice(i - 1, i + 1)) ? c : '',
    ),
);

function find(tree: CanonicalElement, name: string): CanonicalElement | undefined {
  if (tree.name === name) return tree;
  for (const child of tree.children) {
    if (typeof child === 'string') continue;
    const found = find(child, name);
    if (found) return found;
  }
  return undefined;
}

describe('property: random override values survive flattening', () => {
  it('values with <&"\' and non-ASCII text arrive intact and the output always parses', async () => {
    await fc.assert(
      fc.asyncProperty(xmlText, xmlText, xmlText, async (speed, x, entity) => {
        const parameters: [string, string][] = [
          ['AbsoluteTargetSpeed.value', escapeAttributeValue(speed)],
          ['WorldPosition.x', escapeAttributeValue(x)],
          ['entityRef', escapeAttributeValue(entity)],
        ];
        const root = temporaryWorkspace({
          'simple.xosc': scenario(simpleGroup('Go')),
          'main.xosc': scenario(outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters }] }])),
        });
        const store = new ScenarioStore({ root, scenarioPath: [] });
        // Forced: a random entityRef names no declared entity, an error that --force writes through (SPEC 12).
        const result = await new Flattener(store).flatten(diskRef(path.join(root, 'main.xosc')), { force: true });
        assert.ok(result.text !== undefined, JSON.stringify(result.problems.map((p) => p.message)));
        assert.ok(isWellFormed(parseXml(result.text)), 'our parser accepts the output');
        const tree = canonicalTree(result.text);
        assert.ok(tree, 'an independent parser accepts the output');
        // Literal tabs and line breaks in attribute values are normalized to spaces by every XML parser.
        const normalize = (value: string) => value.replace(/[\t\n\r]/g, ' ');
        assert.equal(find(tree, 'AbsoluteTargetSpeed')?.attributes.value, normalize(speed));
        assert.equal(find(tree, 'WorldPosition')?.attributes.x, normalize(x));
        assert.equal((find(find(tree, 'Condition')!, 'EntityRef') as CanonicalElement).attributes.entityRef, normalize(entity));
      }),
      { numRuns: 60 },
    );
  });
});

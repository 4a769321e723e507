import * as assert from 'node:assert/strict';
import fc from 'fast-check';
import { isDistributionParse, isDistributionText } from '../../server/src/core/variations/problems';
import { parseTextMatches, parseXml, reparseXml, TextSearch, textMatches, valueEditOf, XmlDocument } from '../../server/src/core/xml';
import { distributionFile, deterministic, scenario, simpleGroup } from '../support/fixtures';

/** A search whose pattern records the length of each text it is run on. */
function countedSearch(source: string, literal: string, span: number): { search: TextSearch; scanned: number[] } {
  const scanned: number[] = [];
  const pattern = new RegExp(source);
  const test = pattern.test.bind(pattern);
  pattern.test = (text: string) => {
    scanned.push(text.length);
    return test(text);
  };
  return { search: { pattern, literal, span }, scanned };
}

/** The text with `[start, end)` replaced. */
const replaced = (text: string, start: number, end: number, insert: string) => text.slice(0, start) + insert + text.slice(end);

describe('core: a search of a parse’s text, carried over an edit inside one value', () => {
  const text = '<a x="fast" y="slow">\n  <b z="one"/>\n  <c w="two"/>\n</a>\n';

  it('gives every parse of a chain of value edits the answer a scan of its text gives', () => {
    const search: TextSearch = { pattern: /fast\b/, literal: 'fast', span: 5 };
    const values = ['fast', 'slow', 'fas', 't', 'fastest', 'breakfast', '', ' ', 'st'];
    const edit = fc.record({
      attribute: fc.integer({ min: 0, max: 3 }),
      from: fc.nat(),
      length: fc.nat({ max: 6 }),
      insert: fc.constantFrom(...values),
    });
    let valueEdits = 0;
    fc.assert(
      fc.property(fc.array(edit, { minLength: 1, maxLength: 12 }), (edits) => {
        let document: XmlDocument = parseXml(text);
        assert.equal(parseTextMatches(document, search), textMatches(document.text, search));
        for (const { attribute, from, length, insert } of edits) {
          const values = [...document.text.matchAll(/="([^"]*)"/g)];
          const value = values[attribute % values.length];
          const valueStart = (value.index ?? 0) + 2;
          const start = valueStart + (from % (value[1].length + 1));
          const end = Math.min(valueStart + value[1].length, start + length);
          document = reparseXml(document, replaced(document.text, start, end, insert));
          if (valueEditOf(document)) valueEdits++;
          assert.equal(parseTextMatches(document, search), textMatches(document.text, search), JSON.stringify(document.text));
        }
      }),
      { numRuns: 200 },
    );
    assert.ok(valueEdits > 100, `${valueEdits} edits re-parsed as value edits`);
  });

  it('scans only around an edit far from any match, and the whole text after an edit that is not inside one value', () => {
    const { search, scanned } = countedSearch('fast\\b', 'fast', 5);
    const first = parseXml(text);
    assert.equal(parseTextMatches(first, search), true);
    assert.deepEqual(scanned, [text.length]);
    scanned.length = 0;
    const valueEdit = reparseXml(first, text.replace('"two"', '"three"'));
    assert.ok(valueEditOf(valueEdit));
    assert.equal(parseTextMatches(valueEdit, search), true);
    assert.ok(
      scanned.every((length) => length < 20),
      `scanned ${scanned.join(', ')} characters`,
    );
    scanned.length = 0;
    // A new element: not a value edit, the new parse is scanned.
    const markupEdit = reparseXml(valueEdit, valueEdit.text.replace('<c ', '<d/><c '));
    assert.equal(valueEditOf(markupEdit), undefined);
    assert.equal(parseTextMatches(markupEdit, search), true);
    assert.ok(scanned.includes(markupEdit.text.length));
  });

  it('a scenario made a distribution file by an edit that is not inside one value is one, and stops being one the same way', () => {
    const plain = scenario(simpleGroup('G'));
    let document = parseXml(plain);
    assert.equal(isDistributionParse(document), false);
    document = reparseXml(document, plain.replace('value="10"', 'value="12"'));
    assert.ok(valueEditOf(document));
    assert.equal(isDistributionParse(document), false);
    const distribution = distributionFile(
      'plain.xosc',
      deterministic(`      <DeterministicSingleParameterDistribution parameterName="Speed">
        <DistributionSet><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
`),
    );
    document = reparseXml(document, distribution);
    assert.equal(isDistributionParse(document), true);
    document = reparseXml(document, distribution.replace('value="20"', 'value="25"'));
    assert.ok(valueEditOf(document));
    assert.equal(isDistributionParse(document), true);
    document = reparseXml(document, plain);
    assert.equal(isDistributionParse(document), isDistributionText(plain));
    assert.equal(isDistributionParse(document), false);
  });
});

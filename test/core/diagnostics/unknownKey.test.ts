import * as assert from 'node:assert/strict';
import { missingKeysInsertion, UNKNOWN_KEY, unknownKeyData, unknownKeyWording } from '../../../server/src/core/diagnostics/unknownKey';
import { fixContext as context, RANGE } from './support';

describe('diagnostics: unknown-key', () => {
  it('words the problem and its hint from what the flattener found', () => {
    assert.deepEqual(unknownKeyWording({ key: 'Ego.sped', group: 'Drive', suggestion: 'Ego.speed' }), {
      severity: 'error',
      code: 'unknown-key',
      message: "key 'Ego.sped' matches no attribute listed in a parameterAttributes of group 'Drive'",
      hint: "did you mean 'Ego.speed'?",
    });
    const listed = { key: 'a.speed', group: 'G', listedVerbatim: { element: 'Speed', name: 'a.speed', file: 'simple.xosc' } };
    assert.equal(
      unknownKeyWording(listed).hint,
      "<Speed> in simple.xosc lists 'a.speed', which names no attribute; list 'speed' there instead",
    );
    assert.deepEqual(unknownKeyData(listed), { relatedReplacement: 'speed' });
    assert.equal(unknownKeyData({ key: 'x', group: 'G' }), undefined);
  });

  it('fixes a near key where it is written, a whole key where it is listed, and nothing in a file it may not edit', async () => {
    const fixes = UNKNOWN_KEY.fixes!;
    assert.deepEqual(await fixes(context({ suggestion: 'speed' })), [
      { title: "Change key to 'speed'", edits: [{ place: 'document', range: RANGE, newText: 'speed' }], preferred: true },
    ]);
    assert.deepEqual(await fixes(context({ relatedReplacement: 'speed' }, {})), [
      { title: "List 'speed' in simple.xosc instead", edits: [{ place: 'related', range: RANGE, newText: 'speed' }], preferred: true },
    ]);
    assert.deepEqual(await fixes(context({ relatedReplacement: 'speed' }, { editable: async () => false })), []);
    assert.deepEqual(await fixes(context({ relatedReplacement: 'speed' })), []);
  });

  it('adds the missing keys before the closing tag, indented as the last key, in the line ends of the file', () => {
    const text = '<Root>\r\n  <MG>\r\n    <P key="a" value="1"/>\r\n  </MG>\r\n</Root>';
    const start = text.indexOf('<MG>');
    const end = text.indexOf('</MG>') + '</MG>'.length;
    const insertion = missingKeysInsertion(text, start, end, text.indexOf('<P '), [{ key: 'b', defaultValue: 'x"y' }]);
    assert.equal(insertion.title, 'Add 1 missing key with their defaults');
    assert.equal(insertion.offset, text.indexOf('  </MG>'));
    assert.equal(insertion.newText, '    <ParameterReference key="b" value="x&quot;y"/>\r\n');
  });
});

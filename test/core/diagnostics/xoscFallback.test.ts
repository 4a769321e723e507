import * as assert from 'node:assert/strict';
import { fallbackPackageName, XOSC_FALLBACK, xoscFallbackWording } from '../../../server/src/core/diagnostics/xoscFallback';
import { fixContext, RANGE } from './support';

describe('diagnostics: xosc-fallback', () => {
  it('says which package stands in for the missing .xosc, when flattening and when packing', () => {
    assert.equal(fallbackPackageName('lib/cut.xosc'), 'lib/cut.mosc');
    assert.deepEqual(xoscFallbackWording('cut.xosc', 'cut.mosc', 'used'), {
      severity: 'warning',
      code: 'xosc-fallback',
      message: "'cut.xosc' does not exist; the flattened package 'cut.mosc' is used in its place",
      hint: 'write scenarioFileName="cut.mosc"',
    });
    assert.equal(
      xoscFallbackWording('cut.xosc', 'cut.mosc', 'stored').message,
      "'cut.xosc' does not exist; the package 'cut.mosc' is stored for it",
    );
    assert.equal(XOSC_FALLBACK.deprecated, true);
  });

  it('names the package instead', async () => {
    assert.deepEqual(await XOSC_FALLBACK.fixes!(fixContext({ replacement: 'cut.mosc' })), [
      { title: "Change to 'cut.mosc'", edits: [{ place: 'document', range: RANGE, newText: 'cut.mosc' }], preferred: true },
    ]);
    assert.equal(XOSC_FALLBACK.isData!({ replacement: 3 }), false);
  });
});

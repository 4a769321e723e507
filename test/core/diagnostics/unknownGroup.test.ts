import * as assert from 'node:assert/strict';
import { UNKNOWN_GROUP, unknownGroupData, unknownGroupWording } from '../../../server/src/core/diagnostics/unknownGroup';
import { fixContext } from './support';

describe('diagnostics: unknown-group', () => {
  it("lists the file's groups, or says it has none", () => {
    assert.deepEqual(unknownGroupWording('s.xosc', 'Cutin', ['CutIn', 'Brake'], 'CutIn'), {
      severity: 'error',
      code: 'unknown-group',
      message: "'s.xosc' has no ManeuverGroup named 'Cutin'; it has: CutIn, Brake",
      hint: "did you mean 'CutIn'?",
    });
    assert.equal(
      unknownGroupWording('s.xosc', 'X', [], undefined).message,
      "'s.xosc' has no ManeuverGroup named 'X'; it has no ManeuverGroup",
    );
    assert.deepEqual(unknownGroupData(['A'], undefined), { groups: ['A'] });
  });

  it('offers the closest group first, preferred, then every other one, at most 20', async () => {
    const groups = Array.from({ length: 30 }, (_, index) => `G${index}`);
    const fixes = await UNKNOWN_GROUP.fixes!(fixContext({ suggestion: 'G7', groups }));
    assert.equal(fixes.length, 20);
    assert.deepEqual(
      fixes.slice(0, 2).map((fix) => [fix.title, fix.preferred]),
      [
        ["Change to 'G7'", true],
        ["Change to 'G0'", false],
      ],
    );
  });
});

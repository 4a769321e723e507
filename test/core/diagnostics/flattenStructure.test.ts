import * as assert from 'node:assert/strict';
import { ambiguousGroupWording } from '../../../server/src/core/diagnostics/ambiguousGroup';
import { duplicateGroupWording } from '../../../server/src/core/diagnostics/duplicateGroup';
import { keyMixedDefaultsNote, keyMixedDefaultsWording } from '../../../server/src/core/diagnostics/keyMixedDefaults';
import { noActorsWording, noEntityRefAttributeWording } from '../../../server/src/core/diagnostics/noEntityRef';
import { referenceOutsideGroupWording } from '../../../server/src/core/diagnostics/referenceOutsideGroup';
import { tooDeepWording } from '../../../server/src/core/diagnostics/tooDeep';

/** The wording of the modular structure's diagnostics that have no fix: one module each, read by core/flatten/link.ts. */
describe('diagnostics: the shape of references and groups', () => {
  it('reference-outside-group and no-entity-ref', () => {
    assert.equal(referenceOutsideGroupWording().message, 'a ScenarioReference must stand directly inside a ManeuverGroup');
    assert.equal(
      noActorsWording('Cut').message,
      `ManeuverGroup 'Cut' has no <Actors><EntityRef entityRef="..."/></Actors>, so the imported groups have no actor`,
    );
    assert.deepEqual(noEntityRefAttributeWording(), {
      severity: 'error',
      code: 'no-entity-ref',
      message: 'this EntityRef has no entityRef attribute',
      hint: 'write entityRef="NAME" with the name of a ScenarioObject',
    });
  });

  it('too-deep, ambiguous-group and duplicate-group', () => {
    assert.equal(tooDeepWording(3, 'a -> b -> c -> d').message, 'references nest deeper than 3 files: a -> b -> c -> d');
    assert.deepEqual(ambiguousGroupWording('s.xosc', 'G'), {
      severity: 'warning',
      code: 'ambiguous-group',
      message: "'s.xosc' has more than one ManeuverGroup named 'G'; the first one is used",
      hint: undefined,
    });
    assert.equal(
      duplicateGroupWording('G').message,
      "another ManeuverGroup is already named 'G'; a reference to that name takes the first one",
    );
  });

  it('key-mixed-defaults counts each default', () => {
    const wording = keyMixedDefaultsWording(
      'speed',
      3,
      new Map([
        ['10', 2],
        ['20', 1],
      ]),
      '30',
    );
    assert.equal(wording.message, "key 'speed' sets 3 attributes whose defaults differ: '10' (2×), '20' (1×); all of them get '30'");
    assert.equal(wording.severity, 'warning');
    assert.equal(keyMixedDefaultsNote('value', '10'), "'value' with default '10'");
  });
});

import * as assert from 'node:assert/strict';
import {
  declaredAroundGroupWording,
  firstCarriedKeptWording,
  keptDeclarationNote,
  mainDeclarationKeptWording,
  PARAMETER_CONFLICT,
  sourceDeclarationNote,
} from '../../../server/src/core/diagnostics/parameterConflict';

/** Where flattening reports these: test/core/semantics-flatten.test.ts (the carry of declarations, SPEC 11). */
describe('diagnostics: parameter-conflict', () => {
  it('words each way two declarations of one name disagree, and the notes on the other declaration', () => {
    assert.deepEqual(mainDeclarationKeptWording('TargetSpeed', '30', 'Accelerate', 'speed_up.xosc:5', '20'), {
      severity: 'warning',
      code: 'parameter-conflict',
      message:
        "parameter 'TargetSpeed' is declared here with value '30', but the imported group 'Accelerate' uses the declaration of speed_up.xosc:5 with value '20'; the output keeps this one",
    });
    assert.equal(
      firstCarriedKeptWording('Speed', '1', '2').message,
      "imported groups use two declarations of parameter 'Speed' with different values; the output keeps the first one carried (value '1'), not this one (value '2')",
    );
    assert.equal(
      declaredAroundGroupWording('Outer', 'Speed', '1', '2').message,
      "the imported group 'Outer' uses parameter 'Speed' declared with value '1' in its source, but in this file it takes the value '2' of a declaration around the group",
    );
    assert.equal(sourceDeclarationNote('20'), "the source's declaration (value '20')");
    assert.equal(keptDeclarationNote('1'), "the declaration the output keeps (value '1')");
    assert.equal(PARAMETER_CONFLICT.severity, 'warning');
  });
});

import * as assert from 'node:assert/strict';
import { TYPE_MISMATCH } from '../../../server/src/core/diagnostics/typeMismatch';
import { ruleIdOf, ruleOf } from '../../../server/src/core/rules';
import { QC } from '../../../server/src/core/diagnostics/qcRules';
import { semanticProblemsOf } from './support';

/** Where the document checks report it: test/server/parameterTypes.test.ts and test/core/values.test.ts. */
describe('diagnostics: type-mismatch', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(TYPE_MISMATCH.code, 'type-mismatch');
    assert.equal(TYPE_MISMATCH.severity, 'error');
    assert.equal(ruleIdOf('type-mismatch'), TYPE_MISMATCH.rule.qcRule ?? 'modular2simple:type-mismatch');
  });

  // The shape of ASAM's checker's test file tests/data/valid_parameter_declaration_in_catalogs/...negative_no_default.xosc.
  it("a catalog entry's parameter declared with an empty value has no default: ASAM's valid_parameter_declaration_in_catalogs rule", async () => {
    const catalog = (value: string) => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="cars" author="t"/>
  <Catalog name="Cars">
    <Vehicle name="Car" vehicleCategory="car">
      <ParameterDeclarations><ParameterDeclaration name="x" parameterType="double" value="${value}"/></ParameterDeclarations>
      <BoundingBox><Center x="$x" y="0" z="0.75"/><Dimensions width="1.8" length="4.5" height="1.5"/></BoundingBox>
      <Performance maxSpeed="50" maxDeceleration="9" maxAcceleration="5"/>
      <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="2.98" positionZ="0.4"/><RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
    </Vehicle>
  </Catalog>
</OpenSCENARIO>
`;
    const mismatches = async (text: string) =>
      (await semanticProblemsOf(text)).filter((problem) => problem.code === 'type-mismatch').map((problem) => ruleOf(problem).id);
    assert.deepEqual(await mismatches(catalog('')), [QC.catalogParameters]);
    assert.deepEqual(await mismatches(catalog('1.5')), []);
    // A value that is no double is a mistake of its own, not a missing default.
    assert.deepEqual(await mismatches(catalog('fast')), ['modular2simple:type-mismatch']);
  });
});

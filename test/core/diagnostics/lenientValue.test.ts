import * as assert from 'node:assert/strict';
import { LENIENT_VALUE } from '../../../server/src/core/diagnostics/lenientValue';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { fixContext, RANGE, semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: lenient-value', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(LENIENT_VALUE.code, 'lenient-value');
    assert.equal(LENIENT_VALUE.severity, 'warning');
    assert.equal(ruleIdOf('lenient-value'), LENIENT_VALUE.rule.qcRule ?? 'modular2simple:lenient-value');
    assert.equal(LENIENT_VALUE.isData!({ relatedReplacement: 'double' }), true);
    assert.equal(LENIENT_VALUE.isData!({ relatedReplacement: 1 }), false);
  });

  it('is what the document checks report', async () => {
    const problems = (
      await semanticProblemsOf(
        roadScenario({ parameters: '<ParameterDeclaration name="P" parameterType="double" value="1"/>', groups: [group(speed('${P}'))] }),
      )
    ).filter((problem) => problem.code === 'lenient-value');
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'warning',
        code: 'lenient-value',
        message:
          "'P' is the parameter $P written without '$': the standard names parameters in expressions only as $P; esmini reads the bare word as text",
        hint: "write '$P'",
      },
    ]);
    assert.deepEqual(problems[0].data, { suggestion: '$P' });
  });

  it("writes the standard's form where the value is, or the parameterType at the declaration in the same document", async () => {
    const fixes = LENIENT_VALUE.fixes!;
    assert.deepEqual(await fixes(fixContext({ suggestion: '$P' })), [
      { title: "Write the standard form '$P'", edits: [{ place: 'document', range: RANGE, newText: '$P' }], preferred: true },
    ]);
    assert.deepEqual(await fixes(fixContext({ relatedReplacement: 'double' }, { sameDocument: true })), [
      {
        title: 'Declare the parameter parameterType="double"',
        edits: [{ place: 'document', range: RANGE, newText: 'double' }],
        preferred: true,
      },
    ]);
    assert.deepEqual(await fixes(fixContext({ relatedReplacement: 'double' }, { sameDocument: false })), []);
    assert.deepEqual(await fixes(fixContext({ relatedReplacement: 'double' })), []);
  });
});

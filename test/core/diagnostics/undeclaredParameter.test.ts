import * as assert from 'node:assert/strict';
import { UNDECLARED_PARAMETER } from '../../../server/src/core/diagnostics/undeclaredParameter';
import { ruleIdOf } from '../../../server/src/core/rules';
import { parseXml } from '../../../server/src/core/xml';
import { roadScenario } from '../../support/fixtures';
import { applyEdits } from '../../support/textEdits';
import { group, speed } from './semanticSupport';
import { fixContext, RANGE, semanticProblemsOf, wordingOf } from './support';

/** `text` after the module's fix of an undeclared `name`, its scopes the root's alone, `Speed` declared elsewhere as a double 30. */
async function declared(text: string, name: string): Promise<{ title: string; text: string } | undefined> {
  const root = parseXml(text).root;
  const scopes = {
    scopes: root ? [root] : [],
    root,
    declarationOf: (wanted: string) => (wanted === 'Speed' ? { type: 'double', value: '30', from: 'simple.xosc' } : undefined),
  };
  const [fix] = await UNDECLARED_PARAMETER.fixes!(fixContext({ parameter: name }, undefined, text, RANGE, scopes));
  return fix && { title: fix.title, text: applyEdits(text, fix.edits) };
}

describe('diagnostics: undeclared-parameter', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNDECLARED_PARAMETER.code, 'undeclared-parameter');
    assert.equal(UNDECLARED_PARAMETER.severity, 'error');
    assert.equal(ruleIdOf('undeclared-parameter'), UNDECLARED_PARAMETER.rule.qcRule ?? 'modular2simple:undeclared-parameter');
    assert.equal(UNDECLARED_PARAMETER.isData!({ parameter: 'P' }), true);
    assert.equal(UNDECLARED_PARAMETER.isData!({ parameter: 1 }), false);
  });

  it('is what the document checks report', async () => {
    const problems = (await semanticProblemsOf(roadScenario({ groups: [group(speed('$Nope'))] }))).filter(
      (problem) => problem.code === 'undeclared-parameter',
    );
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'error',
        code: 'undeclared-parameter',
        message: "parameter 'Nope' is not declared in this scope",
        hint: 'declare <ParameterDeclaration name="Nope" parameterType="..." value="..."/> in the ParameterDeclarations of the file or of an enclosing element',
      },
    ]);
    assert.deepEqual(problems[0].data, { parameter: 'Nope' });
  });

  it('declares the parameter in the enclosing ParameterDeclarations, with the type and value of its declaration elsewhere', async () => {
    const text =
      '<OpenSCENARIO>\n  <FileHeader/>\n  <ParameterDeclarations>\n    <ParameterDeclaration name="A" parameterType="int" value="1"/>\n  </ParameterDeclarations>\n</OpenSCENARIO>\n';
    assert.deepEqual(await declared(text, 'Speed'), {
      title: "Declare parameter 'Speed' (value 30 from simple.xosc)",
      text: text.replace(
        '  </ParameterDeclarations>',
        '    <ParameterDeclaration name="Speed" parameterType="double" value="30"/>\n  </ParameterDeclarations>',
      ),
    });
  });

  it('writes ParameterDeclarations after the FileHeader where no scope has them, a string of no value where nothing declares the name', async () => {
    const text = '<OpenSCENARIO>\n  <FileHeader/>\n</OpenSCENARIO>\n';
    assert.deepEqual(await declared(text, 'Other'), {
      title: "Declare parameter 'Other'",
      text: '<OpenSCENARIO>\n  <FileHeader/>\n  <ParameterDeclarations>\n    <ParameterDeclaration name="Other" parameterType="string" value=""/>\n  </ParameterDeclarations>\n</OpenSCENARIO>\n',
    });
  });

  it('offers nothing where the file has no analysis', async () => {
    assert.deepEqual(await UNDECLARED_PARAMETER.fixes!(fixContext({ parameter: 'P' })), []);
  });
});

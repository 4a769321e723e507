import * as assert from 'node:assert/strict';
import { XML, xmlWording } from '../../../server/src/core/diagnostics/xml';
import { ruleIdOf } from '../../../server/src/core/rules';
import { analysisProblemsOf, wordingOf } from './support';

describe('diagnostics: xml', () => {
  it("carries the parser's severity and words, under ASAM's valid_xml_document rule", () => {
    assert.deepEqual(xmlWording('warning', 'a stray text'), { severity: 'warning', code: 'xml', message: 'a stray text' });
    assert.equal(XML.severity, 'error');
    assert.equal(ruleIdOf('xml'), 'asam.net:xosc:1.0.0:xml.valid_xml_document');
  });

  it("is what an analysis reports for the parser's findings", async () => {
    const problems = await analysisProblemsOf({ 'main.xosc': '<OpenSCENARIO><FileHeader>' });
    const found = problems.filter((problem) => problem.code === 'xml');
    assert.ok(found.length > 0, problems.map((problem) => problem.code).join(', '));
    for (const problem of found) assert.deepEqual(wordingOf(problem), xmlWording(problem.severity, problem.message));
  });
});

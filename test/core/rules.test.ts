import * as assert from 'node:assert/strict';
import { RuledProblem, ruleOf } from '../../server/src/core/rules';
import { schemaProblems } from '../../server/src/core/diagnostics/schemaFindings';
import { SchemaCheckMemory } from '../../server/src/core/schema/problems';
import { diskRef } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';

const QC = 'asam.net:xosc:1.0.0:xml.';
const STORYBOARD = '<Storyboard><Init><Actions/></Init><StopTrigger/></Storyboard>';
const HEADER = '<FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="d" author="t"/>';

/** `code rule` of each schema problem of a document. */
function schemaRules(text: string): string[] {
  return schemaProblems(diskRef('/rules/scenario.xosc'), parseXml(text), new SchemaCheckMemory()).map(
    (problem) => `${problem.code} ${ruleOf(problem).id}`,
  );
}

/** Each problem names one rule (issue 18, item 2): ASAM's Quality Checker uid where it has the rule, decided per problem. */
describe('rules: the rule of a problem', () => {
  it("is the code's QC rule, with its description and the link to it; the project's own code otherwise, unlinked", () => {
    assert.deepEqual(ruleOf({ code: 'duplicate-name' }), {
      id: 'asam.net:xosc:1.2.0:reference_control.unique_element_names_on_same_level',
      qcRule: 'asam.net:xosc:1.2.0:reference_control.unique_element_names_on_same_level',
      description: 'The names of the elements on one level (the children of one element) are unique.',
      helpUri:
        'https://github.com/asam-ev/qc-openscenarioxml/blob/main/checker_bundle_doc.md#check_asam_xosc_reference_control_unique_element_names_on_same_level',
    });
    const own = ruleOf({ code: 'unused-parameter' });
    assert.equal(own.id, 'modular2simple:unused-parameter');
    assert.equal(own.qcRule, undefined);
    assert.equal(own.helpUri, undefined);
    assert.equal(own.description, 'A declared parameter is used.');
  });

  it('a root element other than <OpenSCENARIO> is xml.root_tag_is_openscenario; an unknown element below it valid_schema', () => {
    assert.deepEqual(schemaRules(`<OpenScenario>${HEADER}</OpenScenario>`), [`schema-unknown-element ${QC}root_tag_is_openscenario`]);
    assert.deepEqual(
      schemaRules(`<OpenSCENARIO>${HEADER}<Entitys/>${STORYBOARD}</OpenSCENARIO>`).filter((line) =>
        line.startsWith('schema-unknown-element'),
      ),
      [`schema-unknown-element ${QC}valid_schema`],
    );
  });

  it('a root without a FileHeader is xml.fileheader_is_present; one out of order is valid_schema', () => {
    assert.deepEqual(schemaRules('<OpenSCENARIO/>'), [`schema-missing-element ${QC}fileheader_is_present`]);
    assert.deepEqual(
      schemaRules(`<OpenSCENARIO><Entities/>${HEADER}${STORYBOARD}</OpenSCENARIO>`).filter((line) => !line.includes('valid_schema')),
      [],
    );
  });

  it("a FileHeader's revMajor/revMinor missing or not an unsignedShort is xml.version_is_defined; its other attributes are valid_schema", () => {
    const header = (attributes: string) => `<OpenSCENARIO><FileHeader ${attributes}/><Entities/>${STORYBOARD}</OpenSCENARIO>`;
    const fileHeaderRules = (attributes: string) =>
      schemaRules(header(attributes)).filter((line) => /^schema-(missing-attribute|value) /.test(line));
    assert.deepEqual(fileHeaderRules('revMajor="1" date="2026-01-01T00:00:00" description="d" author="t"'), [
      `schema-missing-attribute ${QC}version_is_defined`,
    ]);
    assert.deepEqual(fileHeaderRules('revMajor="-1" revMinor="70000" date="2026-01-01T00:00:00" description="d" author="t"'), [
      `schema-value ${QC}version_is_defined`,
      `schema-value ${QC}version_is_defined`,
    ]);
    assert.deepEqual(fileHeaderRules('revMajor="1" revMinor="2" date="yesterday" description="d"'), [
      `schema-missing-attribute ${QC}valid_schema`,
      `schema-value ${QC}valid_schema`,
    ]);
  });

  it('decides by what a problem is about, not by its code alone', () => {
    const value: RuledProblem = { code: 'schema-value' };
    assert.equal(ruleOf(value).id, `${QC}valid_schema`);
    assert.equal(ruleOf({ ...value, subject: { element: 'FileHeader', attribute: 'revMinor' } }).id, `${QC}version_is_defined`);
    assert.equal(ruleOf({ ...value, subject: { element: 'Vehicle', attribute: 'revMinor' } }).id, `${QC}valid_schema`);
  });
});

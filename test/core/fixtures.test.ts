import * as assert from 'node:assert/strict';
import { schemaFindingWords } from '../../server/src/core/diagnostics/schemaFindings';
import { checkSchema } from '../../server/src/core/schema/validate';
import { parseXml } from '../../server/src/core/xml';
import {
  act,
  catalogFile,
  element,
  EMPTY_INIT,
  fileHeader,
  maneuver,
  maneuverGroup,
  MANEUVER_CATALOG,
  outerGroup,
  parameterDeclarations,
  roadScenario,
  scenarioDocument,
  speedChangeGroup,
  speedEvent,
  story,
  vehicleObject,
} from '../support/fixtures';

/** The schema's errors in `text` (the modular extension allowed where `modular`), as the editor words them. */
function schemaProblems(text: string, modular = false): string[] {
  return checkSchema(parseXml(text), { modular })
    .findings.filter((finding) => finding.severity === 'error')
    .map((finding) => `${finding.element.name}: ${schemaFindingWords(finding).message}`);
}

/** A StartTrigger's children (ten spaces in): after 1 s. */
const AFTER_ONE_SECOND = `          <ConditionGroup>
            <Condition name="T" delay="0" conditionEdge="rising">
              <ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition>
            </Condition>
          </ConditionGroup>
`;

/** A scenario written with every skeleton builder that claims to write standard OpenSCENARIO. */
function builtScenario(): string {
  const groups =
    speedChangeGroup('Faster', 'Ego', '20', 'Ego') + maneuverGroup('Slower', 'Ego', maneuver('M', speedEvent('Slow', '$Speed')));
  return scenarioDocument({
    header: fileHeader(),
    parameters: parameterDeclarations([['Speed', 'double', '5']], 4),
    catalogLocations: '',
    roadNetwork: '',
    entities: vehicleObject('Ego'),
    storyboard:
      EMPTY_INIT +
      story(
        'S',
        act('A', groups) + act('B', groups.replaceAll('name="', 'name="B'), AFTER_ONE_SECOND),
        parameterDeclarations([['Gap', 'double', '2']], 8),
      ) +
      element('StopTrigger', '', 4),
  });
}

describe('test fixtures: the shared skeleton builders write schema-valid OpenSCENARIO', () => {
  it('a scenario of the builders (FileHeader, declarations, EMPTY_INIT, Story, Acts, groups, Maneuver, events) is valid', () => {
    const text = builtScenario();
    assert.deepEqual(schemaProblems(text), []);
    // The check is not vacuous: a broken Init or an Act without its StartTrigger is found.
    assert.notDeepEqual(schemaProblems(text.replace(EMPTY_INIT, EMPTY_INIT.replace('Actions', 'Action'))), []);
    assert.notDeepEqual(schemaProblems(text.replace('        <StartTrigger/>\n', '')), []);
  });

  it('roadScenario, catalogFile and MANEUVER_CATALOG are valid', () => {
    assert.deepEqual(schemaProblems(roadScenario({ groups: [speedChangeGroup('G', 'Ego', '10', 'Ego')] })), []);
    assert.deepEqual(schemaProblems(MANEUVER_CATALOG), []);
    assert.deepEqual(schemaProblems(catalogFile('ManeuverCatalog', maneuver('M', speedEvent('E', '3')).replace(/^ {6}/gm, ''))), []);
  });

  it("a main's outer group of references is valid with the modular extension, and only with it", () => {
    const main = builtScenario().replace(
      '      <Act name="A">\n',
      `      <Act name="A">\n${outerGroup('Outer', 'Ego', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters: [['k', 'v']] }] }])}`,
    );
    assert.deepEqual(schemaProblems(main, true), []);
    assert.notDeepEqual(schemaProblems(main, false), []);
  });
});

import * as assert from 'node:assert/strict';
import { previewLineFor } from '../../client/src/previewSync';

const sourceLines = [
  '<OpenSCENARIO>', //                                   0
  '  <Entities><ScenarioObject name="ego"/></Entities>', // 1
  '  <Story name="S">', //                                2
  '    <ManeuverGroup name="Cut" maximumExecutionCount="1">', // 3
  '      <Actors><EntityRef entityRef="ego"/></Actors>', // 4
  '      <ScenarioReference scenarioFileName="a.xosc">', // 5
  '        <ManeuverGroupReference maneuverGroupName="Lane"/>', // 6
  '      </ScenarioReference>', //                        7
  '    </ManeuverGroup>', //                              8
  '    <ManeuverGroup name="Plain">', //                  9
  '      <Maneuver name="Own"/>', //                      10
  '    </ManeuverGroup>', //                              11
  '  </Story>', //                                       12
  '</OpenSCENARIO>', //                                   13
];
const source = sourceLines.join('\n');

// Flattened: lines 3 to 8 (the group Cut) replaced by the imported group Cut.Lane, six lines too.
const imported = [
  '    <ManeuverGroup maximumExecutionCount="1" name="Cut.Lane">',
  '      <Actors><EntityRef entityRef="ego"/></Actors>',
  '      <Maneuver name="LaneManeuver">',
  '        <Event name="E"/>',
  '      </Maneuver>',
  '    </ManeuverGroup>',
];
const preview = [...sourceLines.slice(0, 3), ...imported, ...sourceLines.slice(9)].join('\n');

describe('client: the flattened preview follows the cursor', () => {
  it('shows a referencing group as the group imported in its place', () => {
    for (const line of [3, 4, 5, 6, 7]) assert.equal(previewLineFor(source, preview, line), 3, `line ${line}`);
  });

  it('shows other lines where the same text stands, through the nearest line that occurs once', () => {
    assert.equal(previewLineFor(source, preview, 2), 2);
    assert.equal(previewLineFor(source, preview, 10), 10);
    assert.equal(previewLineFor(source, preview.replace('<Event name="E"/>', '<Event name="E"/>\n        <Event name="F"/>'), 10), 11);
  });

  it('gives no line when nothing anchors it', () => {
    assert.equal(previewLineFor(source, '<!-- cannot be flattened -->', 10), undefined);
    assert.equal(previewLineFor(source, preview, 99), undefined);
  });
});

import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { previewLineOf } from '../../common/src/lineSegments';
import { previewLineMap } from '../../server/src/core/previewLines';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

const EXAMPLES = path.resolve(__dirname, '..', '..', 'examples');

async function previewOf(root: string, main = 'main.xosc') {
  const store = new ScenarioStore({ root, scenarioPath: [] });
  const result = await new Flattener(store).flatten(diskRef(path.join(root, main)));
  assert.ok(result.text, 'no flattened text');
  return { text: result.text, lines: previewLineMap(result.source), source: fs.readFileSync(path.join(root, main), 'utf8') };
}

describe('core: where the flattened preview shows each line of its source', () => {
  it('maps every line outside referencing groups to the same text, and each group reference to its imported group (examples/main.xosc)', async () => {
    const { text, lines, source } = await previewOf(EXAMPLES);
    const sourceLines = source.split('\n');
    const previewLines = text.split('\n');
    const groupStarts = new Map([
      ['maneuverGroupName="CutIn"', 'name="CutInVehicle.CutIn"'],
      ['maneuverGroupName="Brake.HardBrake"', 'name="LeadVehicle.Brake.HardBrake"'],
      ['maneuverGroupName="Walker.Crossing"', 'name="Pedestrian.Walker.Crossing"'],
    ]);
    let insideGroup = false;
    for (let line = 0; line < sourceLines.length; line++) {
      const shown = previewLineOf(lines, line);
      assert.ok(shown !== undefined, `line ${line + 1} is not mapped`);
      const written = sourceLines[line].trim();
      if (/<ManeuverGroup maximumExecutionCount="1" name="(CutInVehicle|LeadVehicle|Pedestrian)"/.test(written)) insideGroup = true;
      const reference = [...groupStarts.keys()].find((key) => written.includes(key));
      if (reference)
        assert.match(
          previewLines[shown],
          new RegExp(`<ManeuverGroup\\b.*${groupStarts.get(reference)?.replace(/\./g, '\\.')}`),
          `line ${line + 1} (${written})`,
        );
      else if (insideGroup)
        assert.match(previewLines[shown], /<ManeuverGroup\b/, `line ${line + 1} (${written}) does not show at an imported group`);
      else assert.equal(previewLines[shown].trim(), written, `line ${line + 1}`);
      if (insideGroup && written === '</ManeuverGroup>') insideGroup = false;
    }
  });

  it('keeps lines apart where a stripped parameterAttributes stood on a line of its own', async () => {
    const simple = scenario(simpleGroup('Go')).replace(/ parameterAttributes=/, '\n            parameterAttributes=');
    const root = temporaryWorkspace({
      'simple.xosc': simple,
      'main.xosc': scenario(outerGroup('Car1', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])),
    });
    const { text, lines } = await previewOf(root, 'simple.xosc');
    const sourceLines = simple.split('\n');
    const previewLines = text.split('\n');
    assert.equal(previewLines.length, sourceLines.length - 1, 'stripping did not join two lines; the fixture tests nothing');
    for (let line = 0; line < sourceLines.length; line++) {
      const shown = previewLineOf(lines, line);
      assert.ok(shown !== undefined);
      if (sourceLines[line].trim().startsWith('parameterAttributes=')) continue;
      const visible = sourceLines[line].replace(/\s*parameterAttributes="[^"]*"/, '').trim();
      assert.ok(
        previewLines[shown].includes(visible) || visible.includes(previewLines[shown].trim()),
        `line ${line + 1}: ${visible} shown as ${previewLines[shown]}`,
      );
    }
  });

  it('shifts the lines after text carried into the root (declarations, catalog directories) by what was carried', async () => {
    const fixture = path.resolve(__dirname, '..', 'fixtures', 'semantics');
    const { text, lines, source } = await previewOf(fixture);
    assert.ok(text.split('\n').length > source.split('\n').length - 20, 'nothing was flattened');
    const previewLines = text.split('\n');
    const sourceLines = source.split('\n');
    const unchanged = ['<Storyboard>', '</Storyboard>', '</OpenSCENARIO>', '<Entities>', '<RoadNetwork>'];
    let checked = 0;
    sourceLines.forEach((written, line) => {
      if (!unchanged.includes(written.trim())) return;
      checked++;
      assert.equal(previewLines[previewLineOf(lines, line) ?? -1]?.trim(), written.trim(), `line ${line + 1}`);
    });
    assert.ok(checked >= 3, `only ${checked} lines checked`);
  });

  it('answers no line outside the file', async () => {
    const { lines, source } = await previewOf(EXAMPLES);
    assert.equal(previewLineOf(lines, source.split('\n').length + 5), undefined);
    assert.equal(previewLineOf(lines, -1), undefined);
  });
});

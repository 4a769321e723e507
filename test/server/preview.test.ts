import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { previewLineOf } from '../../common/src/lineSegments';
import { PreviewRequest, type PreviewResult } from '../../common/src/protocol';
import { serveExamples } from './harness';
import { positionAfter } from '../support/cursor';

describe('language server: the live preview request (JSON-RPC)', function () {
  const examples = serveExamples();

  it('answers the flattened text of the unsaved edit and where each source line shows, from the flattener', async function () {
    const mainPath = path.join(examples.root(), 'main.xosc');
    const text = fs.readFileSync(mainPath, 'utf8');
    const uri = await examples.client().openFile(mainPath);
    const at = positionAfter(text, 'key="AbsoluteTargetSpeed.value" value="');
    await examples.client().change(uri, [{ range: { start: at, end: { line: at.line, character: at.character + 4 } }, text: '31.25' }]);
    const result = await examples.client().request<PreviewResult>(PreviewRequest.method, { uri });
    assert.ok(result.text, JSON.stringify(result.problems));
    assert.ok(result.text.includes('value="31.25"'), 'the preview does not hold the unsaved edit');
    const previewLines = result.text.split('\n');
    // The key's line shows at the group imported for its reference; a line outside groups at itself.
    const shown = previewLineOf(result.lines, at.line);
    assert.ok(shown !== undefined);
    assert.match(previewLines[shown], /<ManeuverGroup .*name="CutInVehicle\.CutIn"/);
    const story = positionAfter(text, '<Story name="EncounterStory"').line;
    assert.equal(previewLines[previewLineOf(result.lines, story) ?? -1].trim(), '<Story name="EncounterStory">');
    const trigger = positionAfter(text, '<Condition name="ActStart"').line;
    assert.equal(previewLines[previewLineOf(result.lines, trigger) ?? -1].trim(), text.split('\n')[trigger].trim());
  });

  it('answers no text and no lines, with the problems, when the scenario cannot be flattened', async function () {
    const mainPath = path.join(examples.root(), 'main.xosc');
    const uri = await examples
      .client()
      .open(
        `${new URL(`file://${mainPath}`).href}`,
        fs.readFileSync(mainPath, 'utf8').replace('scenarioFileName="lane_change.xosc"', 'scenarioFileName="nowhere.xosc"'),
      );
    const result = await examples.client().request<PreviewResult>(PreviewRequest.method, { uri });
    assert.equal(result.text, null);
    assert.deepEqual(result.lines, []);
    assert.ok(result.problems.some((problem) => problem.severity === 'error' && /nowhere\.xosc/.test(problem.message)));
  });
});

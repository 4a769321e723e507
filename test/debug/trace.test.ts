import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiCatalogs, esminiRoads } from '../support/esmini';
import { requireEsminiLibrary } from '../support/esminiBinaries';
import { runCli } from '../support/fixtures';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { temporaryFolder } from '../support/temporaryDirectory';

const cutIn = path.join(openscenarioDir, 'esmini', 'cut-in.xosc');

describe('cli: run --trace', function () {
  this.timeout(120_000);
  before(function () {
    requireEsminiLibrary(this);
    if (!fs.existsSync(cutIn)) this.skip();
  });

  it("writes each transition and condition firing of cut-in.xosc as a JSON line, at esmini's times, on its source line", () => {
    const folder = temporaryFolder();
    const out = path.join(folder, 'trace.jsonl');
    const roads = `${esminiRoads}:${path.join(esminiCatalogs, 'Vehicles')}`;
    const run = runCli(['run', cutIn, '--road-path', roads, '--trace', out, '--duration', '25']);
    assert.equal(run.status, 0, run.stderr);
    const records = fs
      .readFileSync(out, 'utf8')
      .trim()
      .split('\n')
      .map((line) => JSON.parse(line) as Record<string, unknown>);
    const event = records.find((record) => String(record.element).endsWith('::CutInEvent') && record.state === 'running');
    assert.deepEqual(
      { time: event?.time, type: event?.type, line: event?.line, file: path.basename(String(event?.file)) },
      { time: 6.5, type: 'Event', line: 114, file: 'cut-in.xosc' },
    );
    const condition = records.find((record) => String(record.element).endsWith('::CutInStartCondition'));
    assert.deepEqual(
      {
        rule: condition?.rule,
        threshold: condition?.threshold,
        measured: condition?.measured,
        line: condition?.line,
        state: condition?.state,
      },
      { rule: 'greaterThan', threshold: 0.4, measured: 0.41, line: 129, state: 'true' },
    );
    assert.deepEqual(records.at(-1), { time: 22, element: 'storyBoard', type: 'Storyboard', state: 'complete' });
  });
});

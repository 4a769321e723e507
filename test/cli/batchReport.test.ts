import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { XMLValidator } from 'fast-xml-parser';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { deterministic, distributionFile, fileHeader, runCli } from '../support/fixtures';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const FIXTURES = path.join(repoRoot, 'test', 'fixtures', 'variations');

/** follow.xosc with a distribution of its two speeds: 2 x 2 = 4 concrete scenarios. */
function reportFolder(): string {
  const folder = temporaryFolder('m2s-report-');
  fs.copyFileSync(path.join(FIXTURES, 'follow.xosc'), path.join(folder, 'follow.xosc'));
  fs.writeFileSync(
    path.join(folder, 'd.xosc'),
    distributionFile(
      'follow.xosc',
      deterministic(`      <DeterministicSingleParameterDistribution parameterName="EgoSpeed">
        <DistributionSet><Element value="10"/><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="LeadSpeed">
        <DistributionSet><Element value="5"/><Element value="15"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
`),
      fileHeader({ date: '2024-01-01T00:00:00', description: 'report', author: 'test' }),
    ),
  );
  return folder;
}

describe('cli: batch writes results.html and keeps runs', function () {
  this.timeout(180_000);
  let root: string | undefined;
  afterEach(() => {
    if (root) fs.rmSync(root, { recursive: true, force: true });
    root = undefined;
  });

  it('results.html is well-formed, self-contained and has every row; --keep-runs keeps each run under runs/INDEX/', function () {
    requireEsmini(this);
    root = reportFolder();
    const args = [
      'batch',
      'd.xosc',
      '--results',
      'results',
      '--jobs',
      '2',
      '--keep-runs',
      '--road-path',
      esminiRoads,
      '--esmini',
      esminiBinary,
    ];
    const run = runCli(args, { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /results\.html/);
    const html = fs.readFileSync(path.join(root, 'results', 'results.html'), 'utf8');
    assert.ok(html.startsWith('<!DOCTYPE html>\n'));
    const validity = XMLValidator.validate(html.replace(/^<!DOCTYPE html>\n/, ''));
    assert.equal(validity, true, JSON.stringify(validity));
    assert.doesNotMatch(html, /<script|\bsrc=|https?:\/\/(?!www\.w3\.org\/2000\/svg)/, 'nothing loaded from elsewhere, no script');
    const csvRows = fs
      .readFileSync(path.join(root, 'results', 'results.csv'), 'utf8')
      .trim()
      .split('\n')
      .slice(1);
    assert.equal(csvRows.length, 4);
    const tableRows = [...html.matchAll(/<tr class="(\w+)" data-index="(\d+)">/g)].map((match) => match[2]);
    assert.deepEqual(tableRows, ['0', '1', '2', '3']);
    const points = [...html.matchAll(/<circle class="point" data-index="(\d+)"/g)].map((match) => match[1]).sort();
    assert.deepEqual(points, ['0', '1', '2', '3'], 'a point per row in the scatter');
    assert.match(html, />EgoSpeed</);
    assert.match(html, />LeadSpeed</);
    for (const index of ['0', '1', '2', '3']) {
      for (const file of ['scenario.xosc', 'trajectories.csv', 'esmini.log'])
        assert.ok(fs.existsSync(path.join(root, 'results', 'runs', index, file)), `runs/${index}/${file}`);
      // The CSV's header names the kept scenario, not the run's private folder (runs/.running/esmini-run-*/), gone after the run.
      const header = /^Scenario File Name: (.*)$/m.exec(
        fs.readFileSync(path.join(root, 'results', 'runs', index, 'trajectories.csv'), 'utf8'),
      );
      assert.equal(header?.[1], path.join(root, 'results', 'runs', index, 'scenario.xosc'));
    }
    assert.deepEqual(fs.readdirSync(path.join(root, 'results', 'runs')).sort(), ['0', '1', '2', '3'], 'nothing else in runs/');
    // Resumed with nothing to run: the report is written again, the same.
    fs.rmSync(path.join(root, 'results', 'results.html'));
    const again = runCli(args, { cwd: root });
    assert.equal(again.status, 0, again.stderr);
    assert.equal(fs.readFileSync(path.join(root, 'results', 'results.html'), 'utf8'), html);
  });

  it('--keep-runs does not go with --queue', () => {
    const run = runCli(['batch', 'd.xosc', '--results', 'r', '--keep-runs', '--queue', 'redis://127.0.0.1:1'], { cwd: os.tmpdir() });
    assert.equal(run.status, 2);
    assert.match(run.stderr, /--keep-runs .* does not go with --queue/);
  });
});

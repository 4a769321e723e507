import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { firstDifference } from '../../server/src/core/equivalence';
import { Flattener } from '../../server/src/core/flatten';
import { packFolder } from '../../server/src/core/pack';
import { formatProblem } from '../../server/src/core/problems';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { libraryStats } from '../../server/src/core/stats';
import { caseStudyDir, corpusDir, libraryDir, requireCorpus, sharedDir } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const scenarios = fs.existsSync(libraryDir)
  ? fs
      .readdirSync(libraryDir)
      .filter((name) => name.startsWith('modular_'))
      .sort()
  : [];

describe('corpus: the 31 library examples (SPEC 8)', function () {
  before(function () {
    requireCorpus(this);
  });

  it('holds 31 examples', () => assert.equal(scenarios.length, 31));

  for (const name of scenarios) {
    it(`${name}: result.mosc flattens to the equivalent of result.xosc`, async () => {
      const store = new ScenarioStore({ scenarioPath: [libraryDir], root: path.join(libraryDir, name) });
      const result = await new Flattener(store).flatten(childRef(diskRef(path.join(libraryDir, name, 'result.mosc')), 'main.xosc'));
      assert.ok(result.text, result.problems.map((p) => formatProblem(p)).join('\n'));
      assert.equal(firstDifference(result.text, fs.readFileSync(path.join(libraryDir, name, 'result.xosc'), 'utf8')), undefined);
    });
  }
});

describe('corpus: the case study', function () {
  before(function () {
    requireCorpus(this);
  });
  const expected = () => fs.readFileSync(path.join(corpusDir, 'case-study.expected.xosc'), 'utf8');

  it('unpacked: reports the ignored override and, forced, matches the original output', async () => {
    const store = new ScenarioStore({ scenarioPath: [], root: caseStudyDir });
    const strict = await new Flattener(store).flatten(diskRef(path.join(caseStudyDir, 'main.xosc')));
    assert.equal(strict.text, undefined, 'an override that never applied is an error by default');
    const unknown = strict.problems.filter((p) => p.code === 'unknown-key');
    assert.ok(unknown.length >= 1 && unknown.every((p) => /AbsoluteTargetSpeed\.value/.test(p.message)));
    const declaration = strict.problems.find((p) => p.code === 'unknown-parameter-attribute');
    assert.equal(declaration?.source.disk, path.join(caseStudyDir, 'simple_2.xosc'));
    assert.equal(declaration?.range.start.line, 128);
    const fallback = strict.problems.find((p) => p.code === 'xosc-fallback');
    assert.match(fallback?.message ?? '', /modular_1\.xosc/);

    const forced = await new Flattener(store).flatten(diskRef(path.join(caseStudyDir, 'main.xosc')), { force: true });
    assert.ok(forced.text);
    assert.equal(firstDifference(forced.text, expected()), undefined);
  });

  it('packed by our pack into nested .mosc files: matches the original output', async () => {
    const work = temporaryFolder('m2s-case-');
    const store = new ScenarioStore({ scenarioPath: [], root: caseStudyDir });
    const packed = await packFolder(caseStudyDir, store);
    assert.ok(packed.bytes, packed.problems.map((p) => formatProblem(p)).join('\n'));
    assert.deepEqual([...packed.entries].sort(), ['main.xosc', 'modular_1.mosc', 'modular_2.mosc']);
    const packagePath = path.join(work, 'case-study.mosc');
    fs.writeFileSync(packagePath, packed.bytes);
    const isolated = new ScenarioStore({ scenarioPath: [], root: work });
    const result = await new Flattener(isolated).flatten(childRef(diskRef(packagePath), 'main.xosc'), { force: true });
    assert.ok(result.text, result.problems.map((p) => formatProblem(p)).join('\n'));
    assert.equal(firstDifference(result.text, expected()), undefined);
  });
});

/** Reads Table 1 from the paper itself, so the expected figures are the paper's, not ours. */
function paperTable(): { rows: [number, number, number][]; total: [number, number, number] } {
  const paper = fs.readFileSync(path.join(sharedDir, 'seed', 'modular2simple-paper.md'), 'utf8');
  const rows: [number, number, number][] = [];
  let total: [number, number, number] = [0, 0, 0];
  for (const line of paper.split('\n')) {
    const cells = line.split('|').map((cell) => cell.replace(/[*,]/g, '').trim());
    if (cells.length < 6) continue;
    const numbers = cells.slice(2, 5).map(Number);
    if (numbers.some((n) => Number.isNaN(n)) || cells[2] === '') continue;
    if (cells[1] === 'Total') total = numbers as [number, number, number];
    else if (/^\d+$/.test(cells[1])) rows.push(numbers as [number, number, number]);
  }
  return { rows, total };
}

describe("corpus: stats reproduce the paper's Table 1 (SPEC 9)", function () {
  before(function () {
    requireCorpus(this);
  });

  it('every row and the totals', async () => {
    const table = paperTable();
    assert.equal(table.rows.length, 31);
    const stats = await libraryStats(libraryDir);
    assert.deepEqual(
      stats.rows.map((row) => [row.modularLines, row.flattenedLines, row.reduction]),
      table.rows,
    );
    assert.deepEqual(
      stats.shared.map((item) => path.basename(item.file) + ':' + item.lines),
      ['simple_1.xosc:247', 'simple_2.xosc:276'],
    );
    assert.deepEqual([stats.totals.modularLines, stats.totals.flattenedLines, stats.totals.reduction], table.total);
  });
});

import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { readScenarioParameters, valuesAfter } from '../../server/src/core/variations/concrete';
import { loadVariations, Variations } from '../../server/src/core/variations';
import { esminiXodrDir, requireEsminiProgram } from '../support/esminiBinaries';
import { sharedDir } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';
import {
  deterministic,
  distributionFile,
  element,
  EMPTY_INIT,
  fileHeader,
  parameterDeclarations,
  runCli,
  scenarioDocument,
} from '../support/fixtures';

/**
 * The expansion against esmini itself: `--return_nr_permutations` for the count (read from its log line,
 * since the exit code is the count modulo 256) and `--param_permutation I --save_xosc` for the values of
 * concrete scenario I (esmini saves SCENARIO_{I+1}_of_{N}.xosc in its working folder). `--save_xosc quit`
 * is not used: esmini 3.6 then loops on the same permutation forever; the scenarios here stop at once.
 */

/** A scenario on `road` with the parameters the distributions vary, stopping at once. */
const SCENARIO = (road: string): string =>
  scenarioDocument({
    header: fileHeader({ description: 'variations against esmini', author: 'm2s' }),
    parameters: parameterDeclarations(
      [
        ['Speed', 'double', '10'],
        ['Gap', 'double', '1'],
        ['Car', 'string', 'car_white'],
        ['Lane', 'int', '-1'],
        ['Weather', 'string', 'dry'],
      ],
      4,
    ),
    catalogLocations: '',
    roadNetwork: `    <LogicFile filepath="${road}"/>\n`,
    entities: '',
    storyboard:
      EMPTY_INIT +
      element(
        'StopTrigger',
        `      <ConditionGroup>
        <Condition name="stop" delay="0" conditionEdge="none">
          <ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition>
        </Condition>
      </ConditionGroup>
`,
        4,
      ),
  });

function distribution(body: string, scenarioFile = 'scenario.xosc'): string {
  return distributionFile(scenarioFile, deterministic(`${body}\n`), fileHeader({ description: 'd', author: 'm2s' }));
}

const single = (name: string, inner: string): string =>
  `      <DeterministicSingleParameterDistribution parameterName="${name}">${inner}</DeterministicSingleParameterDistribution>`;
const range = (name: string, step: string, lower: string, upper: string): string =>
  single(name, `<DistributionRange stepWidth="${step}"><Range lowerLimit="${lower}" upperLimit="${upper}"/></DistributionRange>`);
const set = (name: string, values: string[]): string =>
  single(name, `<DistributionSet>${values.map((v) => `<Element value="${v}"/>`).join('')}</DistributionSet>`);
const multi = (sets: [string, string][][]): string =>
  `      <DeterministicMultiParameterDistribution><ValueSetDistribution>${sets.map((assignments) => `<ParameterValueSet>${assignments.map(([p, v]) => `<ParameterAssignment parameterRef="${p}" value="${v}"/>`).join('')}</ParameterValueSet>`).join('')}</ValueSetDistribution></DeterministicMultiParameterDistribution>`;

/** Distributions written for each deterministic kind esmini expands, and for their combinations. */
const CASES: { name: string; body: string }[] = [
  { name: 'set', body: set('Car', ['car_red', 'a&amp;b', '&lt;x&gt;', 'car blue', '']) },
  { name: 'range accumulating 0.1 to an upper limit reached a hair below', body: range('Speed', '0.1', '0', '1') },
  { name: 'range overshooting its upper limit by accumulation', body: range('Speed', '0.2', '1.1', '1.5') },
  { name: 'range stopping short of its upper limit', body: range('Speed', '0.3', '0', '1') },
  { name: 'range with exact halves at the sixth decimal (printf ties to even)', body: range('Speed', '0.0078125', '0', '0.05') },
  { name: 'negative range through zero', body: range('Gap', '0.1', '-0.3', '0.3') },
  { name: 'large values', body: range('Speed', '1.5', '1000000', '1000003') },
  { name: 'a range of one value', body: range('Lane', '1', '2', '2') },
  {
    name: 'multi-parameter sets assigning different parameters',
    body: multi([
      [
        ['Car', 'car_blue'],
        ['Weather', 'wet'],
      ],
      [['Weather', 'snow']],
      [
        ['Car', 'van'],
        ['Speed', '3'],
        ['Gap', '0.5'],
      ],
    ]),
  },
  {
    name: 'several distributions combined',
    body: [
      range('Speed', '5', '10', '30'),
      set('Car', ['car_red', 'car_yellow']),
      multi([
        [
          ['Weather', 'fog'],
          ['Lane', '-2'],
        ],
        [['Lane', '-3']],
      ]),
      range('Gap', '0.25', '0.5', '1.25'),
    ].join('\n'),
  },
  {
    name: 'the same parameter in two distributions (the later wins)',
    body: [
      set('Speed', ['1', '2']),
      multi([
        [['Speed', '7']],
        [['Gap', '9']],
        [
          ['Gap', '3'],
          ['Gap', '4'],
        ],
      ]),
    ].join('\n'),
  },
  {
    name: 'a larger product, sampled',
    body: [
      range('Speed', '0.5', '0', '20'),
      range('Gap', '0.1', '0.5', '3.5'),
      set('Car', ['a', 'b', 'c']),
      set('Weather', ['dry', 'wet']),
    ].join('\n'),
  },
];

interface EsminiRun {
  status: number | null;
  log: string;
}

function esmini(program: string, cwd: string, args: string[]): EsminiRun {
  const result = spawnSync(program, ['--headless', '--fixed_timestep', '0.1', '--disable_log', ...args], {
    cwd,
    encoding: 'utf8',
    timeout: 60_000,
  });
  return { status: result.status, log: `${result.stdout ?? ''}${result.stderr ?? ''}` };
}

function esminiCount(program: string, dir: string, file: string): number {
  const run = esmini(program, dir, ['--osc', file, '--return_nr_permutations']);
  const match = /Nr permutations: (\d+)/.exec(run.log);
  assert.ok(match, `esmini printed no count for ${file}:\n${run.log}`);
  return Number(match[1]);
}

/** The root parameter values esmini saved for permutation `index`. */
function esminiValues(program: string, dir: string, file: string, scenarioName: string, index: bigint, count: bigint): Map<string, string> {
  const cwd = fs.mkdtempSync(path.join(dir, 'run-'));
  const run = esmini(program, cwd, ['--osc', path.join(dir, file), '--param_permutation', index.toString(), '--save_xosc']);
  const saved = path.join(cwd, `${scenarioName}_${index + 1n}_of_${count}.xosc`);
  assert.ok(fs.existsSync(saved), `esmini saved no ${saved} (status ${run.status}):\n${run.log.slice(-2000)}`);
  const { scenario, problems } = readScenarioParameters(fs.readFileSync(saved, 'utf8'), saved);
  assert.deepEqual(problems, []);
  fs.rmSync(cwd, { recursive: true, force: true });
  const declared = scenario as NonNullable<typeof scenario>;
  return valuesAfter(declared, []);
}

function ourValues(variations: Variations, index: bigint): Map<string, string> {
  const concrete = variations.concreteAt(index);
  assert.ok('text' in concrete);
  const { scenario } = readScenarioParameters(concrete.text, 'ours.xosc');
  return valuesAfter(scenario as NonNullable<typeof scenario>, []);
}

/** Every index when there are few, else the ends, the middle and a fixed spread. */
function sampledIndices(count: bigint): bigint[] {
  if (count <= 40n) return [...Array(Number(count)).keys()].map(BigInt);
  const picks = new Set<bigint>([0n, 1n, count / 2n, count - 2n, count - 1n]);
  for (let k = 1n; k <= 12n; k++) picks.add(((k * 7919n * count) / 100_003n) % count);
  return [...picks].sort((a, b) => (a < b ? -1 : 1));
}

async function compare(program: string, dir: string, file: string, log: string[]): Promise<void> {
  const text = fs.readFileSync(path.join(dir, file), 'utf8');
  const loaded = await loadVariations(text, path.join(dir, file), (p) => fs.promises.readFile(p, 'utf8'));
  assert.deepEqual(loaded.problems, [], `${file}: ${JSON.stringify(loaded.problems)}`);
  const variations = loaded.variations as Variations;
  const count = esminiCount(program, dir, file);
  assert.equal(variations.count, BigInt(count), `${file}: the count`);
  const scenarioName = path.basename(variations.scenarioPath).replace(/\.xosc$/, '');
  const indices = sampledIndices(variations.count);
  for (const index of indices) {
    assert.deepEqual(
      ourValues(variations, index),
      esminiValues(program, dir, file, scenarioName, index, variations.count),
      `${file}: index ${index}`,
    );
  }
  log.push(`${file}: ${count} combinations, ${indices.length} indices compared`);
}

describe('core: variations against esmini (--return_nr_permutations, --param_permutation --save_xosc)', function () {
  this.timeout(600_000);
  let program: string;
  let dir: string;
  const log: string[] = [];

  before(function () {
    program = requireEsminiProgram(this, 'esmini');
    dir = temporaryFolder('m2s-vary-esmini-');
    fs.writeFileSync(path.join(dir, 'scenario.xosc'), SCENARIO(path.join(esminiXodrDir, 'straight_500m.xodr')));
  });
  after(() => {
    if (dir) fs.rmSync(dir, { recursive: true, force: true });
    if (log.length > 0) console.log(log.map((line) => `      ${line}`).join('\n'));
  });

  for (const [n, testCase] of CASES.entries()) {
    it(`${testCase.name}: same count, same values`, async () => {
      const file = `case${n}.xosc`;
      fs.writeFileSync(path.join(dir, file), distribution(testCase.body));
      await compare(program, dir, file, log);
    });
  }

  it("esmini's own cut-in_parameter_set.xosc: same count, same values at every index", async function () {
    const source = path.join(sharedDir, 'corpus', 'openscenario', 'esmini');
    if (!fs.existsSync(path.join(source, 'cut-in_parameter_set.xosc'))) {
      console.log(`    (skipped: ${source} is absent)`);
      this.skip();
    }
    // The scenario names ../xodr/e6mini.xodr and ../xosc/Catalogs: the corpus folder goes in as xosc/ beside xodr/.
    const root = fs.mkdtempSync(path.join(dir, 'esmini-'));
    fs.cpSync(source, path.join(root, 'xosc'), { recursive: true });
    fs.symlinkSync(esminiXodrDir, path.join(root, 'xodr'));
    await compare(program, path.join(root, 'xosc'), 'cut-in_parameter_set.xosc', log);
  });

  it("ValueConstraintGroups (an expression over another parameter, two groups): esmini's numbering kept, the combinations that break them discarded at their own index", async () => {
    // esmini knows no ValueConstraintGroup: its permutation I is combination I of the whole product, whatever the constraints say.
    const constrained = SCENARIO(path.join(esminiXodrDir, 'straight_500m.xodr')).replace(
      '<ParameterDeclaration name="Gap" parameterType="double" value="1"/>',
      `<ParameterDeclaration name="Gap" parameterType="double" value="1">
      <ConstraintGroup><ValueConstraint rule="lessThan" value="\${$Speed - 0.2}"/><ValueConstraint rule="greaterThan" value="0"/></ConstraintGroup>
      <ConstraintGroup><ValueConstraint rule="equalTo" value="$Top"/></ConstraintGroup>
    </ParameterDeclaration>
    <ParameterDeclaration name="Top" parameterType="double" value="2.5"/>`,
    );
    fs.writeFileSync(path.join(dir, 'constrained.xosc'), constrained);
    const file = 'constrainedDistribution.xosc';
    fs.writeFileSync(
      path.join(dir, file),
      distribution(
        [set('Speed', ['1', '2', '3']), set('Gap', ['0.5', '1.5', '2.5', '-1']), set('Car', ['a', 'b'])].join('\n'),
        'constrained.xosc',
      ),
    );
    const loaded = await loadVariations(fs.readFileSync(path.join(dir, file), 'utf8'), path.join(dir, file), (p) =>
      fs.promises.readFile(p, 'utf8'),
    );
    assert.deepEqual(loaded.problems, []);
    const variations = loaded.variations as Variations;
    const count = esminiCount(program, dir, file);
    assert.equal(variations.count, BigInt(count), "the count is esmini's, constraints or not");
    const discarded: bigint[] = [];
    for (let index = 0n; index < variations.count; index++) {
      const theirs = esminiValues(program, dir, file, 'constrained', index, variations.count);
      const concrete = variations.concreteAt(index);
      assert.deepEqual(valuesAfter(variations.scenario, concrete.assignments), theirs, `index ${index}`);
      // The constraint read by hand from esmini's values: 0 < Gap < Speed - 0.2, or Gap = Top (2.5).
      const speed = Number(theirs.get('Speed'));
      const gap = Number(theirs.get('Gap'));
      const holds = (gap < speed - 0.2 && gap > 0) || gap === 2.5;
      assert.equal('broken' in concrete, !holds, `index ${index}: Speed ${speed}, Gap ${gap}`);
      if (!holds) discarded.push(index);
    }
    assert.ok(discarded.length > 0 && discarded.length < count, `some, not all, are discarded: ${discarded.length} of ${count}`);
    const counted = runCli(['vary', file, '--count'], { cwd: dir });
    assert.equal(counted.status, 0, counted.stderr);
    assert.equal(
      counted.stdout.trim(),
      `${count} combinations (esmini's --param_permutation 0..${count - 1}), ${count - discarded.length} kept: ${discarded.length} break the scenario's ValueConstraintGroups and are discarded`,
    );
    const refused = runCli(['vary', file, '--index', discarded[0].toString()], { cwd: dir });
    assert.equal(refused.status, 1);
    assert.match(refused.stderr, new RegExp(`concrete scenario ${discarded[0]} is discarded`));
    log.push(`${file}: ${count} combinations, ${discarded.length} discarded, every index compared`);
  });

  it('UserDefinedDistribution: esmini refuses it, this tool expands type="list" in order', async () => {
    const file = 'userDefined.xosc';
    fs.writeFileSync(
      path.join(dir, file),
      distribution(single('Car', '<UserDefinedDistribution type="list">car_red car_blue\n van</UserDefinedDistribution>')),
    );
    const run = esmini(program, dir, ['--osc', file, '--return_nr_permutations']);
    assert.match(run.log, /UserDefinedDistribution not yet supported/);
    const loaded = await loadVariations(fs.readFileSync(path.join(dir, file), 'utf8'), path.join(dir, file), (p) =>
      fs.promises.readFile(p, 'utf8'),
    );
    const variations = loaded.variations as Variations;
    assert.equal(variations.count, 3n);
    assert.deepEqual(
      [0n, 1n, 2n].map((i) => ourValues(variations, i).get('Car')),
      ['car_red', 'car_blue', 'van'],
    );
  });
});

import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { varyCommand } from '../../server/src/cli/vary';
import { concreteScenarioText, readScenarioParameters } from '../../server/src/core/variations/concrete';
import { assignmentAt, expandDeterministic, formatFixed6, rangeValues } from '../../server/src/core/variations/deterministic';
import { parseDistribution } from '../../server/src/core/variations/distribution';
import { formatVariationProblems, loadVariations } from '../../server/src/core/variations';
import { distributionFile, element, fileHeader, openScenarioFile, parameterDeclarations } from '../support/fixtures';
import { temporaryFolder } from '../support/temporaryDirectory';

const SCENARIO = openScenarioFile(
  element(
    'ParameterDeclarations',
    parameterDeclarations(
      [
        ['Speed', 'double', '10'],
        ['Gap', 'double', '1'],
        ['Car', 'string', 'car_white'],
      ],
      4,
    ),
    2,
  ) + '  <Storyboard/>\n',
  fileHeader({ description: 'variations', author: 'm2s' }),
);

/** A distribution of `scenario`: `body` is what follows its ScenarioFile (four spaces in, not ending its line). */
function distribution(body: string, scenario = 'scenario.xosc'): string {
  return distributionFile(scenario, `${body}\n`, fileHeader({ description: 'd', author: 'm2s' }));
}

const RANGE_AND_SET = `    <Deterministic>
      <DeterministicSingleParameterDistribution parameterName="Speed">
        <DistributionRange stepWidth="0.2"><Range lowerLimit="1.1" upperLimit="1.5"/></DistributionRange>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="Car">
        <DistributionSet><Element value="a"/><Element value="b"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
    </Deterministic>`;

interface Captured {
  code: number;
  out: string[];
  err: string[];
}

async function run(args: string[], cwd?: string): Promise<Captured> {
  const out: string[] = [];
  const err: string[] = [];
  const before = process.cwd();
  if (cwd) process.chdir(cwd);
  try {
    const code = await varyCommand(args, { out: (text) => out.push(text), err: (text) => err.push(text) });
    return { code, out, err };
  } finally {
    process.chdir(before);
  }
}

describe('core: variations, deterministic expansion', () => {
  it('formats range values as C printf("%f") does: six decimals, exact ties to even, negative zero kept', () => {
    // Expected values printed by glibc's printf("%f") (and Python's '%f', which agrees).
    const table: [number, string][] = [
      [0, '0.000000'],
      [-0, '-0.000000'],
      [0.0078125, '0.007812'],
      [0.0390625, '0.039062'],
      [2.5e-7, '0.000000'],
      [-2.5e-7, '-0.000000'],
      [5e-7, '0.000000'],
      [1.0000005, '1.000001'],
      [1.5e-6, '0.000002'],
      [123456789.123456789, '123456789.123457'],
      [1e20, '100000000000000000000.000000'],
      [0.1 + 0.2, '0.300000'],
      [-1.5, '-1.500000'],
      [2 ** -20, '0.000001'],
      [1e-300, '0.000000'],
    ];
    for (const [value, expected] of table) assert.equal(formatFixed6(value), expected, String(value));
  });

  it('steps a range by accumulating doubles, the upper limit counting within 1e-6', () => {
    assert.deepEqual(rangeValues(1.1, 1.5, 0.2), ['1.100000', '1.300000', '1.500000']);
    assert.equal(rangeValues(0, 1, 0.1).length, 11);
    assert.equal(rangeValues(0, 1, 0.1)[10], '1.000000');
    assert.deepEqual(rangeValues(5, 5, 1), ['5.000000']);
    assert.deepEqual(rangeValues(0, 1, 0.4), ['0.000000', '0.400000', '0.800000']);
  });

  it('numbers combinations with the last distribution varying fastest (esmini --param_permutation)', () => {
    const parsed = parseDistribution(distribution(RANGE_AND_SET), '/x/d.xosc');
    assert.deepEqual(parsed.problems, []);
    const { expansion } = expandDeterministic(parsed.distribution?.deterministic ?? [], '/x/d.xosc');
    assert.equal(expansion.count, 6n);
    const values = [0n, 1n, 2n, 3n, 4n, 5n].map((i) =>
      assignmentAt(expansion, i)
        .map((a) => a.value)
        .join(','),
    );
    assert.deepEqual(values, ['1.100000,a', '1.100000,b', '1.300000,a', '1.300000,b', '1.500000,a', '1.500000,b']);
  });

  it('splices values into the scenario and keeps every other byte (BOM, CRLF, quotes, escapes)', () => {
    const text =
      '\uFEFF<?xml version="1.0"?>\r\n<OpenSCENARIO>\r\n  <ParameterDeclarations>\r\n    <ParameterDeclaration name=\'Car\'  parameterType="string" value = \'x\' />\r\n    <ParameterDeclaration name="Speed" parameterType="double" value="1"/>\r\n  </ParameterDeclarations>\r\n  <Storyboard><ParameterDeclarations><ParameterDeclaration name="Car" parameterType="string" value="inner"/></ParameterDeclarations></Storyboard>\r\n</OpenSCENARIO>\r\n';
    const { scenario, problems } = readScenarioParameters(text, '/x/s.xosc');
    assert.deepEqual(problems, []);
    const result = concreteScenarioText(scenario as NonNullable<typeof scenario>, [{ parameter: 'Car', value: "a'&<b", offset: 0 }]);
    assert.equal(result, text.replace("value = 'x'", "value = 'a&apos;&amp;&lt;b'"));
  });
});

describe('core: variations, files and problems', () => {
  let dir: string;
  beforeEach(() => {
    dir = temporaryFolder('m2s-vary-');
    fs.writeFileSync(path.join(dir, 'scenario.xosc'), SCENARIO);
  });
  afterEach(() => fs.rmSync(dir, { recursive: true, force: true }));

  async function problemsOf(body: string, scenario?: string): Promise<string[]> {
    const file = path.join(dir, 'd.xosc');
    const text = distribution(body, scenario);
    const loaded = await loadVariations(text, file, (p) => fs.promises.readFile(p, 'utf8'));
    return formatVariationProblems(loaded.problems, loaded.lines, dir);
  }

  it('names file:line:col for a parameter the scenario lacks, a missing ScenarioFile, a step of 0 or below, an empty range', async () => {
    assert.deepEqual(await problemsOf(RANGE_AND_SET.replace('"Car"', '"Colour"')), [
      "d.xosc:10:64: error: parameter 'Colour' is not declared in the root ParameterDeclarations of scenario.xosc",
    ]);
    const missing = await problemsOf(RANGE_AND_SET, 'nowhere.xosc');
    assert.equal(missing.length, 1);
    assert.match(missing[0], /^d\.xosc:5:29: error: ScenarioFile nowhere\.xosc .*no such file$/);
    assert.deepEqual(await problemsOf(RANGE_AND_SET.replace('stepWidth="0.2"', 'stepWidth="0"')), [
      'd.xosc:8:39: error: stepWidth 0 must be greater than 0',
    ]);
    assert.deepEqual(await problemsOf(RANGE_AND_SET.replace('stepWidth="0.2"', 'stepWidth="-1"')), [
      'd.xosc:8:39: error: stepWidth -1 must be greater than 0',
    ]);
    assert.deepEqual(await problemsOf(RANGE_AND_SET.replace('upperLimit="1.5"', 'upperLimit="1"')), [
      'd.xosc:8:44: error: the range is empty: upperLimit 1 is below lowerLimit 1.1',
    ]);
    assert.deepEqual(await problemsOf(RANGE_AND_SET.replace('stepWidth="0.2"', 'stepWidth="fast"')), [
      'd.xosc:8:39: error: stepWidth="fast" is not a number',
    ]);
  });

  it('a range of too many values says how many in a form one can read, and the stepWidth that would do (it printed 300 digits)', async () => {
    const [huge] = await problemsOf(RANGE_AND_SET.replace('stepWidth="0.2"', 'stepWidth="1e-300"'));
    assert.equal(
      huge,
      'd.xosc:8:47: error: this range has about 4.0e299 values at stepWidth 1e-300; at most 1,000,000 are expanded: widen stepWidth to 4.01e-7 or more, or narrow the range',
    );
    const [large] = await problemsOf(RANGE_AND_SET.replace('stepWidth="0.2"', 'stepWidth="0.0000001"'));
    assert.match(large, /about 4,000,00[01] values at stepWidth 1e-7; .*widen stepWidth to 4\.01e-7 or more/);
    // The step it names expands: at most a million values.
    const [within] = await problemsOf(RANGE_AND_SET.replace('stepWidth="0.2"', 'stepWidth="4.01e-7"'));
    assert.equal(within, undefined);
  });

  it('reports bad input instead of failing: not XML, not a distribution, no distribution, not UTF-8', async () => {
    const file = path.join(dir, 'd.xosc');
    const cases: [string | Buffer, RegExp][] = [
      ['<OpenSCENARIO><ParameterValueDistribution>', /^d\.xosc:1:\d+: error: /],
      [SCENARIO, /^d\.xosc:2:1: error: no <ParameterValueDistribution>: this is not a distribution file$/],
      [distribution(''), /^d\.xosc:4:3: error: no <Deterministic> or <Stochastic> distribution$/],
      [distribution('    <Deterministic/>'), /^d\.xosc:5:29: error: the <Deterministic> element has no distribution/],
      [Buffer.from([0x3c, 0x61, 0xff, 0x3e]), /^modular2simple: error: .*d\.xosc: not UTF-8 text$/],
      ['', /^d\.xosc:1:1: error: /],
    ];
    for (const [content, expected] of cases) {
      fs.writeFileSync(file, content);
      const result = await run([file, '--count'], dir);
      assert.equal(result.code, 1, String(content));
      assert.deepEqual(result.out, []);
      assert.match(result.err[0], expected);
    }
  });

  it('warns of values that do not fit the parameter type (esmini takes them as they are)', async () => {
    const body = RANGE_AND_SET.replace('parameterName="Car"', 'parameterName="Gap"').replace(
      '<Element value="a"/>',
      '<Element value="0.5"/>',
    );
    assert.deepEqual(await problemsOf(body), ["d.xosc:11:64: warning: the value 'b' for double parameter 'Gap' is not a number"]);
    // An expression is checked by its value, as esmini evaluates it in the declaration (Euro NCAP's CPRA: '${0.6/2-0.36}');
    // each warning is on the value's own Element, not on the distribution's parameterName.
    const expressions = RANGE_AND_SET.replace('parameterName="Car"', 'parameterName="Gap"')
      .replace('<Element value="a"/>', '<Element value="${0.6/2-0.36}"/>')
      .replace('<Element value="b"/>', '<Element value="${$Speed * 2}"/><Element value="${1 &lt; 2}"/>');
    assert.deepEqual(await problemsOf(expressions), [
      "d.xosc:11:106: warning: the value '${1 < 2}' for double parameter 'Gap' is not a number",
    ]);
    const stochastic = `    <Stochastic numberOfTestRuns="3">
      <StochasticDistribution parameterName="Speed"><PoissonDistribution expectedValue="2"/></StochasticDistribution>
    </Stochastic>`;
    assert.deepEqual(await problemsOf(stochastic), []);
  });

  it("discards combinations that break the scenario's ValueConstraintGroups, and counts them", async () => {
    fs.writeFileSync(
      path.join(dir, 'scenario.xosc'),
      SCENARIO.replace(
        '<ParameterDeclaration name="Speed" parameterType="double" value="10"/>',
        '<ParameterDeclaration name="Speed" parameterType="double" value="10"><ConstraintGroup><ValueConstraint rule="lessThan" value="1.2"/></ConstraintGroup><ConstraintGroup><ValueConstraint rule="equalTo" value="1.5"/></ConstraintGroup></ParameterDeclaration>',
      ),
    );
    fs.writeFileSync(path.join(dir, 'd.xosc'), distribution(RANGE_AND_SET));
    const counted = await run([path.join(dir, 'd.xosc'), '--count']);
    assert.deepEqual(
      [counted.code, counted.out],
      [0, ["6 combinations (esmini's --param_permutation 0..5), 4 kept: 2 break the scenario's ValueConstraintGroups and are discarded"]],
    );
    assert.deepEqual(counted.err, []);
    const discarded = await run([path.join(dir, 'd.xosc'), '--index', '2']);
    assert.equal(discarded.code, 1);
    assert.match(
      discarded.err.join('\n'),
      /concrete scenario 2 is discarded: parameter 'Speed' = '1.300000' breaks its ValueConstraintGroups/,
    );
    const all = await run([path.join(dir, 'd.xosc'), '--out-dir', path.join(dir, 'out')]);
    assert.equal(all.code, 0);
    assert.deepEqual(fs.readdirSync(path.join(dir, 'out')).sort(), [
      'scenario_0.xosc',
      'scenario_1.xosc',
      'scenario_4.xosc',
      'scenario_5.xosc',
    ]);
    assert.match(all.err.join('\n'), /wrote 4 concrete scenarios .*; 2 discarded by the scenario's ValueConstraintGroups/);
  });
});

describe('cli: vary', () => {
  let dir: string;
  let file: string;
  beforeEach(() => {
    dir = temporaryFolder('m2s-vary-');
    fs.writeFileSync(path.join(dir, 'scenario.xosc'), SCENARIO);
    file = path.join(dir, 'd.xosc');
    fs.writeFileSync(file, distribution(RANGE_AND_SET));
  });
  afterEach(() => fs.rmSync(dir, { recursive: true, force: true }));

  it('--count prints the number alone', async () => {
    assert.deepEqual(await run([file, '--count']), { code: 0, out: ['6'], err: [] });
  });

  it('--index I -o OUT writes concrete scenario I; without -o it goes to standard output', async () => {
    const output = path.join(dir, 'five.xosc');
    assert.equal((await run([file, '--index', '5', '-o', output])).code, 0);
    const expected = SCENARIO.replace(
      'name="Speed" parameterType="double" value="10"',
      'name="Speed" parameterType="double" value="1.500000"',
    ).replace('value="car_white"', 'value="b"');
    assert.equal(fs.readFileSync(output, 'utf8'), expected);
    assert.deepEqual((await run([file, '--index', '5'])).out, [expected]);
  });

  it('refuses an index out of range, an output over an input, wrong usage', async () => {
    const outOfRange = await run([file, '--index', '6']);
    // An option's value outside what it takes is a usage error, as every command's is; the file has no line to blame.
    assert.equal(outOfRange.code, 2);
    assert.match(
      outOfRange.err[0],
      /--index 6 is out of range: .*d\.xosc has 6 concrete scenarios, numbered 0\.\.5; give --index one of those/,
    );
    const overInput = await run([file, '--index', '0', '-o', path.join(dir, 'scenario.xosc')]);
    assert.equal(overInput.code, 2);
    assert.equal(fs.readFileSync(path.join(dir, 'scenario.xosc'), 'utf8'), SCENARIO);
    assert.equal((await run([file])).code, 2);
    assert.equal((await run([file, '--count', '--index', '1'])).code, 2);
    assert.equal((await run([file, '--index', 'x'])).code, 2);
    assert.equal((await run([file, '--count', '--sample', '3'])).code, 2);
    assert.equal((await run([path.join(dir, 'absent.xosc'), '--count'])).code, 1);
  });

  it('refuses 10^9 combinations before writing anything unless --sample; --sample N --seed S writes N', async () => {
    const big = `    <Deterministic>
${['Speed', 'Gap', 'Car']
  .map(
    (name) =>
      `      <DeterministicSingleParameterDistribution parameterName="${name}"><DistributionRange stepWidth="1"><Range lowerLimit="1" upperLimit="1000"/></DistributionRange></DeterministicSingleParameterDistribution>`,
  )
  .join('\n')}
    </Deterministic>`;
    fs.writeFileSync(file, distribution(big));
    assert.deepEqual((await run([file, '--count'])).out, ['1000000000']);
    const outDir = path.join(dir, 'out');
    const refused = await run([file, '--out-dir', outDir]);
    assert.equal(refused.code, 1);
    assert.match(refused.err[0], /1000000000 combinations are more than --max-combinations 1000000; nothing was written/);
    assert.equal(fs.existsSync(outDir), false);
    const sampled = await run([file, '--out-dir', outDir, '--sample', '5', '--seed', '7']);
    assert.equal(sampled.code, 0);
    const names = fs.readdirSync(outDir).sort();
    assert.equal(names.length, 5);
    const again = await run([file, '--out-dir', path.join(dir, 'again'), '--sample', '5', '--seed', '7']);
    assert.equal(again.code, 0);
    assert.deepEqual(fs.readdirSync(path.join(dir, 'again')).sort(), names);
    const lowered = await run([file, '--out-dir', outDir, '--max-combinations', '10']);
    assert.equal(lowered.code, 1);
  });

  it('takes the scenario text from the loader hook (where a flattener plugs in)', async () => {
    const asked: string[] = [];
    const code = await varyCommand([file, '--count'], { out: () => undefined, err: () => undefined }, async (scenarioPath) => {
      asked.push(scenarioPath);
      return SCENARIO;
    });
    assert.equal(code, 0);
    assert.deepEqual(asked, [path.join(dir, 'scenario.xosc')]);
  });
});

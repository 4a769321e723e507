import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { varyCommand } from '../../server/src/cli/vary';
import { loadVariations, Variations } from '../../server/src/core/variations';
import { NumericRange, StochasticDistribution, StochasticSampler } from '../../server/src/core/variations/distribution';
import { generatorForRun, Xoshiro128StarStar } from '../../server/src/core/variations/random';
import { draw, SamplingError } from '../../server/src/core/variations/stochastic';
import { BARE_XML_DECLARATION, distributionFile, fileHeader } from '../support/fixtures';
import { temporaryFolder } from '../support/temporaryDirectory';

const N = 20_000;

function distribution(sampler: StochasticSampler, range?: { lower: number; upper: number }): StochasticDistribution {
  return { parameter: 'p', offset: 0, sampler, range: range ? { ...range, offset: 0 } : undefined };
}

function bin(lower: number, upper: number): NumericRange {
  return { lower, upper, offset: 0 };
}

function drawMany(d: StochasticDistribution, seed = 1): string[] {
  const random = generatorForRun(seed, 0);
  return Array.from({ length: N }, () => draw(random, d));
}

function moments(values: number[]): { mean: number; variance: number } {
  const mean = values.reduce((sum, v) => sum + v, 0) / values.length;
  const variance = values.reduce((sum, v) => sum + (v - mean) ** 2, 0) / (values.length - 1);
  return { mean, variance };
}

/** Kolmogorov-Smirnov statistic of a sample against a continuous CDF. */
function ks(values: number[], cdf: (x: number) => number): number {
  const sorted = [...values].sort((a, b) => a - b);
  let d = 0;
  sorted.forEach((x, i) => {
    const f = cdf(x);
    d = Math.max(d, Math.abs(f - i / sorted.length), Math.abs((i + 1) / sorted.length - f));
  });
  return d;
}

/** Pearson's chi-square of observed counts against expected probabilities. */
function chiSquare(observed: number[], probabilities: number[]): number {
  const total = observed.reduce((sum, v) => sum + v, 0);
  return observed.reduce((sum, o, i) => sum + (o - total * probabilities[i]) ** 2 / (total * probabilities[i]), 0);
}

/** erf by Abramowitz and Stegun 7.1.26 (error below 1.5e-7, far below the KS tolerance). */
function erf(x: number): number {
  const t = 1 / (1 + 0.3275911 * Math.abs(x));
  const y = 1 - ((((1.061405429 * t - 1.453152027) * t + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t * Math.exp(-x * x);
  return x >= 0 ? y : -y;
}

// KS critical value at p = 0.001 for n = 20000, and chi-square critical values at p = 0.001 by degrees of freedom.
const KS_CRITICAL = 1.95 / Math.sqrt(N);
const CHI2_CRITICAL: Record<number, number> = { 1: 10.83, 2: 13.82, 3: 16.27, 10: 29.59 };

describe('core: variations, seeded random numbers', () => {
  it('is xoshiro128** seeded by SplitMix64: the reference C implementation gives the same words', () => {
    // Printed by the reference C code of both generators (prng.di.unimi.it), seeded as random.ts documents.
    const seed0 = generatorForRun(0, 0);
    assert.deepEqual(
      Array.from({ length: 6 }, () => seed0.nextUint32()),
      [513008459, 2795874746, 972916236, 1374099887, 2042740824, 3697851841],
    );
    const seed42 = generatorForRun(42, 1);
    assert.deepEqual(
      Array.from({ length: 6 }, () => seed42.nextUint32()),
      [3699588373, 2050747386, 117689897, 4143233103, 1677809260, 2948185039],
    );
    assert.equal(generatorForRun(12345.5, 0).nextDouble(), 0.3456700715785038);
  });

  it('gives the committed first draws of every sampler for seed 2026 (the algorithm is the contract)', () => {
    const cases: [StochasticDistribution, string[]][] = [
      [
        distribution({ kind: 'normal', mean: 5, variance: 4 }),
        ['6.391592319134579', '4.06891030158754', '8.543146280785773', '2.696703226398891', '2.9465572575825845'],
      ],
      [
        distribution({ kind: 'normal', mean: 0, variance: 1 }, { lower: 0.5, upper: 1 }),
        ['0.6957961595672898', '0.8115708773868275', '0.9937395145480998', '0.676665932124986', '0.6761186244275265'],
      ],
      [
        distribution({ kind: 'logNormal', mean: 10, variance: 4 }),
        ['11.254541531892071', '8.942160351773394', '13.926882697579616', '7.806055321389547', '8.001592439665526'],
      ],
      [
        distribution({ kind: 'uniform' }, { lower: -2, upper: 3 }),
        ['-0.8912462892895816', '-1.8513903539908299', '-1.4862709450226053', '0.4828960817663468', '2.6142892047524677'],
      ],
      [distribution({ kind: 'poisson', mean: 4 }), ['1', '3', '5', '1', '0']],
      [distribution({ kind: 'poisson', mean: 100 }), ['91', '85', '118', '101', '98']],
      [
        distribution({
          kind: 'histogram',
          bins: [
            { weight: 1, range: bin(0, 1) },
            { weight: 2, range: bin(1, 2) },
            { weight: 1, range: bin(2, 4) },
          ],
        }),
        ['0.02972192920183403', '0.4965792163532694', '2.213887756843163', '1.4383331791725682', '1.5236009105969637'],
      ],
      [
        distribution({
          kind: 'probabilitySet',
          elements: [
            { value: 'a', weight: 1 },
            { value: 'b', weight: 3 },
          ],
        }),
        ['a', 'a', 'a', 'b', 'b'],
      ],
      [distribution({ kind: 'userDefined', type: 'list', values: ['x', 'y', 'z'] }), ['x', 'x', 'x', 'y', 'z']],
    ];
    for (const [d, expected] of cases) {
      const random = generatorForRun(2026, 0);
      assert.deepEqual(
        Array.from({ length: 5 }, () => draw(random, d)),
        expected,
        d.sampler.kind,
      );
    }
  });

  it('draws big integers below a bound without bias', () => {
    const random = new Xoshiro128StarStar(5n);
    const counts = [0, 0, 0];
    for (let i = 0; i < N; i++) counts[Number(random.nextBigBelow(3n))]++;
    assert.ok(chiSquare(counts, [1 / 3, 1 / 3, 1 / 3]) < CHI2_CRITICAL[2]);
    const huge = 10n ** 30n;
    for (let i = 0; i < 100; i++) assert.ok(random.nextBigBelow(huge) < huge);
  });
});

describe('core: variations, samplers fit their distributions (n = 20000, fixed seed)', () => {
  it('normal: mean, variance and Kolmogorov-Smirnov', () => {
    const values = drawMany(distribution({ kind: 'normal', mean: 5, variance: 4 })).map(Number);
    const { mean, variance } = moments(values);
    assert.ok(Math.abs(mean - 5) < 0.06, `mean ${mean}`);
    assert.ok(Math.abs(variance - 4) < 0.16, `variance ${variance}`);
    assert.ok(ks(values, (x) => 0.5 * (1 + erf((x - 5) / (2 * Math.SQRT2)))) < KS_CRITICAL);
  });

  it('log-normal: the mean and variance asked for, and positive values', () => {
    const values = drawMany(distribution({ kind: 'logNormal', mean: 10, variance: 4 })).map(Number);
    const { mean, variance } = moments(values);
    assert.ok(values.every((v) => v > 0));
    assert.ok(Math.abs(mean - 10) < 0.05, `mean ${mean}`);
    assert.ok(Math.abs(variance - 4) < 0.25, `variance ${variance}`);
    const s2 = Math.log(1 + 4 / 100);
    const mu = Math.log(10) - s2 / 2;
    assert.ok(ks(values, (x) => 0.5 * (1 + erf((Math.log(x) - mu) / Math.sqrt(2 * s2)))) < KS_CRITICAL);
  });

  it('uniform: Kolmogorov-Smirnov over its Range', () => {
    const values = drawMany(distribution({ kind: 'uniform' }, { lower: -2, upper: 3 })).map(Number);
    assert.ok(values.every((v) => v >= -2 && v < 3));
    assert.ok(ks(values, (x) => (x + 2) / 5) < KS_CRITICAL);
  });

  it('Poisson: Knuth below 30 (chi-square against the mass function), PTRS above (mean and variance)', () => {
    const small = drawMany(distribution({ kind: 'poisson', mean: 4 })).map(Number);
    const counts = new Array<number>(11).fill(0);
    for (const v of small) counts[Math.min(v, 10)]++;
    const pmf = counts.map((_, k) => (Math.exp(-4) * 4 ** k) / [1, 1, 2, 6, 24, 120, 720, 5040, 40320, 362880][k] || 0);
    pmf[10] = 1 - pmf.slice(0, 10).reduce((sum, p) => sum + p, 0);
    assert.ok(chiSquare(counts, pmf) < CHI2_CRITICAL[10], `chi-square ${chiSquare(counts, pmf)}`);
    for (const lambda of [30, 100, 1000]) {
      const values = drawMany(distribution({ kind: 'poisson', mean: lambda })).map(Number);
      const { mean, variance } = moments(values);
      assert.ok(values.every((v) => Number.isInteger(v) && v >= 0));
      assert.ok(Math.abs(mean - lambda) < 4 * Math.sqrt(lambda / N), `λ ${lambda}: mean ${mean}`);
      assert.ok(Math.abs(variance / lambda - 1) < 0.05, `λ ${lambda}: variance ${variance}`);
    }
  });

  it('histogram: bins by weight (chi-square), uniform within a bin', () => {
    const values = drawMany(
      distribution({
        kind: 'histogram',
        bins: [
          { weight: 1, range: bin(0, 1) },
          { weight: 2, range: bin(1, 2) },
          { weight: 1, range: bin(2, 4) },
        ],
      }),
    ).map(Number);
    const counts = [0, 0, 0];
    for (const v of values) counts[v < 1 ? 0 : v < 2 ? 1 : 2]++;
    assert.ok(chiSquare(counts, [0.25, 0.5, 0.25]) < CHI2_CRITICAL[2]);
    assert.ok(
      ks(
        values.filter((v) => v >= 2),
        (x) => (x - 2) / 2,
      ) <
        1.95 / Math.sqrt(counts[2]),
    );
  });

  it('probability set and user-defined list: chi-square against their weights', () => {
    const set = drawMany(
      distribution({
        kind: 'probabilitySet',
        elements: [
          { value: 'a', weight: 1 },
          { value: 'b', weight: 3 },
          { value: 'c', weight: 0 },
        ],
      }),
    );
    assert.equal(set.filter((v) => v === 'c').length, 0);
    assert.ok(chiSquare([set.filter((v) => v === 'a').length, set.filter((v) => v === 'b').length], [0.25, 0.75]) < CHI2_CRITICAL[1]);
    const listed = drawMany(distribution({ kind: 'userDefined', type: 'list', values: ['x', 'y', 'z'] }));
    assert.ok(
      chiSquare(
        ['x', 'y', 'z'].map((v) => listed.filter((w) => w === v).length),
        [1 / 3, 1 / 3, 1 / 3],
      ) < CHI2_CRITICAL[2],
    );
  });

  it('a Range is honoured by drawing again; an unreachable one is an error, not a hang', () => {
    const values = drawMany(distribution({ kind: 'normal', mean: 0, variance: 1 }, { lower: 0.5, upper: 1 })).map(Number);
    assert.ok(values.every((v) => v >= 0.5 && v <= 1));
    const poisson = drawMany(distribution({ kind: 'poisson', mean: 4 }, { lower: 2, upper: 3 })).map(Number);
    assert.ok(poisson.every((v) => v === 2 || v === 3));
    assert.throws(
      () => draw(generatorForRun(0, 0), distribution({ kind: 'normal', mean: 0, variance: 1 }, { lower: 50, upper: 51 })),
      SamplingError,
    );
  });
});

describe('core: variations, stochastic distribution files', () => {
  let dir: string;
  const scenario = `<?xml version="1.0"?>
<OpenSCENARIO>
  <ParameterDeclarations>
    <ParameterDeclaration name="Speed" parameterType="double" value="10"/>
    <ParameterDeclaration name="Car" parameterType="string" value="car_white"/>
    <ParameterDeclaration name="Count" parameterType="int" value="1"/>
  </ParameterDeclarations>
</OpenSCENARIO>
`;
  const stochastic = (seed: string, extra = ''): string =>
    distributionFile(
      'scenario.xosc',
      `    <Stochastic numberOfTestRuns="50" ${seed}>
      <StochasticDistribution parameterName="Speed"><NormalDistribution expectedValue="30" variance="9"><Range lowerLimit="20" upperLimit="40"/></NormalDistribution></StochasticDistribution>
      <StochasticDistribution parameterName="Car"><ProbabilityDistributionSet><Element value="car_red" weight="1"/><Element value="van" weight="1"/></ProbabilityDistributionSet></StochasticDistribution>
      <StochasticDistribution parameterName="Count"><PoissonDistribution expectedValue="3"/></StochasticDistribution>${extra}
    </Stochastic>
`,
      fileHeader({ description: 'd', author: 'm2s' }),
      BARE_XML_DECLARATION,
    );
  beforeEach(() => {
    dir = temporaryFolder('m2s-vary-stochastic-');
    fs.writeFileSync(path.join(dir, 'scenario.xosc'), scenario);
  });
  afterEach(() => fs.rmSync(dir, { recursive: true, force: true }));

  async function load(text: string): Promise<Variations> {
    const loaded = await loadVariations(text, path.join(dir, 'd.xosc'), (p) => fs.promises.readFile(p, 'utf8'));
    assert.deepEqual(loaded.problems, []);
    return loaded.variations as Variations;
  }

  it('has numberOfTestRuns concrete scenarios; run I is the same drawn alone or after the others; the seed changes it', async () => {
    const variations = await load(stochastic('randomSeed="7"'));
    assert.equal(variations.count, 50n);
    const all = [...Array(50).keys()].map((i) =>
      variations
        .assignmentAt(BigInt(i))
        .map((a) => a.value)
        .join(','),
    );
    const alone = (await load(stochastic('randomSeed="7"')))
      .assignmentAt(37n)
      .map((a) => a.value)
      .join(',');
    assert.equal(alone, all[37]);
    assert.equal(new Set(all).size, 50);
    const reseeded = (await load(stochastic('randomSeed="8"')))
      .assignmentAt(37n)
      .map((a) => a.value)
      .join(',');
    assert.notEqual(reseeded, all[37]);
    const values = async (seed: string): Promise<string[]> => (await load(stochastic(seed))).assignmentAt(0n).map((a) => a.value);
    assert.deepEqual(await values(''), await values('randomSeed="0"'));
  });

  it('vary --out-dir writes them; --count prints numberOfTestRuns; an unreachable Range stops before anything is written', async () => {
    const file = path.join(dir, 'd.xosc');
    fs.writeFileSync(file, stochastic('randomSeed="7"'));
    const out: string[] = [];
    const io = { out: (text: string) => out.push(text), err: () => undefined };
    assert.equal(await varyCommand([file, '--count'], io), 0);
    assert.deepEqual(out, ['50']);
    assert.equal(await varyCommand([file, '--out-dir', path.join(dir, 'out'), '--sample', '10', '--seed', '3'], io), 0);
    assert.equal(fs.readdirSync(path.join(dir, 'out')).length, 10);
    fs.writeFileSync(
      file,
      stochastic(
        'randomSeed="7"',
        '\n      <StochasticDistribution parameterName="Speed"><NormalDistribution expectedValue="0" variance="1"><Range lowerLimit="100" upperLimit="101"/></NormalDistribution></StochasticDistribution>',
      ),
    );
    const errors: string[] = [];
    assert.equal(
      await varyCommand([file, '--out-dir', path.join(dir, 'never')], { out: () => undefined, err: (text) => errors.push(text) }),
      1,
    );
    assert.equal(fs.existsSync(path.join(dir, 'never')), false);
    assert.match(errors.join('\n'), /d\.xosc:10:\d+: error: 10000 draws in a row fell outside the Range \[100, 101\]/);
  });
});

import { NumericRange, ParameterValue, StochasticDistribution, StochasticSampler } from './distribution';
import { generatorForRun, Xoshiro128StarStar } from './random';

/**
 * Samplers for OpenSCENARIO's stochastic distributions, drawing from the generator in ./random.
 * - Normal: Box-Muller, cosine branch only (two uniforms per draw, no cached second value), sigma = sqrt(variance).
 * - LogNormal: expectedValue and variance are those of the log-normal value itself:
 *   s^2 = ln(1 + variance / mean^2), mu = ln(mean) - s^2 / 2, value = exp(mu + s * normal).
 * - Uniform: lower + u * (upper - lower) over the Range.
 * - Poisson: Knuth's product of uniforms for mean < 30; above, PTRS (Hörmann 1993, "The transformed
 *   rejection method for generating Poisson random variables"), as numpy's legacy generator does.
 * - Histogram: a bin chosen with probability weight / sum of weights, then uniform within its Range.
 * - ProbabilityDistributionSet: an element chosen with probability weight / sum of weights.
 * - UserDefinedDistribution (type="list"): one of the listed values, each equally likely.
 * A Range (optional except for Uniform) is honoured by drawing again, at most MAX_TRIES times.
 */

export const MAX_TRIES = 10_000;

export class SamplingError extends Error {
  constructor(
    message: string,
    readonly offset: number,
  ) {
    super(message);
  }
}

export function normal(random: Xoshiro128StarStar): number {
  const u1 = 1 - random.nextDouble(); // in (0, 1]: the logarithm stays finite
  const u2 = random.nextDouble();
  return Math.sqrt(-2 * Math.log(u1)) * Math.cos(2 * Math.PI * u2);
}

export function poisson(random: Xoshiro128StarStar, mean: number): number {
  if (mean === 0) return 0;
  if (mean < 30) {
    const limit = Math.exp(-mean);
    let product = random.nextDouble();
    let k = 0;
    while (product > limit) {
      k++;
      product *= random.nextDouble();
    }
    return k;
  }
  const slam = Math.sqrt(mean);
  const loglam = Math.log(mean);
  const b = 0.931 + 2.53 * slam;
  const a = -0.059 + 0.02483 * b;
  const invalpha = 1.1239 + 1.1328 / (b - 3.4);
  const vr = 0.9277 - 3.6224 / (b - 2);
  for (;;) {
    const u = random.nextDouble() - 0.5;
    const v = random.nextDouble();
    const us = 0.5 - Math.abs(u);
    const k = Math.floor(((2 * a) / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= vr) return k;
    if (k < 0 || (us < 0.013 && v > us)) continue;
    if (Math.log(v) + Math.log(invalpha) - Math.log(a / (us * us) + b) <= -mean + k * loglam - logGamma(k + 1)) return k;
  }
}

/** ln Γ(x) for x >= 1 by the Stirling series, after shifting x up to 7 (numpy's loggam). */
export function logGamma(x: number): number {
  const coefficients = [
    8.333333333333333e-2, -2.777777777777778e-3, 7.936507936507937e-4, -5.952380952380952e-4, 8.417508417508418e-4, -1.917526917526918e-3,
    6.41025641025641e-3, -2.955065359477124e-2, 1.796443723688307e-1, -1.3924322169059,
  ];
  if (x === 1 || x === 2) return 0;
  let shifted = x;
  let shifts = 0;
  if (x <= 7) {
    shifts = Math.floor(7 - x);
    shifted = x + shifts;
  }
  const inverseSquare = 1 / (shifted * shifted);
  let series = coefficients[9];
  for (let k = 8; k >= 0; k--) series = series * inverseSquare + coefficients[k];
  let result = series / shifted + 0.5 * Math.log(2 * Math.PI) + (shifted - 0.5) * Math.log(shifted) - shifted;
  if (x <= 7) {
    for (let k = 1; k <= shifts; k++) {
      shifted -= 1;
      result -= Math.log(shifted);
    }
  }
  return result;
}

function weightedIndex(random: Xoshiro128StarStar, weights: number[]): number {
  const total = weights.reduce((sum, weight) => sum + weight, 0);
  const target = random.nextDouble() * total;
  let cumulative = 0;
  for (let i = 0; i < weights.length; i++) {
    cumulative += weights[i];
    if (target < cumulative) return i;
  }
  // Rounding can leave target at the very top: the last bin with weight takes it.
  for (let i = weights.length - 1; i >= 0; i--) if (weights[i] > 0) return i;
  return weights.length - 1;
}

/** One draw, as the text a parameter's value gets. */
function drawOnce(
  random: Xoshiro128StarStar,
  sampler: StochasticSampler,
  range: NumericRange | undefined,
): { text: string; value: number | undefined } {
  switch (sampler.kind) {
    case 'normal': {
      const value = sampler.mean + Math.sqrt(sampler.variance) * normal(random);
      return { text: formatNumber(value), value };
    }
    case 'logNormal': {
      const s2 = Math.log(1 + sampler.variance / (sampler.mean * sampler.mean));
      const value = Math.exp(Math.log(sampler.mean) - s2 / 2 + Math.sqrt(s2) * normal(random));
      return { text: formatNumber(value), value };
    }
    case 'uniform': {
      const limits = range as NumericRange;
      const value = limits.lower + random.nextDouble() * (limits.upper - limits.lower);
      return { text: formatNumber(value), value };
    }
    case 'poisson': {
      const value = poisson(random, sampler.mean);
      return { text: String(value), value };
    }
    case 'histogram': {
      const bin =
        sampler.bins[
          weightedIndex(
            random,
            sampler.bins.map((b) => b.weight),
          )
        ];
      const value = bin.range.lower + random.nextDouble() * (bin.range.upper - bin.range.lower);
      return { text: formatNumber(value), value };
    }
    case 'probabilitySet': {
      const text =
        sampler.elements[
          weightedIndex(
            random,
            sampler.elements.map((e) => e.weight),
          )
        ].value;
      return { text, value: numberOrUndefined(text) };
    }
    case 'userDefined': {
      const text = sampler.values[Math.floor(random.nextDouble() * sampler.values.length)];
      return { text, value: numberOrUndefined(text) };
    }
  }
}

function numberOrUndefined(text: string): number | undefined {
  const value = Number(text.trim());
  return text.trim() !== '' && Number.isFinite(value) ? value : undefined;
}

/** Shortest text that reads back as the same double (JavaScript's Number to String). */
export function formatNumber(value: number): string {
  return Object.is(value, -0) ? '0' : String(value);
}

/** A draw honouring the distribution's Range by rejection; throws SamplingError when MAX_TRIES draws all fall outside. */
export function draw(random: Xoshiro128StarStar, distribution: StochasticDistribution): string {
  const { range } = distribution;
  for (let attempt = 0; attempt < MAX_TRIES; attempt++) {
    const { text, value } = drawOnce(random, distribution.sampler, range);
    if (!range || distribution.sampler.kind === 'uniform') return text;
    if (value === undefined) throw new SamplingError(`the value "${text}" is not a number, so the Range cannot hold it`, range.offset);
    if (value >= range.lower && value <= range.upper) return text;
  }
  throw new SamplingError(
    `${MAX_TRIES} draws in a row fell outside the Range [${range?.lower}, ${range?.upper}]; the range is too narrow for this distribution`,
    range?.offset ?? distribution.offset,
  );
}

/** The assignments of stochastic run `runIndex`: one draw per distribution, in document order, from that run's own generator. */
export function stochasticAssignment(distributions: StochasticDistribution[], seed: number, runIndex: number): ParameterValue[] {
  const random = generatorForRun(seed, runIndex);
  return distributions.map((distribution) => ({
    parameter: distribution.parameter,
    value: draw(random, distribution),
    offset: distribution.offset,
  }));
}

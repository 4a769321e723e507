import { ESMINI_SMALL_NUMBER } from '../profiles/esmini';
import { DeterministicDistribution, ParameterValue, VariationProblem } from './distribution';

/**
 * Deterministic expansion as esmini 3.6 does it (ScenarioEngine/OSCTypeDefs/OSCParameterDistribution.cpp):
 * - each distribution is one factor of a product, in document order; index I is a mixed-radix number whose
 *   LAST factor varies fastest (esmini's GetParameterEntry: `r = n % size(last)`, then `n /= size(last)`);
 * - a range is `for (v = lower; v < upper + 1e-6; v += step)`, accumulating in doubles, and each value is
 *   written by `std::to_string(double)`, i.e. printf("%f"): six decimals, round half to even;
 * - set and multi-parameter values are the attribute values as written;
 * - when two factors assign the same parameter the later one wins (esmini sets them in order).
 * Differences, on purpose: esmini refuses `UserDefinedDistribution` (here `type="list"` is expanded in order),
 * loops forever on a step <= 0 and counts in 32 bits (here: an error, and exact counts).
 */

/** More values than this in one range are refused: each is kept, and esmini would take hours. */
export const MAX_RANGE_VALUES = 1_000_000;

/** A count as a reader takes it in: digits with separators, else (past 10^15, where a stepWidth of 1e-300 takes it) a power of ten. */
function aboutCount(count: number): string {
  return count < 1e15 ? count.toLocaleString('en-US') : count.toExponential(1).replace('e+', 'e');
}

/** The stepWidth that gives a range of `width` at most MAX_RANGE_VALUES values, rounded up to three significant digits. */
function smallestStep(width: number): number {
  const exact = width / (MAX_RANGE_VALUES - 1);
  const unit = 10 ** (Math.floor(Math.log10(exact)) - 2);
  return Number((Math.ceil(exact / unit) * unit).toPrecision(3));
}

export interface DeterministicExpansion {
  /** Per factor, its alternatives; each alternative assigns one or more parameters. */
  factors: ParameterValue[][][];
  count: bigint;
}

export function expandDeterministic(
  distributions: DeterministicDistribution[],
  file: string,
): { expansion: DeterministicExpansion; problems: VariationProblem[] } {
  const problems: VariationProblem[] = [];
  const factors: ParameterValue[][][] = [];
  for (const distribution of distributions) {
    switch (distribution.kind) {
      case 'set':
      case 'userDefined':
        factors.push(distribution.values.map((value) => [value]));
        break;
      case 'multi':
        factors.push(distribution.sets);
        break;
      case 'range': {
        const { lower, upper } = distribution.range;
        const estimate = Math.floor((upper - lower) / distribution.step) + 1;
        if (estimate > MAX_RANGE_VALUES) {
          problems.push({
            file,
            offset: distribution.range.offset,
            severity: 'error',
            message: `this range has about ${aboutCount(estimate)} values at stepWidth ${distribution.step}; at most ${MAX_RANGE_VALUES.toLocaleString('en-US')} are expanded: widen stepWidth to ${smallestStep(upper - lower)} or more, or narrow the range`,
          });
          factors.push([]);
          break;
        }
        factors.push(
          rangeValues(lower, upper, distribution.step).map((value) => [
            { parameter: distribution.parameter, value, offset: distribution.offset },
          ]),
        );
        break;
      }
    }
  }
  let count = factors.length === 0 ? 0n : 1n;
  for (const factor of factors) count *= BigInt(factor.length);
  return { expansion: { factors, count }, problems };
}

/** The values of a DistributionRange, exactly as esmini steps and prints them. */
export function rangeValues(lower: number, upper: number, step: number): string[] {
  const values: string[] = [];
  // esmini's SMALL_NUMBER, added to the upper limit so that an accumulated value a hair above it still counts.
  const end = upper + ESMINI_SMALL_NUMBER;
  for (let value = lower; value < end; value += step) values.push(formatFixed6(value));
  return values;
}

/** The parameter assignments of concrete scenario `index` (0-based, esmini's --param_permutation), in factor order. */
export function assignmentAt(expansion: DeterministicExpansion, index: bigint): ParameterValue[] {
  if (index < 0n || index >= expansion.count) throw new RangeError(`index ${index} is outside 0..${expansion.count - 1n}`);
  const chosen: ParameterValue[][] = [];
  let rest = index;
  for (let i = expansion.factors.length - 1; i >= 0; i--) {
    const size = BigInt(expansion.factors[i].length);
    chosen.unshift(expansion.factors[i][Number(rest % size)]);
    rest /= size;
  }
  return chosen.flat();
}

/** C's printf("%.6f", value) (what std::to_string(double) writes), computed exactly: round half to even, "-0.000000" kept. */
export function formatFixed6(value: number): string {
  if (!Number.isFinite(value)) return Number.isNaN(value) ? 'nan' : value > 0 ? 'inf' : '-inf';
  const negative = value < 0 || Object.is(value, -0);
  const view = new DataView(new ArrayBuffer(8));
  view.setFloat64(0, Math.abs(value));
  const bits = view.getBigUint64(0);
  const exponentBits = Number((bits >> 52n) & 0x7ffn);
  const fraction = bits & ((1n << 52n) - 1n);
  // |value| = mantissa * 2^exponent exactly.
  const mantissa = exponentBits === 0 ? fraction : fraction | (1n << 52n);
  const exponent = (exponentBits === 0 ? 1 : exponentBits) - 1075;
  let micros: bigint;
  if (exponent >= 0) micros = (mantissa << BigInt(exponent)) * 1_000_000n;
  else {
    const numerator = mantissa * 1_000_000n;
    const denominator = 1n << BigInt(-exponent);
    micros = numerator / denominator;
    const twiceRemainder = (numerator % denominator) * 2n;
    if (twiceRemainder > denominator || (twiceRemainder === denominator && micros % 2n === 1n)) micros += 1n;
  }
  const digits = micros.toString().padStart(7, '0');
  return `${negative ? '-' : ''}${digits.slice(0, -6)}.${digits.slice(-6)}`;
}

/**
 * The project's seeded random numbers for stochastic distributions. The algorithm is part of the contract:
 * the same seed gives the same values on every machine and every version, so a concrete scenario can be
 * named by its seed and index alone.
 *
 * - Generator: xoshiro128** 1.1 (Blackman and Vigna, https://prng.di.unimi.it/xoshiro128starstar.c),
 *   32-bit arithmetic only, so JavaScript computes it exactly.
 * - Seeding: the 128-bit state is the first two outputs of SplitMix64 (Steele, Lea, Flood 2014;
 *   https://prng.di.unimi.it/splitmix64.c), each split into its high then low 32-bit word.
 * - A double in [0, 1): 53 bits from two outputs, (a >>> 5) * 2^26 + (b >>> 6), divided by 2^53.
 */

const MASK64 = (1n << 64n) - 1n;
const GOLDEN_GAMMA = 0x9e3779b97f4a7c15n;

/** SplitMix64's output function: a bijection of 64-bit words. */
export function mix64(value: bigint): bigint {
  let z = value & MASK64;
  z = ((z ^ (z >> 30n)) * 0xbf58476d1ce4e5b9n) & MASK64;
  z = ((z ^ (z >> 27n)) * 0x94d049bb133111ebn) & MASK64;
  return z ^ (z >> 31n);
}

/** The 64 bits of a double's IEEE-754 representation (`randomSeed` is a Double in the schema). */
export function seedBits(seed: number): bigint {
  const view = new DataView(new ArrayBuffer(8));
  view.setFloat64(0, Object.is(seed, -0) ? 0 : seed);
  return view.getBigUint64(0);
}

export class Xoshiro128StarStar {
  private s0: number;
  private s1: number;
  private s2: number;
  private s3: number;

  /** Seeded from a 64-bit word through SplitMix64. */
  constructor(seed: bigint) {
    let state = seed & MASK64;
    const words: number[] = [];
    for (let i = 0; i < 2; i++) {
      state = (state + GOLDEN_GAMMA) & MASK64;
      const output = mix64(state);
      words.push(Number(output >> 32n) >>> 0, Number(output & 0xffffffffn) >>> 0);
    }
    [this.s0, this.s1, this.s2, this.s3] = words;
    // An all-zero state would only ever give zeros; SplitMix64 never yields it for two consecutive outputs, but be sure.
    if ((this.s0 | this.s1 | this.s2 | this.s3) === 0) this.s0 = 1;
  }

  /** The next 32-bit output, as an unsigned integer. */
  nextUint32(): number {
    const result = Math.imul(rotl(Math.imul(this.s1, 5), 7), 9) >>> 0;
    const t = this.s1 << 9;
    this.s2 ^= this.s0;
    this.s3 ^= this.s1;
    this.s1 ^= this.s2;
    this.s0 ^= this.s3;
    this.s2 ^= t;
    this.s3 = rotl(this.s3, 11);
    return result;
  }

  /** A double uniformly distributed in [0, 1), with 53 random bits. */
  nextDouble(): number {
    const high = this.nextUint32() >>> 5;
    const low = this.nextUint32() >>> 6;
    return (high * 67108864 + low) / 9007199254740992;
  }

  /** A uniformly distributed integer in [0, bound), bound > 0, by rejection (no modulo bias). */
  nextBigBelow(bound: bigint): bigint {
    if (bound <= 0n) throw new RangeError('bound must be positive');
    const bits = bound.toString(2).length;
    const words = Math.ceil(bits / 32);
    const excess = BigInt(words * 32 - bits);
    for (;;) {
      let value = 0n;
      for (let i = 0; i < words; i++) value = (value << 32n) | BigInt(this.nextUint32());
      value >>= excess;
      if (value < bound) return value;
    }
  }
}

function rotl(x: number, k: number): number {
  return (x << k) | (x >>> (32 - k)) | 0;
}

/** The generator of stochastic run `runIndex` for a seed: runs are independent, so any run can be drawn alone. */
export function generatorForRun(seed: number, runIndex: number): Xoshiro128StarStar {
  return new Xoshiro128StarStar(seedBits(seed) ^ mix64(BigInt(runIndex)));
}

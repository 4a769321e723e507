import fc from 'fast-check';

/**
 * The seed of every fast-check property (loaded through .mocharc.json's `require`). CI sets
 * M2S_PROPERTY_SEED so that whether main lands does not hang on a draw; elsewhere each run draws its own
 * seed, and a failure prints it (`seed`, `path`) to replay. `npm run soak` runs the properties on many seeds.
 */
const written = process.env.M2S_PROPERTY_SEED;
if (written !== undefined && written !== '') {
  const seed = Number(written);
  if (!Number.isSafeInteger(seed)) throw new Error(`M2S_PROPERTY_SEED must be an integer (a fast-check seed), not '${written}'`);
  fc.configureGlobal({ ...fc.readConfigureGlobal(), seed });
}

// Modularize on real libraries (issue 28 item 5): per library, lines before and after (SPEC 9), the share
// saved, how many mains flatten back equivalent (SPEC 8), the groups left inline and why, and the share of
// lines inside ManeuverGroups (all that extracting groups can take). Run by bench/run.mjs with
// `node --import tsx`; prints figures, asserts nothing. The public test-protocol libraries are read from a
// checkout in M2S_REAL_LIBRARIES (default .cache/real-libraries: ncap/ and alks/); nothing is downloaded.
import { figuresLine, modularizeLibrary, realLibraries } from '../test/support/modularizeLibrary';

async function main(): Promise<void> {
  const { libraries, missing } = realLibraries();
  const details = process.argv.includes('--details');
  console.log('modularize on real libraries (in memory; every main flattened again by its own flattener)');
  for (const library of libraries) {
    const started = process.hrtime.bigint();
    const { figures } = await modularizeLibrary(library);
    const seconds = Number(process.hrtime.bigint() - started) / 1e9;
    console.log(`  ${figuresLine(figures)} [${seconds.toFixed(1)} s]`);
    const reasons = new Map<string, number>();
    for (const kept of figures.keptInline) {
      const reason = kept.reason.replace(/-?\d+/g, 'N').replace(/'[^']*'/g, "'…'");
      reasons.set(reason, (reasons.get(reason) ?? 0) + 1);
    }
    for (const [reason, count] of reasons) console.log(`      left inline ${count}×: ${reason}`);
    if (details) for (const kept of figures.keptInline) console.log(`        ${kept.group} in ${kept.input}: ${kept.reason}`);
  }
  for (const name of missing)
    console.log(`  (${name} skipped: absent; see the header of test/support/modularizeLibrary.ts for where it is looked for)`);
}

main().catch((error: unknown) => {
  console.error(error);
  process.exitCode = 1;
});

/**
 * Run by the signal tests: starts an atomic write whose data never ends, says so on standard
 * output, and waits to be interrupted.
 */
import { writeFileAtomic } from '../../common/src/atomic';

async function* endless(): AsyncGenerator<Uint8Array> {
  yield new TextEncoder().encode('<OpenSCENARIO>');
  process.stdout.write('writing\n');
  await new Promise(() => setInterval(() => undefined, 1000));
}

writeFileAtomic(process.argv[2], endless()).catch((error) => {
  process.stderr.write(`${(error as Error).stack}\n`);
  process.exit(1);
});

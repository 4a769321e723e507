import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot, sharedDir } from './paths';

export const esminiXodrDir = path.join(sharedDir, 'esmini', 'xodr');
export const esminiBinDir = path.join(repoRoot, '.cache', 'esmini', 'bin');

/**
 * The path of an esmini program built into the project's cache (esmini, odrplot, dat2csv), or a skip
 * of the suite with a message. With M2S_REQUIRE_ESMINI set, a missing program fails instead.
 */
export function requireEsminiProgram(context: Mocha.Context, program: 'esmini' | 'odrplot' | 'dat2csv'): string {
  return requireBuilt(context, path.join(esminiBinDir, program));
}

/** esmini's C library as the same build installs it (`.cache/esmini/lib`), or a skip with a message (a failure with M2S_REQUIRE_ESMINI). */
export function requireEsminiLibrary(context: Mocha.Context): string {
  return requireBuilt(context, path.join(esminiBinDir, '..', 'lib', 'libesminiLib.so'));
}

function requireBuilt(context: Mocha.Context, file: string): string {
  if (fs.existsSync(file) && fs.existsSync(esminiXodrDir)) return file;
  const why = !fs.existsSync(esminiXodrDir)
    ? `${esminiXodrDir} is absent`
    : `${file} is absent (build it with: bash ../shared/esmini/build.sh .cache/esmini)`;
  if (process.env.M2S_REQUIRE_ESMINI) throw new Error(`M2S_REQUIRE_ESMINI is set, but ${why}`);
  console.log(`    (skipped: ${why})`);
  context.skip();
}

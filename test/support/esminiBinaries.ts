import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinary, esminiRoads } from './esmini';

export const esminiXodrDir = esminiRoads;

/**
 * The path of a program esmini's build installs beside `esmini` (odrplot, dat2csv), or a skip of the
 * suite with a message. With M2S_REQUIRE_ESMINI set, a missing program fails instead.
 */
export function requireEsminiProgram(context: Mocha.Context, program: 'esmini' | 'odrplot' | 'dat2csv'): string {
  const file = path.join(path.dirname(esminiBinary), program);
  if (fs.existsSync(file) && fs.existsSync(esminiRoads)) return file;
  const why = !fs.existsSync(esminiRoads) ? `${esminiRoads} is absent` : `${file} is absent (build it with: bash ../shared/esmini/build.sh .cache/esmini)`;
  if (process.env.M2S_REQUIRE_ESMINI) throw new Error(`M2S_REQUIRE_ESMINI is set, but ${why}`);
  console.log(`    (skipped: ${why})`);
  context.skip();
}

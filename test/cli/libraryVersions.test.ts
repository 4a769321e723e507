import { strict as assert } from 'node:assert';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { main } from '../../server/src/cli';
import { LibraryModule, listLibraries } from '../../server/src/core/library';
import { nodeFileSystem } from '../../server/src/core/sources';
import { builtInLibraryFolder, libraryFolders } from '../../server/src/libraries';
import { LIBRARY_RUN_ARGS, runExample } from '../../scripts/library-pictures';
import { esminiBinary, requireEsmini } from '../support/esmini';
import { recordedEnvironments } from '../support/esminiDat';
import { BEHAVIOURS, tracksOf } from '../support/libraryBehaviours';
import { temporaryFolder } from '../support/temporaryDirectory';

/**
 * A library module (OpenSCENARIO 1.1) imported by a main of a later version: the output is written in the main's
 * version, so that neither `check` nor esmini warns of a deprecated attribute in a file the user cannot edit (issue 28).
 */
describe('library modules in a main of a later OpenSCENARIO version', function () {
  this.timeout(120_000);
  const library = builtInLibraryFolder() ?? '';
  const folder = temporaryFolder('m2s-library-versions-');
  let weather: LibraryModule;

  before(async () => {
    const listing = await listLibraries(nodeFileSystem, libraryFolders([], {}));
    const found = listing.modules.find((module) => module.name === 'weather-light-change');
    assert.ok(found?.example, 'no weather-light-change module with an example main');
    weather = found;
  });

  /** The weather module's example main stating OpenSCENARIO 1.`minor`, its road found from `folder`, with `keys` changed. */
  function exampleIn(minor: number, keys: Record<string, string> = {}): string {
    let text = fs
      .readFileSync(weather.example ?? '', 'utf8')
      .replace('revMinor="1"', `revMinor="${minor}"`)
      .replace('filepath="../roads/', `filepath="${path.join(library, 'roads')}/`);
    for (const [key, value] of Object.entries(keys))
      text = text.replace(new RegExp(`(key="${key.replace('.', '\\.')}" value=")[^"]*`), `$1${value}`);
    const file = path.join(folder, `weather-1.${minor}${Object.keys(keys).length > 0 ? '-keys' : ''}.xosc`);
    fs.writeFileSync(file, text);
    return file;
  }

  async function cli(...args: string[]): Promise<{ code: number; text: string }> {
    const lines: string[] = [];
    const code = await main(args, { out: (text) => lines.push(text), err: (text) => lines.push(text) });
    return { code, text: lines.join('\n') };
  }

  it('weather-light-change in a 1.3 main: no deprecation warning; the output writes fractionalCloudCover and illuminance', async () => {
    const file = exampleIn(3);
    const checked = await cli('check', file);
    assert.equal(checked.code, 0, checked.text);
    assert.match(checked.text, /0 errors, 0 warnings/);
    const flat = await cli('flatten', file, '-q');
    assert.match(flat.text, /<Weather fractionalCloudCover="sixOktas">/);
    assert.match(flat.text, /<Sun azimuth="4.2" elevation="0.05" illuminance="400"\/>/);
    assert.doesNotMatch(flat.text, /cloudState=|intensity="400"/);
  });

  it("a key's value is what the later version's attribute holds; 1.2 renames the clouds only, 1.1 nothing", async () => {
    const keyed = await cli('flatten', exampleIn(3, { 'Weather.cloudState': 'cloudy', 'Sun.intensity': '1200' }), '-q');
    assert.match(keyed.text, /<Weather fractionalCloudCover="fourOktas">/);
    assert.match(keyed.text, /illuminance="1200"/);
    const file12 = exampleIn(2);
    const checked12 = await cli('check', file12);
    assert.match(checked12.text, /0 errors, 0 warnings/);
    const flat12 = await cli('flatten', file12, '-q');
    assert.match(flat12.text, /<Weather fractionalCloudCover="sixOktas">/);
    assert.match(
      flat12.text,
      /<Sun azimuth="4.2" elevation="0.05" intensity="400"\/>/,
      'illuminance is not in 1.2; intensity is required there',
    );
    const flat11 = await cli('flatten', exampleIn(1), '-q');
    assert.match(flat11.text, /<Weather cloudState="rainy">/);
  });

  it('in esmini the 1.3 main changes the environment as the module asks, its clouds as the 1.1 example, with no warning of a deprecated attribute', async function () {
    requireEsmini(this);
    const recordings = [1, 3].map((minor) => path.join(folder, `weather-1.${minor}.dat`));
    const environments = [];
    for (const [index, minor] of [1, 3].entries()) {
      const { run } = await runExample({ ...weather, example: exampleIn(minor) }, folder, esminiBinary, recordings[index]);
      const recorded = recordedEnvironments(fs.readFileSync(recordings[index]));
      BEHAVIOURS['weather-light-change'](weather, tracksOf(run), recorded);
      environments.push(recorded[0]);
    }
    assert.equal(environments[1].cloudStateFactor, environments[0].cloudStateFactor, 'the clouds differ from the 1.1 example');
    const flat = path.join(folder, 'weather-1.3.flat.xosc');
    assert.equal((await cli('flatten', exampleIn(3), '-o', flat, '-q')).code, 0);
    const args = LIBRARY_RUN_ARGS.filter((arg) => arg !== '--disable_log');
    const esmini = spawnSync(esminiBinary, [...args, '--logfile_path', path.join(folder, 'log.txt'), '--osc', flat], {
      cwd: folder,
      encoding: 'utf8',
    });
    assert.equal(esmini.status, 0, esmini.stdout + esmini.stderr);
    assert.doesNotMatch(esmini.stdout, /deprecated/i);
    assert.match(esmini.stdout, /WeatherLightChange/, 'esmini logged nothing of the run');
  });
});

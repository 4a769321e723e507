// `npx tsx scripts/library-pictures.ts [--check]`: draws each module's picture (library/pictures/NAME.svg) from
// esmini's log of its example main, flattened as `modular2simple flatten` does and run headless with a fixed step.
// --check writes nothing and lists the pictures that differ (exit 1 if any). test/cli/libraryModules.test.ts runs
// the same function and asserts each module's behaviour on the same log.
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { EsminiRun, parseEsminiCsv } from '../common/src/esminiCsv';
import { main } from '../server/src/cli';
import { LibraryModule, listLibraries } from '../server/src/core/library';
import { parseOpenDrive } from '../server/src/core/opendrive/road';
import { sampleNetwork } from '../server/src/core/opendrive/sample';
import { nodeFileSystem } from '../server/src/core/sources';
import { trackPicture } from '../server/src/core/trackPicture';
import { locateEsmini } from '../server/src/esmini/locate';
import { builtInLibraryFolder, libraryFolders } from '../server/src/libraries';

/** The step and seed every library run uses, so that a run, and its picture, repeat exactly. */
export const LIBRARY_RUN_ARGS = ['--headless', '--fixed_timestep', '0.05', '--seed', '1', '--disable_log'];

/**
 * A module's example main flattened into `folder`, run in esmini, and drawn: esmini's log and the picture; with
 * `record`, esmini also writes its recording (`--record`) there, which carries what the log does not (the environment).
 */
export async function runExample(
  module: LibraryModule,
  folder: string,
  esmini: string,
  record?: string,
): Promise<{ run: EsminiRun; svg: string }> {
  if (!module.example) throw new Error(`${module.name} has no example main`);
  const flat = path.join(folder, `${module.name}.xosc`);
  const csv = path.join(folder, `${module.name}.csv`);
  const errors: string[] = [];
  const code = await main(['flatten', module.example, '-o', flat, '-q'], { out: () => {}, err: (text) => errors.push(text) });
  if (code !== 0) throw new Error(`flatten ${module.example}: ${errors.join('\n')}`);
  const result = spawnSync(esmini, [...LIBRARY_RUN_ARGS, '--osc', flat, '--csv_logger', csv, ...(record ? ['--record', record] : [])], {
    cwd: folder,
    encoding: 'utf8',
    timeout: 120_000,
  });
  if (result.status !== 0 || !fs.existsSync(csv))
    throw new Error(`esmini failed on ${module.name} (exit ${result.status}):\n${(result.stdout + result.stderr).slice(-2000)}`);
  const run = parseEsminiCsv(fs.readFileSync(csv, 'utf8'));
  const exampleText = fs.readFileSync(module.example, 'utf8');
  const road = /<LogicFile\s+filepath="([^"]+)"/.exec(exampleText)?.[1];
  if (!road) throw new Error(`${module.example} names no road`);
  const network = parseOpenDrive(fs.readFileSync(path.resolve(path.dirname(module.example), road), 'utf8'));
  const svg = trackPicture(sampleNetwork(network), run, { title: `library:${module.name}: ${module.title}` });
  fs.rmSync(csv, { force: true });
  fs.rmSync(flat, { force: true });
  return { run, svg };
}

async function writePictures(check: boolean): Promise<number> {
  const library = builtInLibraryFolder();
  if (!library) throw new Error('no library/ folder beside this project');
  const esmini = locateEsmini(undefined);
  if (!esmini.found) throw new Error(esmini.message);
  const listing = await listLibraries(nodeFileSystem, libraryFolders([], {}, library).slice(-1));
  for (const problem of listing.problems) console.error(`${problem.file}:${problem.line ?? ''} ${problem.message}`);
  const pictures = path.join(library, 'pictures');
  fs.mkdirSync(pictures, { recursive: true });
  const work = fs.mkdtempSync(path.join(fs.realpathSync(process.env.TMPDIR ?? '/tmp'), 'm2s-pictures-'));
  let stale = 0;
  try {
    for (const module of listing.modules) {
      const { svg } = await runExample(module, work, esmini.program);
      const file = path.join(pictures, `${module.name}.svg`);
      if (!check) fs.writeFileSync(file, svg);
      else if (!fs.existsSync(file) || fs.readFileSync(file, 'utf8') !== svg) {
        console.log(`library/pictures/${module.name}.svg differs from what scripts/library-pictures.ts draws: run it`);
        stale++;
      }
    }
  } finally {
    fs.rmSync(work, { recursive: true, force: true });
  }
  return stale > 0 || listing.problems.length > 0 ? 1 : 0;
}

if (require.main === module) {
  writePictures(process.argv.includes('--check')).then(
    (code) => (process.exitCode = code),
    (error: unknown) => {
      console.error(error);
      process.exitCode = 1;
    },
  );
}

import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';

/**
 * The mocha run's private temporary folder (loaded first through .mocharc.json's `require`): TMPDIR names
 * it for this process and every process a test starts, before any test file asks os.tmpdir(). A private
 * folder rather than a before/after listing of the shared one, so that other runs on the machine do not count.
 * The run fails when anything is left in it at the end, and the folder goes either way.
 */
export const outerTemporaryDirectory = os.tmpdir();
export const runTemporaryDirectory = fs.mkdtempSync(path.join(outerTemporaryDirectory, 'm2s-run-'));
process.env.TMPDIR = runTemporaryDirectory;

/** Folders made by temporaryFolder while a suite runs: they go when its top-level suite ends. */
const madeFolders: string[] = [];
/** Folders made while the test files load: the run's end removes them. */
const madeAtLoad: string[] = [];

/** A fresh temporary folder (its real path), removed by the time the top-level `describe` that asked for it ends. */
export function temporaryFolder(prefix = 'm2s-test-'): string {
  const folder = fs.realpathSync(fs.mkdtempSync(path.join(os.tmpdir(), prefix)));
  madeFolders.push(folder);
  return folder;
}

/**
 * The folders the product keeps in os.tmpdir() for the private folders of its runs, which it removes one by one
 * (server/src/esmini/run.ts, server/src/batch/worker.ts): left empty, they are the product's; anything in them is a leak.
 */
const SHARED_RUN_PARENTS = ['modular2simple-esmini', 'modular2simple-worker'];

function removeEmptySharedParents(): void {
  for (const parent of SHARED_RUN_PARENTS) {
    try {
      fs.rmdirSync(path.join(runTemporaryDirectory, parent));
    } catch (error) {
      if (!['ENOENT', 'ENOTEMPTY'].includes((error as NodeJS.ErrnoException).code ?? '')) throw error;
    }
  }
}

function remove(folders: string[]): void {
  for (const folder of folders.splice(0)) fs.rmSync(folder, { recursive: true, force: true });
}

/** The top-level suite after which each entry of the run's folder was first seen. */
const leftBy = new Map<string, string>();

/** The entries of the run's folder, those of the product's shared parents one by one (`parent/entry`). */
function entries(): string[] {
  return fs.readdirSync(runTemporaryDirectory).flatMap((entry) => {
    if (!SHARED_RUN_PARENTS.includes(entry)) return [entry];
    const inside = fs.readdirSync(path.join(runTemporaryDirectory, entry));
    return inside.length > 0 ? inside.map((child) => `${entry}/${child}`) : [entry];
  });
}

function noteWhatIsLeft(suite: string): void {
  for (const entry of entries()) if (!leftBy.has(entry)) leftBy.set(entry, suite);
}

/** What is left in the run's folder, one line per entry: what it holds (at most 20 files named) and which suite left it. */
function leftovers(): string[] {
  return entries().map((entry) => {
    const full = path.join(runTemporaryDirectory, entry);
    const files = fs.statSync(full).isDirectory() ? fs.readdirSync(full, { recursive: true }).map(String) : [];
    const named = files.slice(0, 20).join(', ') + (files.length > 20 ? `, ... (${files.length} in all)` : '');
    const suite = leftBy.get(entry);
    return `${entry}${files.length > 0 ? `/ (${named})` : ''}${suite ? `, left by "${suite}"` : ''}`;
  });
}

let removed = false;
function removeRunTemporaryDirectory(): void {
  if (removed) return;
  removed = true;
  fs.rmSync(runTemporaryDirectory, { recursive: true, force: true });
}
// A run that ends without reaching the root after-hook (an interrupted run) still takes its folder away.
process.once('exit', removeRunTemporaryDirectory);
for (const signal of ['SIGTERM', 'SIGHUP'] as const)
  process.once(signal, () => {
    removeRunTemporaryDirectory();
    process.kill(process.pid, signal);
  });

export const mochaHooks = {
  beforeAll(this: Mocha.Context): void {
    madeAtLoad.push(...madeFolders.splice(0));
    noteWhatIsLeft('loading the test files');
    for (const suite of this.test?.parent?.suites ?? [])
      suite.afterAll('remove the temporary folders this suite made', () => {
        remove(madeFolders);
        noteWhatIsLeft(suite.fullTitle());
      });
  },
  afterAll: function nothingIsLeftInTheTemporaryDirectory(): void {
    remove(madeFolders);
    remove(madeAtLoad);
    removeEmptySharedParents();
    const left = leftovers();
    removeRunTemporaryDirectory();
    if (left.length > 0)
      throw new Error(
        `the tests left ${left.length} entr${left.length === 1 ? 'y' : 'ies'} in the temporary directory:\n  ${left.join('\n  ')}`,
      );
  },
};

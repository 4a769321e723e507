import * as fs from 'node:fs';
import * as path from 'node:path';

export const repoRoot = path.resolve(__dirname, '..', '..');
export const sharedDir = path.resolve(repoRoot, '..', 'shared');
export const corpusDir = path.join(sharedDir, 'corpus', 'modular2simple');
export const libraryDir = path.join(corpusDir, 'library');
export const caseStudyDir = path.join(corpusDir, 'case-study');
export const cliPath = path.join(repoRoot, 'dist', 'cli.js');
export const serverBundle = path.join(repoRoot, 'dist', 'server.js');

/** Skips the calling suite, with a message, when ../shared/corpus is absent. */
export function requireCorpus(context: Mocha.Context): void {
  if (!fs.existsSync(corpusDir)) {
    console.log(`    (skipped: ${corpusDir} is absent)`);
    context.skip();
  }
}

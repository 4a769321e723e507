import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot } from './paths';
import { temporaryFolder } from './temporaryDirectory';

/**
 * The built CLI in a project folder of its own (its program copied, the bundle it runs linked), with no node_modules:
 * what the CLI finds by the folder it runs from (the esmini npm start built, the Redis queue's packages) is then
 * only what a test puts there, never the repository's own.
 */
export interface CliProject {
  project: string;
  run(args: string[], cwd: string, env?: Record<string, string>): { status: number | null; stdout: string; stderr: string };
  remove(): void;
}

/** `esmini`: a program to place where npm start builds esmini, `.cache/esmini/bin/esmini` (a link to it). */
export function cliInTemporaryProject(esmini?: string): CliProject {
  const project = temporaryFolder('m2s-project-');
  fs.writeFileSync(path.join(project, 'package.json'), '{}');
  fs.mkdirSync(path.join(project, 'dist'));
  const cli = path.join(project, 'dist', 'cli.js');
  // Copied: Node runs a linked program from where the link points, which would be the repository again.
  fs.copyFileSync(path.join(repoRoot, 'dist', 'cli.js'), cli);
  for (const file of ['cli-main.js', 'cli-main.js.cache', 'openscenario-schemas.json'])
    fs.symlinkSync(path.join(repoRoot, 'dist', file), path.join(project, 'dist', file));
  if (esmini !== undefined) {
    fs.mkdirSync(path.join(project, '.cache', 'esmini', 'bin'), { recursive: true });
    fs.symlinkSync(esmini, path.join(project, '.cache', 'esmini', 'bin', 'esmini'));
  }
  return {
    project,
    run(args, cwd, env = {}) {
      const result = spawnSync(process.execPath, [cli, ...args], {
        cwd,
        env: { ...process.env, SCENARIO_PATH: '', ...env },
        encoding: 'utf8',
      });
      return { status: result.status, stdout: result.stdout, stderr: result.stderr };
    },
    remove: () => fs.rmSync(project, { recursive: true, force: true }),
  };
}

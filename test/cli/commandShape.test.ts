import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { COMMAND_NAMES, ExitCode } from '../../server/src/cli';
import { runCli } from '../support/fixtures';
import { listFiles } from '../support/workspace';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

/** Every command of the table, over the program itself (dist/cli.js, which runs a short command's own bundle). */
describe('cli: every command has one shape (help, options, exit codes)', function () {
  this.timeout(120_000);
  let root: string;
  before(() => {
    root = temporaryFolder('m2s-shape-');
    fs.copyFileSync(path.join(repoRoot, 'test/fixtures/variations/follow.xosc'), path.join(root, 'follow.xosc'));
    fs.copyFileSync(path.join(repoRoot, 'test/fixtures/variations/follow_distribution.xosc'), path.join(root, 'distribution.xosc'));
  });
  after(() => fs.rmSync(root, { recursive: true, force: true }));

  it('lists every command and the original forms', () => {
    assert.deepEqual(
      [...COMMAND_NAMES].sort(),
      [
        '--convert-mosc-to-xosc',
        '--convert-xosc-into-mosc',
        '-cmx',
        '-cxm',
        'batch',
        'check',
        'export',
        'flatten',
        'format',
        'library',
        'modularize',
        'pack',
        'qc-bundle',
        'run',
        'stats',
        'vary',
        'worker',
      ].sort(),
    );
  });

  for (const name of COMMAND_NAMES) {
    it(`${name} --help prints its own help on standard output and exits 0; so do -h and --help after other arguments`, () => {
      const help = runCli([name, '--help'], { cwd: root });
      assert.equal(help.status, ExitCode.ok, help.stderr);
      assert.equal(help.stderr, '');
      // Its own: the command's usage, not the overview of all commands.
      assert.ok(help.stdout.includes(name), help.stdout);
      assert.doesNotMatch(help.stdout, /^Usage:/m);
      assert.match(help.stdout, /Exit codes: 0 /);
      // Each help text is whole: no placeholder of a shared part left as written (check --help printed '${LIMIT_OPTIONS_HELP}').
      assert.doesNotMatch(help.stdout, /\$\{[A-Z_]+\}/);
      assert.deepEqual(runCli([name, '-h'], { cwd: root }), help);
      assert.deepEqual(runCli([name, 'no-such-input.xosc', '--help'], { cwd: root }), help);
      assert.deepEqual(listFiles(root), ['distribution.xosc', 'follow.xosc'], 'help wrote nothing');
    });
  }

  it('the overview names each command and how to get its help', () => {
    const help = runCli(['--help']);
    assert.equal(help.status, ExitCode.ok);
    for (const name of COMMAND_NAMES.filter((command) => !command.startsWith('-')))
      assert.match(help.stdout, new RegExp(`modular2simple ${name} `));
    assert.match(help.stdout, /modular2simple COMMAND --help/);
    assert.match(help.stdout, /-o, --output FILE/);
    assert.match(help.stdout, /--out-dir DIR/);
  });

  // The arguments that make each command reach its input (a missing one), so that the input's error is what stops it.
  const missingInput: Record<string, string[]> = {
    flatten: ['no-such.xosc'],
    pack: ['no-such.xosc', '-o', 'out.mosc'],
    check: ['no-such.xosc'],
    stats: ['no-such-folder'],
    format: ['no-such.xosc'],
    run: ['no-such.xosc'],
    vary: ['no-such.xosc', '--count'],
    modularize: ['no-such.xosc', '--out-dir', 'out'],
    batch: ['no-such.xosc', '--results', 'results'],
    'qc-bundle': ['-c', 'no-such.xml'],
    export: ['no-such.xosc', '--target', 'carla', '-o', 'out.xosc'],
    library: ['show', 'no-such-module'],
    '-cxm': ['no-such.xosc', 'out.mosc'],
    '-cmx': ['no-such.mosc', 'out.xosc'],
  };

  for (const name of COMMAND_NAMES) {
    it(`${name}: an unknown option is wrong usage (exit 2), worded as every command words it`, () => {
      const run = runCli([name, '--no-such-option'], { cwd: root });
      assert.equal(run.status, ExitCode.usage, run.stderr);
      assert.equal(run.stderr, "modular2simple: unknown option '--no-such-option'\nRun 'modular2simple --help' for usage.\n");
      assert.equal(run.stdout, '');
    });
  }

  for (const [name, args] of Object.entries(missingInput)) {
    it(`${name}: an input that is not there is exit 1, naming it, and nothing is written`, () => {
      const run = runCli([name, ...args], { cwd: root });
      assert.equal(run.status, ExitCode.problems, run.stderr);
      assert.match(run.stderr, /no-such/);
      assert.doesNotMatch(run.stderr, /internal error|\n\s+at /);
      assert.deepEqual(listFiles(root), ['distribution.xosc', 'follow.xosc']);
    });
  }

  it('what a command needs beside its inputs (esmini, Redis) missing is exit 3, for run, batch and worker alike', () => {
    const esmini = path.join(root, 'no-such-esmini');
    const runs = [
      runCli(['run', 'follow.xosc', '--esmini', esmini], { cwd: root }),
      runCli(['batch', 'distribution.xosc', '--results', 'results', '--esmini', esmini], { cwd: root }),
      runCli(['worker', '--queue', 'redis://127.0.0.1:9', '--esmini', esmini], { cwd: root }),
    ];
    for (const run of runs) {
      assert.equal(run.status, ExitCode.io, run.stderr);
      assert.match(run.stderr, /^modular2simple: error: esmini is not at /m);
      assert.doesNotMatch(run.stderr, /internal error|\n\s+at /);
    }
    assert.deepEqual(listFiles(root), ['distribution.xosc', 'follow.xosc']);
  });

  it('modularize and qc-bundle take --out-dir DIR, and -o DIR as before; either, not both', () => {
    for (const args of [
      ['modularize', 'follow.xosc', '-o', 'out', '--out-dir', 'out'],
      ['qc-bundle', '-c', 'config.xml', '-o', 'out', '--out-dir', 'out'],
    ]) {
      const run = runCli(args, { cwd: root });
      assert.equal(run.status, ExitCode.usage, run.stderr);
      assert.match(run.stderr, /use either -o or --out-dir/);
    }
    const dry = (flag: string) => runCli(['modularize', 'follow.xosc', flag, 'out', '--dry-run'], { cwd: root });
    const old = dry('-o');
    assert.equal(old.status, ExitCode.ok, old.stderr);
    assert.deepEqual(dry('--out-dir'), old);
    assert.deepEqual(listFiles(root), ['distribution.xosc', 'follow.xosc']);
  });
});

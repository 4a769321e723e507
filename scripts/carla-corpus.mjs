// How many of the corpus files `export --target carla` writes and ScenarioRunner's own loader builds, per
// ScenarioRunner release (issue 26): esmini's samples, ScenarioRunner's examples, the paper's 31 library
// scenarios and its case study. Needs `npm run build` and the harness (python3 ../shared/carla/check.py setup).
//   node scripts/carla-corpus.mjs            prints the table, and each refusal's reason with -v
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const shared = path.resolve(root, '..', 'shared');
const corpus = path.join(shared, 'corpus');
const cli = path.join(root, 'dist', 'cli.js');
const harness = path.join(shared, 'carla', 'check.py');
const verbose = process.argv.includes('-v');

/**
 * @typedef {{ input: string, extra: string[] }} Input
 * @typedef {{ name: string, inputs: Input[] }} Corpus
 */

const esmini = path.join(corpus, 'openscenario', 'esmini');
const examples = path.join(corpus, 'openscenario', 'scenario_runner');
const library = path.join(corpus, 'modular2simple', 'library');
/** @type {Corpus[]} */
const corpora = [
  {
    name: "esmini's samples",
    inputs: readdirSync(esmini)
      .filter((name) => name.endsWith('.xosc'))
      .map((name) => ({
        input: path.join(esmini, name),
        extra: [
          ...['--road-path', path.join(shared, 'esmini', 'xodr'), '--scenario-path', path.join(esmini, 'Catalogs')],
          ...(name === 'cut-in_parameter_set.xosc' ? ['--index', '0'] : []),
        ],
      })),
  },
  {
    name: "ScenarioRunner's examples",
    inputs: readdirSync(examples)
      .filter((name) => name.endsWith('.xosc') && !name.endsWith('Catalog.xosc'))
      .map((name) => ({ input: path.join(examples, name), extra: ['--scenario-path', examples] })),
  },
  {
    name: "the paper's library + case study",
    inputs: [
      ...readdirSync(library)
        .filter((name) => existsSync(path.join(library, name, 'main.xosc')))
        .map((name) => ({ input: path.join(library, name, 'main.xosc'), extra: ['--scenario-path', library] })),
      { input: path.join(corpus, 'modular2simple', 'case-study'), extra: ['--force'] },
    ],
  },
];

for (const needed of [cli, harness, path.join(root, '.cache', 'carla', 'scenario_runner')])
  if (!existsSync(needed)) {
    console.error(`${needed} is missing: npm run build, and python3 ../shared/carla/check.py setup`);
    process.exit(1);
  }

/**
 * ScenarioRunner's verdict on each file: OK, or the stage and reason it failed.
 * @param {string[]} files
 * @param {boolean} fixSrBugs
 * @returns {Map<string, { status: string, stage: string | null, reason: string | null }>}
 */
function verdicts(files, fixSrBugs) {
  if (files.length === 0) return new Map();
  const json = path.join(out, `verdicts-${Date.now()}.json`);
  const args = [harness, '--json', json, '--jobs', '2', '--timeout', '120', ...(fixSrBugs ? ['--fix-sr-bugs'] : []), ...files];
  const result = spawnSync('python3', args, { cwd: root, encoding: 'utf8', timeout: files.length * 120_000 + 60_000 });
  if (!existsSync(json)) throw new Error(`the harness failed (${result.status}): ${result.stdout}${result.stderr}`);
  /** @type {{ results: { file: string, status: string, stage: string | null, reason: string | null }[] }} */
  const parsed = JSON.parse(readFileSync(json, 'utf8'));
  return new Map(parsed.results.map((each) => [path.resolve(each.file), each]));
}

const out = mkdtempSync(path.join(tmpdir(), 'm2s-carla-corpus-'));
try {
  /** @type {string[][]} */
  const rows = [];
  /** @type {string[]} */
  const reasons = [];
  /** @type {string[]} */
  const notBuilt = [];
  for (const { name, inputs } of corpora) {
    const asWritten = verdicts(
      inputs.map(({ input }) => (input.endsWith('.xosc') ? input : path.join(input, 'main.xosc'))),
      false,
    );
    const row = [name, String(inputs.length), `${[...asWritten.values()].filter((each) => each.status === 'OK').length}`];
    for (const release of ['0.9.16', '0.9.15']) {
      const folder = path.join(out, `${rows.length}-${release}`);
      mkdirSync(folder);
      /** @type {string[]} */
      const written = [];
      /** @type {Map<string, number>} */
      const refusedFor = new Map();
      inputs.forEach(({ input, extra }, index) => {
        const output = path.join(
          folder,
          `${index}-${path.basename(input === path.dirname(input) ? input : input.replace(/\/main\.xosc$/, ''))}.xosc`,
        );
        const result = spawnSync(
          process.execPath,
          [cli, 'export', input, '--target', 'carla', '--carla', release, '-o', output, '-q', ...extra],
          {
            encoding: 'utf8',
            timeout: 120_000,
          },
        );
        if (result.status === 0) written.push(output);
        else {
          const reason = /export refused: (.*)|error: (.*)/.exec(result.stderr);
          const why = (reason?.[1] ?? reason?.[2] ?? result.stderr.trim().split('\n')[0] ?? '').replace(/^\S+:\d+: /, '');
          const short = why.replace(/ \[refused;.*$/, '').replace(/none of its \d+ events/, 'none of its events');
          const kind = /crashes ScenarioRunner 0\.9\.16/.test(result.stderr) ? "0.9.16's route crash" : short.slice(0, 90);
          refusedFor.set(kind, (refusedFor.get(kind) ?? 0) + 1);
          if (verbose) reasons.push(`${release} ${path.relative(corpus, input)}: ${why}`);
        }
      });
      const built = verdicts(written, release === '0.9.15');
      const ok = written.filter((file) => built.get(path.resolve(file))?.status === 'OK').length;
      for (const file of written) {
        const verdict = built.get(path.resolve(file));
        if (verdict?.status !== 'OK') notBuilt.push(`${release} written but not built: ${file}: ${verdict?.stage} ${verdict?.reason}`);
      }
      const refused = [...refusedFor].map(([why, count]) => `${count} ${why}`).join('; ');
      row.push(`${written.length} written, ${ok} build${refused ? ` | refused: ${refused}` : ''}`);
    }
    rows.push(row);
  }
  console.log('export --target carla on the corpus, built by ScenarioRunner (../shared/carla/check.py; 0.9.15 = --fix-sr-bugs)');
  for (const row of rows) {
    console.log(`\n${row[0]}: ${row[1]} files, ${row[2]} build as written (0.9.16)`);
    console.log(`  export, 0.9.16: ${row[3]}`);
    console.log(`  export, 0.9.15: ${row[4]}`);
  }
  if (notBuilt.length > 0) console.log(`\n${notBuilt.join('\n')}`);
  if (verbose) console.log(`\n${reasons.join('\n')}`);
} finally {
  rmSync(out, { recursive: true, force: true });
}

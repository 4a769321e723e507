// How many of the corpus files `export --target carla` writes and ScenarioRunner's own loader builds, per
// ScenarioRunner release (issue 26): esmini's samples, ScenarioRunner's examples, the paper's 31 library
// scenarios and its case study. Needs `npm run build` and the harness (python3 ../shared/carla/check.py setup).
//   node scripts/carla-corpus.mjs            prints the table, and each refusal's reason with -v
//   node scripts/carla-corpus.mjs --check    instead compares `check --simulator carla` with ScenarioRunner's verdict
//                                            on each file as written: a false alarm, or a refusal the check missed
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
const compareCheck = process.argv.includes('--check');

/**
 * @typedef {{ input: string, extra: string[] }} Input
 * @typedef {{ name: string, inputs: Input[], asWritten?: Input[] }} Corpus
 * `asWritten`: the files ScenarioRunner reads as they are, when `inputs` are modular (the original tool's flattened output).
 */

const esmini = path.join(corpus, 'openscenario', 'esmini');
const examples = path.join(corpus, 'openscenario', 'scenario_runner');
const library = path.join(corpus, 'modular2simple', 'library');
// Town05's OpenDRIVE, as esmini finds it: the export plans the library's story routes on its lanes.
const townRoad = ['--road-path', path.join(shared, 'esmini', 'xodr')];
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
        .map((name) => ({ input: path.join(library, name, 'main.xosc'), extra: ['--scenario-path', library, ...townRoad] })),
      { input: path.join(corpus, 'modular2simple', 'case-study'), extra: ['--force', ...townRoad] },
    ],
    asWritten: [
      ...readdirSync(library)
        .filter((name) => existsSync(path.join(library, name, 'result.xosc')))
        .map((name) => ({ input: path.join(library, name, 'result.xosc'), extra: [] })),
      { input: path.join(corpus, 'modular2simple', 'case-study.expected.xosc'), extra: [] },
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

/** The folder options of an export's arguments, which check takes too (not --index, --force). */
function searchPaths(/** @type {string[]} */ extra) {
  return extra.flatMap((each, index) =>
    ['--road-path', '--scenario-path'].includes(extra[index - 1] ?? '') || ['--road-path', '--scenario-path'].includes(each) ? [each] : [],
  );
}

/**
 * `check --simulator carla` on each file as written against ScenarioRunner's verdict on it, per release: the check's
 * errors say ScenarioRunner refuses the file, so an error on a file it builds is a false alarm, and no error on a file
 * it refuses a refusal missed.
 */
function checkAgainstScenarioRunner() {
  console.log('check --simulator carla against ScenarioRunner on each file as written (../shared/carla/check.py; 0.9.15 = --fix-sr-bugs)');
  /** @type {string[]} */
  const disagreements = [];
  for (const { name, inputs, asWritten } of corpora) {
    const files = (asWritten ?? inputs).filter(({ input }) => input.endsWith('.xosc'));
    for (const release of ['0.9.16', '0.9.15']) {
      const built = verdicts(
        files.map(({ input }) => input),
        release === '0.9.15',
      );
      /** @type {Map<string, string[]>} */
      const errors = new Map();
      for (const { input, extra } of files) {
        const result = spawnSync(
          process.execPath,
          [cli, 'check', input, '--simulator', 'carla', '--carla', release, '--format', 'json', ...searchPaths(extra)],
          { encoding: 'utf8', timeout: 120_000, maxBuffer: 64 * 1024 * 1024 },
        );
        if (result.status !== 0 && result.status !== 1) throw new Error(`check ${input} exited ${result.status}: ${result.stderr}`);
        /** @type {{ problems: { severity: string, code: string, message: string }[] }} */
        const report = JSON.parse(result.stdout);
        errors.set(
          input,
          report.problems.filter((each) => each.severity === 'error').map((each) => `${each.code}: ${each.message}`),
        );
      }
      let [builds, refuses, falseAlarms, missed] = [0, 0, 0, 0];
      for (const { input } of files) {
        const verdict = built.get(path.resolve(input));
        if (!verdict || verdict.status === 'SKIP') continue;
        const said = errors.get(input) ?? [];
        if (verdict.status === 'OK') {
          builds++;
          if (said.length > 0) {
            falseAlarms++;
            disagreements.push(`${release} false alarm: ${input}: ${said[0]}`);
          }
        } else {
          refuses++;
          if (said.length === 0) {
            missed++;
            disagreements.push(`${release} missed: ${input}: ScenarioRunner ${verdict.stage}: ${verdict.reason}`);
          }
        }
      }
      console.log(`  ${name}, ${release}: ${builds} build, ${refuses} refused; ${falseAlarms} false alarms, ${missed} refusals missed`);
    }
  }
  if (disagreements.length > 0) console.log(`\n${disagreements.join('\n')}`);
  return disagreements.length;
}

const out = mkdtempSync(path.join(tmpdir(), 'm2s-carla-corpus-'));
try {
  if (compareCheck) process.exitCode = checkAgainstScenarioRunner() > 0 ? 1 : 0;
  else exportCorpus();
} finally {
  rmSync(out, { recursive: true, force: true });
}

/** Each corpus exported for both releases, and what ScenarioRunner builds of what was written. */
function exportCorpus() {
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
}

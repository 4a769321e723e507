// Figures for hostile input (not a timed test): for each bound of docs/cli.md, the CLI on the largest
// input that bound lets through or stops, with its time and peak memory. Run `npm run build` first.
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import JSZip from 'jszip';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const cli = path.join(root, 'dist', 'cli.js');
const peak = path.join(root, 'bench', 'peak-rss.cjs');
const MiB = 1024 * 1024;

/** @param {string} groups */
const header = (groups) => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2026-01-01T00:00:00" description="bench" author="bench"/>
  <Entities><ScenarioObject name="car"/></Entities>
  <Storyboard><Story name="S"><Act name="A">
${groups}  </Act></Story></Storyboard>
</OpenSCENARIO>
`;
/** @param {string} name */
const simpleGroup = (
  name,
) => `<ManeuverGroup name="${name}" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>
  <Maneuver name="M"><Event name="E" priority="overwrite"><Action name="A"><SpeedActionTarget><AbsoluteTargetSpeed parameterAttributes="value" value="10"/></SpeedActionTarget></Action></Event></Maneuver></ManeuverGroup>
`;
/**
 * @param {string} outer
 * @param {string} file
 * @param {string} group
 */
const reference = (
  outer,
  file,
  group,
) => `<ManeuverGroup name="${outer}" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>
  <ScenarioReference scenarioFileName="${file}"><ManeuverGroupReference maneuverGroupName="${group}"/></ScenarioReference></ManeuverGroup>
`;

/**
 * The CLI on `args` (a command, then its operands), the schema check off: the inputs are minimal, not
 * schema-valid, and the outcome printed must be the bound's or the parser's (the first error), not the schema's.
 * @param {string} label
 * @param {string[]} args
 * @param {string} cwd
 */
function measure(label, args, cwd) {
  const started = process.hrtime.bigint();
  const [command, ...operands] = args;
  const result = spawnSync(process.execPath, ['--require', peak, cli, command, '--schema-version=off', ...operands], {
    cwd,
    encoding: 'utf8',
    env: { ...process.env, SCENARIO_PATH: '' },
    maxBuffer: 256 * MiB,
  });
  const ms = Number(process.hrtime.bigint() - started) / 1e6;
  const kb = Number(/@@peak-rss-kb (\d+)/.exec(result.stderr)?.[1] ?? NaN);
  const outcome = result.status === 0 ? 'accepted' : (/error: (.*)/.exec(result.stderr)?.[1] ?? `exit ${result.status}`).slice(0, 90);
  console.log(
    `  ${label.padEnd(52)} ${ms.toFixed(0).padStart(7)} ms ${(kb / 1024).toFixed(0).padStart(6)} MB  exit ${result.status}: ${outcome}`,
  );
}

/** @param {Record<string, string | Uint8Array>} files */
async function zipOf(files) {
  const zip = new JSZip();
  for (const [name, content] of Object.entries(files)) zip.file(name, content);
  return zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
}

const work = mkdtempSync(path.join(tmpdir(), 'm2s-bench-hostile-'));
/** @param {string} name */
const folder = (name) => {
  const dir = path.join(work, name);
  mkdirSync(dir, { recursive: true });
  return dir;
};

console.log('hostile input, one CLI run each (time includes process start; peak = resident memory)');

// One file at the file bound (32 MiB), and just over it.
{
  const dir = folder('file');
  const body = simpleGroup('G');
  const text = body.repeat(Math.floor((32 * MiB - 1024) / body.length));
  writeFileSync(path.join(dir, 'at.xosc'), header(text));
  writeFileSync(path.join(dir, 'over.xosc'), header(text + body.repeat(20)));
  measure('file: 32 MiB scenario (at the bound), check', ['check', 'at.xosc', '-q'], dir);
  measure('file: 32 MiB + 4 KiB scenario (over), check', ['check', 'over.xosc', '-q'], dir);
}

// Packages unpacking to the run's total bound (128 MiB): four packages of 31 MiB each, then five.
{
  const dir = folder('total');
  const padding = `<!-- ${'x'.repeat(31 * MiB)} -->`;
  const groups = [];
  for (let index = 0; index < 5; index++) {
    writeFileSync(path.join(dir, `p${index}.mosc`), await zipOf({ 'main.xosc': header(simpleGroup('G')) + padding }));
    groups.push(reference(`C${index}`, `p${index}.mosc`, 'G'));
  }
  writeFileSync(path.join(dir, 'four.xosc'), header(groups.slice(0, 4).join('')));
  writeFileSync(path.join(dir, 'five.xosc'), header(groups.join('')));
  measure('unpacked: 4 packages of 31 MiB (124 MiB, within)', ['check', 'four.xosc', '-q'], dir);
  measure('unpacked: 5 packages of 31 MiB (over 128 MiB)', ['check', 'five.xosc', '-q'], dir);
  // A lying entry: declares 100 bytes, inflates to 1 GiB.
  const bomb = await zipOf({ 'main.xosc': new Uint8Array(1024 * MiB) });
  const view = new DataView(bomb.buffer, bomb.byteOffset, bomb.byteLength);
  for (let offset = bomb.length - 22; offset >= 0; offset--) {
    if (view.getUint32(offset, true) === 0x06054b50) {
      const central = view.getUint32(offset + 16, true);
      view.setUint32(central + 24, 100, true);
      break;
    }
  }
  writeFileSync(path.join(dir, 'bomb.mosc'), bomb);
  measure('unpacked: 1 MiB ZIP inflating to 1 GiB, declaring 100 bytes', ['check', 'bomb.mosc', '-q'], dir);
}

// Flattened size: a group imported twice at each of 20 levels, stopped at the 8 Mi bound.
{
  const dir = folder('reuse');
  writeFileSync(path.join(dir, 'l20.xosc'), header(simpleGroup('G')));
  for (let level = 0; level < 20; level++) {
    /** @param {string} name */
    const half = (name) => reference(name, `l${level + 1}.xosc`, 'G');
    writeFileSync(
      path.join(dir, `l${level}.xosc`),
      header(
        `<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>\n${half('X')}${half('Y')}</ManeuverGroup>\n`,
      ),
    );
  }
  measure('flattened: 20 levels x 2 imports (2^20 copies), flatten', ['flatten', 'l0.xosc', '-o', 'out.xosc', '-q'], dir);
  measure('flattened: the level that fits (l8.xosc, 4,096 copies)', ['flatten', 'l8.xosc', '-o', 'out.xosc', '-q'], dir);
}

// Nesting depth: packages nested 63 deep (within the bound of 64 files) and 200 deep.
for (const levels of [63, 200]) {
  const dir = folder(`depth${levels}`);
  /** @type {Uint8Array | undefined} */
  let inner;
  for (let level = levels; level >= 0; level--) {
    const name = Array.from({ length: levels - level }, () => 'G').join('.');
    inner = await zipOf(
      inner ? { 'main.xosc': header(reference('G', 'inner.mosc', name)), 'inner.mosc': inner } : { 'main.xosc': header(simpleGroup('G')) },
    );
  }
  writeFileSync(path.join(dir, 'outer.mosc'), /** @type {Uint8Array} */ (inner));
  measure(`depth: packages nested ${levels} deep, flatten`, ['flatten', 'outer.mosc', '-o', 'out.xosc', '-q'], dir);
}

// Parsing: 1,000,000 attributes in one tag, and 4.8 MB of end tags matching nothing.
{
  const dir = folder('parse');
  writeFileSync(path.join(dir, 'attributes.xosc'), `<OpenSCENARIO ${Array.from({ length: 1_000_000 }, (_, i) => `a${i}="1"`).join(' ')}/>`);
  writeFileSync(
    path.join(dir, 'ends.xosc'),
    '<OpenSCENARIO>' + '<a>'.repeat(1999) + '</zz>'.repeat(960_000) + '</a>'.repeat(1999) + '</OpenSCENARIO>',
  );
  measure('parse: one tag with 1,000,000 attributes (13 MB)', ['check', 'attributes.xosc', '-q'], dir);
  measure('parse: 4.8 MB of end tags matching nothing', ['check', 'ends.xosc', '-q'], dir);
}

rmSync(work, { recursive: true, force: true });

// Modularize benchmark (prints figures, asserts nothing): `modularize` of the paper's 31-file library
// (target < 2 s) and of 500 generated scenarios sharing a few behaviours (target < 30 s), as processes.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const cli = path.join(root, 'dist', 'cli.js');
const library = path.resolve(root, '..', 'shared', 'corpus', 'modular2simple', 'library');
const runs = Number(process.env.BENCH_RUNS ?? 3);

if (!existsSync(cli)) {
  console.error('dist/cli.js is missing: run npm run build first');
  process.exit(1);
}

/**
 * Wall time of one run in ms, the output folder removed first; the report's total line.
 * @param {string[]} args
 * @param {string} out
 */
function measure(args, out) {
  rmSync(out, { recursive: true, force: true });
  const started = process.hrtime.bigint();
  const result = spawnSync(
    process.execPath,
    ['--require', path.join(root, 'bench', 'cpu-time.cjs'), cli, 'modularize', ...args, '-o', out],
    { encoding: 'utf8', maxBuffer: 64 * 1024 * 1024 },
  );
  const ms = Number(process.hrtime.bigint() - started) / 1e6;
  if (result.status !== 0) throw new Error(`modularize failed (exit ${result.status}): ${result.stderr.slice(-2000)}`);
  return {
    ms,
    cpuMs: Number(/@@cpu-ms (\d+)/.exec(result.stderr)?.[1] ?? NaN),
    total: /^total \(SPEC 9\).*$/m.exec(result.stdout)?.[0].replace(/\s+/g, ' ') ?? '',
  };
}

/**
 * @param {{ ms: number, cpuMs: number }[]} samples
 * @param {'ms' | 'cpuMs'} [field]
 */
function median(samples, field = 'ms') {
  const times = samples.map((sample) => sample[field]).sort((a, b) => a - b);
  return times[Math.floor(times.length / 2)];
}

/**
 * A deterministic generator (mulberry32), so every run modularizes the same scenarios.
 * @param {number} seed
 */
function generator(seed) {
  let state = seed >>> 0;
  return () => {
    state = (state + 0x6d2b79f5) >>> 0;
    let t = state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** @type {((value: number) => string)[]} */
const BEHAVIOURS = [
  (v) =>
    `<LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="${v}"/></SpeedActionTarget></SpeedAction></LongitudinalAction>`,
  (v) =>
    `<LateralAction><LaneChangeAction><LaneChangeActionDynamics dynamicsShape="sinusoidal" value="${v}" dynamicsDimension="time"/><LaneChangeTarget><RelativeTargetLane entityRef="ego" value="1"/></LaneChangeTarget></LaneChangeAction></LateralAction>`,
  (v) => `<TeleportAction><Position><WorldPosition x="${v}" y="0" z="0" h="0"/></Position></TeleportAction>`,
  (v) =>
    `<LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="linear" value="${v}" dynamicsDimension="rate"/><SpeedActionTarget><RelativeTargetSpeed entityRef="ego" value="0" speedTargetValueType="delta" continuous="false"/></SpeedActionTarget></SpeedAction></LongitudinalAction>`,
];

/**
 * A scenario of `groups` maneuver groups, each one of the behaviours above with its own values.
 * @param {() => number} random
 * @param {number} index
 */
function generatedScenario(random, index) {
  const lines = [
    '<?xml version="1.0" encoding="UTF-8"?>',
    '<OpenSCENARIO>',
    `  <FileHeader revMajor="1" revMinor="0" date="2026-01-01T00:00:00" description="generated ${index}" author="bench"/>`,
    '  <ParameterDeclarations/>',
    '  <CatalogLocations/>',
    '  <RoadNetwork/>',
    '  <Entities>',
  ];
  const cars = ['ego', 'car1', 'car2', 'car3'];
  for (const car of cars) lines.push(`    <ScenarioObject name="${car}"/>`);
  lines.push(
    '  </Entities>',
    '  <Storyboard>',
    '    <Init>',
    '      <Actions/>',
    '    </Init>',
    '    <Story name="S">',
    '      <Act name="A">',
  );
  for (let group = 0; group < 6; group++) {
    const kind = Math.floor(random() * BEHAVIOURS.length);
    const actor = cars[1 + Math.floor(random() * 3)];
    const value = [10, 20, 30, 5.5][Math.floor(random() * 4)];
    const delay = [0, 0, 1, 2][Math.floor(random() * 4)];
    lines.push(
      `        <ManeuverGroup maximumExecutionCount="1" name="G${group}.B${kind}">`,
      '          <Actors selectTriggeringEntities="false">',
      `            <EntityRef entityRef="${actor}"/>`,
      '          </Actors>',
      `          <Maneuver name="M${kind}">`,
      `            <Event name="E${kind}" priority="overwrite">`,
      `              <Action name="A${kind}">`,
      `                <PrivateAction>${BEHAVIOURS[kind](value)}</PrivateAction>`,
      '              </Action>',
      '              <StartTrigger>',
      '                <ConditionGroup>',
      `                  <Condition name="C" delay="${delay}" conditionEdge="rising">`,
      '                    <ByValueCondition>',
      `                      <SimulationTimeCondition value="${group}" rule="greaterThan"/>`,
      '                    </ByValueCondition>',
      '                  </Condition>',
      '                </ConditionGroup>',
      '              </StartTrigger>',
      '            </Event>',
      '          </Maneuver>',
      '        </ManeuverGroup>',
    );
  }
  lines.push('        <StartTrigger/>', '      </Act>', '    </Story>', '    <StopTrigger/>', '  </Storyboard>', '</OpenSCENARIO>', '');
  return lines.join('\n');
}

const work = mkdtempSync(path.join(tmpdir(), 'm2s-modularize-bench-'));
try {
  console.log(
    `modularize benchmark (median of ${runs} runs, wall time of the whole process; node ${process.version}; load average ${loadavg()[0].toFixed(1)})`,
  );
  if (existsSync(library)) {
    const inputs = readdirSync(library)
      .filter((folder) => existsSync(path.join(library, folder, 'result.xosc')))
      .map((folder) => path.join(library, folder, 'result.xosc'));
    const samples = Array.from({ length: runs }, () => measure(inputs, path.join(work, 'library-out')));
    const ms = median(samples);
    console.log(
      `  the paper's library (${inputs.length} files)       ${ms.toFixed(0).padStart(7)} ms wall, ${median(samples, 'cpuMs').toFixed(0).padStart(6)} ms CPU  ${ms < 2000 ? 'within' : 'OVER'} the 2 s target; ${samples[0].total}`,
    );
  } else {
    console.log(`  (library skipped: ${library} is absent)`);
  }
  const generated = path.join(work, 'generated');
  mkdirSync(generated);
  const random = generator(19);
  for (let i = 0; i < 500; i++)
    writeFileSync(path.join(generated, `scenario_${String(i).padStart(3, '0')}.xosc`), generatedScenario(random, i));
  const samples = Array.from({ length: Math.max(1, Math.min(runs, 2)) }, () => measure([generated], path.join(work, 'generated-out')));
  const ms = median(samples);
  console.log(
    `  500 generated scenarios                 ${ms.toFixed(0).padStart(7)} ms wall, ${median(samples, 'cpuMs').toFixed(0).padStart(6)} ms CPU  ${ms < 30000 ? 'within' : 'OVER'} the 30 s target; ${samples[0].total}`,
  );
} finally {
  rmSync(work, { recursive: true, force: true });
}

/**
 * Run in a child process by the scaling tests: builds an input of the given kind and size, then
 * prints the best of three CPU times of the operation, in milliseconds. The input is built outside the
 * timing; only the operation under test is timed.
 */
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import JSZip from 'jszip';
import { Flattener } from '../../server/src/core/flatten';
import { schemaFindingWords } from '../../server/src/core/diagnostics/schemaFindings';
import { checkSchema } from '../../server/src/core/schema/validate';
import { parameterValueProblems } from '../../server/src/core/semantics/parameterValues';
import { analyzeDocument, CatalogLoader, OUTPUT_CHECKS, SEMANTIC_CHECKS, simulatorProfile } from '../../server/src/core/semantics';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { checkScalingFiles } from './checkScaling';
import { outerGroup, roadScenario, scenario, simpleGroup } from './fixtures';
import { STRAIGHT_ROAD } from './roads';

type Operation = () => Promise<void> | void;

/** CPU milliseconds of this process since `started`: on a busy machine the wait for a core is not the operation's (wall time is). */
function cpuMsSince(started: NodeJS.CpuUsage): number {
  const used = process.cpuUsage(started);
  return (used.user + used.system) / 1000;
}

async function nestedPackages(levels: number): Promise<Operation> {
  // Level k's main.xosc imports group Go from inner.mosc, which is level k+1.
  let inner: Uint8Array | undefined;
  for (let level = levels; level >= 0; level--) {
    const zip = new JSZip();
    if (inner) {
      // The imported group carries the names of every level below: Go, Go.Go, Go.Go.Go, ...
      const name = Array.from({ length: levels - level }, () => 'Go').join('.');
      zip.file('main.xosc', scenario(outerGroup('Go', 'car', [{ file: 'inner.mosc', groups: [{ name }] }])));
      zip.file('inner.mosc', inner);
    } else {
      zip.file('main.xosc', scenario(simpleGroup('Go')));
    }
    inner = await zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
  }
  const folder = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-scaling-'));
  process.on('exit', () => fs.rmSync(folder, { recursive: true, force: true }));
  const file = path.join(folder, 'outer.mosc');
  fs.writeFileSync(file, inner as Uint8Array);
  return async () => {
    const store = new ScenarioStore({ root: folder, scenarioPath: [], limits: { maxDepth: levels + 10, maxTotalBytes: 2 ** 31 } });
    const result = await new Flattener(store).analyze(childRef(diskRef(file), 'main.xosc'));
    if (result.source.dependencies.length < levels) throw new Error(`only ${result.source.dependencies.length} files were read`);
  };
}

/** A schema-valid scenario whose vehicle's Properties hold `size` File entries (issue 27: 200,000 of them, 4 MB), checked and flattened as the CLI does. */
function siblingFiles(size: number): Operation {
  const folder = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-scaling-'));
  const file = path.join(folder, 'main.xosc');
  const files = Array.from({ length: size }, () => '<File filepath=""/>').join('\n');
  fs.writeFileSync(path.join(folder, 'road.xodr'), STRAIGHT_ROAD);
  fs.writeFileSync(
    file,
    roadScenario({
      groups: [
        '<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><Maneuver name="M"><Event name="E" priority="override"><Action name="A"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>',
      ],
    }).replace('<Properties/>', `<Properties>\n${files}\n</Properties>`),
  );
  process.on('exit', () => fs.rmSync(folder, { recursive: true, force: true }));
  return async () => {
    const flattener = new Flattener(new ScenarioStore({ root: folder, scenarioPath: [] }), 'esmini', { version: 'auto' });
    const result = await flattener.flatten(diskRef(file), { outputPath: path.join(folder, 'out', 'flat.xosc') });
    const errors = result.problems.filter((problem) => problem.severity === 'error');
    if (errors.length > 0 || result.text === undefined)
      throw new Error(`not flattened: ${errors.map((problem) => problem.message).join('; ')}`);
  };
}

async function build(kind: string, size: number): Promise<Operation> {
  switch (kind) {
    case 'attributes': {
      const text = '<r ' + Array.from({ length: size }, (_, i) => `a${i}="${i}"`).join(' ') + ' a0="again"/>';
      return () => {
        if (!parseXml(text).problems.some((problem) => /appears twice/.test(problem.message)))
          throw new Error('the duplicate was not found');
      };
    }
    case 'end-tags': {
      // End tags that match nothing, under a deep stack of open elements.
      const text = '<r>' + '<a>'.repeat(1999) + '</zz>'.repeat(size) + '</a>'.repeat(1999) + '</r>';
      return () => void parseXml(text);
    }
    case 'nested-packages':
      return nestedPackages(size);
    case 'sibling-files':
      return siblingFiles(size);
    default:
      throw new Error(`unknown kind ${kind}`);
  }
}

/**
 * Every check of a document alone, in CPU milliseconds, best of three rounds, each on fresh parses and
 * in the order a check of the file runs them (a check runs once per analysis, so each is timed once a
 * round, its caches cold): the model and catalogs, each of SEMANTIC_CHECKS and OUTPUT_CHECKS, the
 * simulator profiles, the schema and the parameters' values against it. (The flatten of a file as a
 * whole is the `sibling-files` kind's.)
 */
async function checkTimes(size: number): Promise<Record<string, number>> {
  const folder = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-scaling-'));
  try {
    for (const [name, text] of Object.entries(checkScalingFiles(size))) {
      fs.mkdirSync(path.dirname(path.join(folder, name)), { recursive: true });
      fs.writeFileSync(path.join(folder, name), text);
    }
    const main = path.join(folder, 'main.xosc');
    const text = fs.readFileSync(main, 'utf8');
    const analyze = () =>
      analyzeDocument(
        diskRef(main),
        parseXml(text),
        new CatalogLoader(new ScenarioStore({ root: folder, scenarioPath: [] })),
        false,
        'esmini',
      );
    const best: Record<string, number> = {};
    const time = async <T>(name: string, operation: () => T | Promise<T>): Promise<T> => {
      // The garbage of the operations before is not this one's to collect (node runs this with --expose-gc).
      globalThis.gc?.();
      const started = process.cpuUsage();
      const result = await operation();
      best[name] = Math.min(best[name] ?? Infinity, cpuMsSince(started));
      return result;
    };
    for (let round = 0; round < 3; round++) {
      const context = await time('parse, semantic model and catalogs', analyze);
      if (context.catalogs.references.filter((reference) => reference.entry).length !== size)
        throw new Error('the catalog entries did not resolve');
      if (!context.road) throw new Error('the road file was not read');
      for (const { name, check } of SEMANTIC_CHECKS) await time(name, () => check(context));
      await time('simulator profile (carla)', () => simulatorProfile({ ...context, simulator: 'carla' }));
      // A flattened output is a parse of its own (here of the same text: the file imports nothing).
      const output = await analyze();
      for (const { name, check } of OUTPUT_CHECKS) await time(`output: ${name}`, () => check(output));
      const schema = await time('schema', () => checkSchema(context.model.document, { version: 'auto', modular: false }));
      if (schema.findings.some((finding) => finding.severity === 'error'))
        throw new Error(
          `not schema-valid: ${[...new Set(schema.findings.map((finding) => schemaFindingWords(finding).message))].slice(0, 5).join('; ')}`,
        );
      await time('parameter values against the schema', () => parameterValueProblems(context, 'auto'));
    }
    return best;
  } finally {
    fs.rmSync(folder, { recursive: true, force: true });
  }
}

async function main(): Promise<void> {
  const [kind, sizeText] = process.argv.slice(2);
  if (kind === 'checks') {
    process.stdout.write(`${JSON.stringify(await checkTimes(Number(sizeText)))}\n`);
    return;
  }
  const operation = await build(kind, Number(sizeText));
  let best = Infinity;
  for (let run = 0; run < 3; run++) {
    const started = process.cpuUsage();
    await operation();
    best = Math.min(best, cpuMsSince(started));
  }
  process.stdout.write(`${best}\n`);
}

main().catch((error) => {
  process.stderr.write(`${(error as Error).stack}\n`);
  process.exit(1);
});

// The refactorings' code action lists (issue 19) on 15,000-line files, over stdio against dist/server.js:
// Extract to a simple scenario on a group's start tag of a plain scenario, Extract to catalog on a
// Maneuver of it, Make overridable on an
// attribute of a simple scenario, Inline on a referencing group of a main. Figures, not a timed test.
import { existsSync, mkdtempSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { now, startServer, uriOf } from './lspSession.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const server = path.join(root, 'dist', 'server.js');
const samples = Number(process.env.BENCH_SAMPLES ?? 100);
const target = 50;
if (!existsSync(server)) {
  console.error('dist/server.js is missing: run npm run build first');
  process.exit(1);
}

/**
 * @param {number} index
 * @param {boolean} listed
 */
function group(index, listed) {
  /** @param {string} names */
  const list = (names) => (listed ? ` parameterAttributes="${names}"` : '');
  return `        <ManeuverGroup name="G${index}" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="car${index % 20}"/>
          </Actors>
          <Maneuver name="M${index}">
            <Event name="E${index}" priority="overwrite">
              <Action name="Speed${index}">
                <PrivateAction>
                  <LongitudinalAction>
                    <SpeedAction>
                      <SpeedActionDynamics dynamicsShape="step" value="${index % 5}" dynamicsDimension="time"/>
                      <SpeedActionTarget>
                        <AbsoluteTargetSpeed${list('value')} value="${index % 30}"/>
                      </SpeedActionTarget>
                    </SpeedAction>
                  </LongitudinalAction>
                </PrivateAction>
              </Action>
              <StartTrigger>
                <ConditionGroup>
                  <Condition name="Start${index}" delay="0" conditionEdge="rising">
                    <ByValueCondition>
                      <SimulationTimeCondition${list('value')} value="${index % 9}" rule="greaterThan"/>
                    </ByValueCondition>
                  </Condition>
                </ConditionGroup>
              </StartTrigger>
            </Event>
          </Maneuver>
        </ManeuverGroup>`;
}

/** @param {number} index */
function referenceGroup(index) {
  return `        <ManeuverGroup name="Car${index}" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="car${index % 20}"/>
          </Actors>
          <ScenarioReference scenarioFileName="simple.xosc">
            <ManeuverGroupReference maneuverGroupName="G${index % 10}">
              <ParameterReference key="AbsoluteTargetSpeed.value" value="${index % 40}"/>
            </ManeuverGroupReference>
          </ScenarioReference>
        </ManeuverGroup>`;
}

/**
 * @param {(index: number) => string} groups
 * @param {number} lines
 */
function scenario(groups, lines) {
  const entities = Array.from({ length: 20 }, (_, i) => `    <ScenarioObject name="car${i}"/>`).join('\n');
  const head = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="bench" author="bench"/>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
${entities}
  </Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S">
      <Act name="A">
`;
  const tail = `
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
  const body = [];
  let count = head.split('\n').length + tail.split('\n').length;
  for (let i = 0; count < lines; i++) {
    const text = groups(i);
    body.push(text);
    count += text.split('\n').length;
  }
  return head + body.join('\n') + tail;
}

/**
 * @param {string} text
 * @param {number} offset
 */
function positionOf(text, offset) {
  const before = text.slice(0, offset);
  return { line: before.split('\n').length - 1, character: offset - (before.lastIndexOf('\n') + 1) };
}

/**
 * Offsets of every occurrence of `needle`, `into` characters in.
 * @param {string} text
 * @param {string} needle
 * @param {number} into
 */
function offsets(text, needle, into) {
  const found = [];
  for (let index = text.indexOf(needle); index >= 0; index = text.indexOf(needle, index + 1)) found.push(index + into);
  return found;
}

const folder = realpathSync(mkdtempSync(path.join(tmpdir(), 'm2s-refactor-bench-')));
/** @type {Record<string, string>} */
const files = {
  'plain.xosc': scenario((i) => group(i, false), 15_000),
  'simple.xosc': scenario((i) => group(i, true), 15_000),
  'main.xosc': scenario(referenceGroup, 15_000),
};
for (const [name, text] of Object.entries(files)) writeFileSync(path.join(folder, name), text);

// As the editor starts it (its node flags), with the workspace edits a refactoring answers with.
const session = await startServer(server, folder, {}, { workspaceEdit: { documentChanges: true, resourceOperations: ['create'] } });
const connection = session.connection;

/** @param {string} name */
async function open(name) {
  const uri = uriOf(path.join(folder, name));
  const diagnosed = session.diagnosticsFor(uri, 1);
  await connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'xml', version: 1, text: files[name] } });
  await diagnosed;
  return uri;
}

/**
 * @param {string} name
 * @param {string} needle
 * @param {number} into
 * @param {string[] | undefined} only
 * @param {string} kind
 */
async function actionLatency(name, needle, into, only, kind) {
  const uri = await open(name);
  const text = files[name];
  const places = offsets(text, needle, into);
  const times = [];
  let offered = 0;
  for (let i = 0; i < samples; i++) {
    const position = positionOf(text, places[(i * 37) % places.length]);
    const started = now();
    /** @type {import('vscode-languageserver-protocol').CodeAction[]} */
    const actions = await connection.sendRequest('textDocument/codeAction', {
      textDocument: { uri },
      range: { start: position, end: position },
      context: { diagnostics: [], only },
    });
    times.push(now() - started);
    if (actions.some((action) => action.kind === kind && !action.disabled)) offered++;
  }
  times.sort((a, b) => a - b);
  const median = times[Math.floor(times.length / 2)];
  const p95 = times[Math.min(times.length - 1, Math.ceil(times.length * 0.95) - 1)];
  const lines = text.split('\n').length - 1;
  // The light bulb's request (no `only`) is told from the request for one kind, though it looks for the same action.
  const label = only ? `${kind} (${lines} lines)` : `light bulb, every kind (${lines} lines)`;
  console.log(
    `  ${label.padEnd(52)}${median.toFixed(1).padStart(8)} ${p95.toFixed(1).padStart(8)}   ${p95 <= target ? 'within' : 'OVER'} ${target} ms p95  (offered ${offered}/${samples})`,
  );
}

console.log(`refactoring code action lists (${samples} samples each; dist/server.js over stdio)`);
console.log(`  ${''.padEnd(52)}  median      p95`);
try {
  await actionLatency('plain.xosc', '<ManeuverGroup name="G', 3, ['refactor.extract'], 'refactor.extract.simpleScenario');
  await actionLatency('plain.xosc', '<Maneuver name="M', 3, ['refactor.extract'], 'refactor.extract.catalog');
  await actionLatency('simple.xosc', 'dynamicsShape="step"', 2, ['refactor.rewrite'], 'refactor.rewrite.makeOverridable');
  await actionLatency('main.xosc', '<ManeuverGroup name="Car', 3, ['refactor.inline'], 'refactor.inline.scenarioReference');
  // Every kind at once, as an editor asks when the light bulb shows.
  await actionLatency('plain.xosc', '<ManeuverGroup name="G', 3, undefined, 'refactor.extract.simpleScenario');
} finally {
  await session.stop();
  rmSync(folder, { recursive: true, force: true });
}

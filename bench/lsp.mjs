// Language server benchmark (figures, not a timed test): drives the built dist/server.js over stdio
// on the largest corpus scenario, on a generated workspace of 1,000 scenario files and on a
// generated 15,000-line main file. Run `npm run build` first.
import { cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { previewLatency } from './previewLatency.mjs';
import { cpuMs, now, residentMb, startServer, stats, uriOf } from './lspSession.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
// BENCH_SERVER: another build's server.js, to measure two builds side by side in the same minutes.
const server = process.env.BENCH_SERVER ?? path.join(root, 'dist', 'server.js');
const library = path.resolve(root, '..', 'shared', 'corpus', 'modular2simple', 'library');
const samples = Number(process.env.BENCH_SAMPLES ?? 100);
/**
 * @param {string} folder
 * @param {Record<string, unknown>} [settings]
 */
const start = (folder, settings = {}) => startServer(server, folder, settings);
// BENCH_NODE_ARGS are given to the server's node (e.g. --require of a probe); BENCH_LSP_EDITS_ONLY=1 stops after part 1;
// BENCH_TIMES=1 prints each edit's time in order.

if (!existsSync(server)) {
  console.error('dist/server.js is missing: run npm run build first');
  process.exit(1);
}

/**
 * @param {import('vscode-languageserver-protocol').ProtocolConnection} connection
 * @param {string} method
 * @param {object[]} paramsList
 */
async function timeRequests(connection, method, paramsList) {
  const times = [];
  let last;
  for (let i = 0; i < samples; i++) {
    const params = paramsList[i % paramsList.length];
    const started = now();
    last = await connection.sendRequest(method, params);
    times.push(now() - started);
  }
  return { ...stats(times), last };
}

/**
 * @param {string} text
 * @param {string} needle
 * @param {number} [nth]
 */
function positionAfter(text, needle, nth = 0) {
  let index = -1;
  for (let i = 0; i <= nth; i++) index = text.indexOf(needle, index + 1);
  if (index < 0) throw new Error(`${needle} not found`);
  const before = text.slice(0, index + needle.length);
  const line = before.split('\n').length - 1;
  return { line, character: before.length - (before.lastIndexOf('\n') + 1) };
}

// ---- generated scenarios --------------------------------------------------------------------

// Schema-valid (OpenSCENARIO 1.0), as the schema check runs by default and blocks a preview on errors.
const vehicle =
  '<Vehicle name="v" vehicleCategory="car"><BoundingBox><Center x="1.4" y="0" z="0.9"/><Dimensions width="2" length="5" height="1.8"/></BoundingBox>' +
  '<Performance maxSpeed="69" maxAcceleration="10" maxDeceleration="10"/><Axles>' +
  '<FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.7" positionX="2.9" positionZ="0.4"/>' +
  '<RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.7" positionX="0" positionZ="0.4"/></Axles><Properties/></Vehicle>';

/** @param {number} index */
function simpleScenario(index) {
  const groups = [0, 1, 2]
    .map(
      (group) => `        <ManeuverGroup name="G${group}" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef parameterAttributes="entityRef" entityRef="ego"/>
          </Actors>
          <Maneuver name="M${group}">
            <Event name="E${group}" priority="overwrite">
              <Action name="Speed">
                <PrivateAction><LongitudinalAction><SpeedAction>
                  <SpeedActionDynamics parameterAttributes="value" dynamicsShape="step" value="${group}" dynamicsDimension="time"/>
                  <SpeedActionTarget><AbsoluteTargetSpeed parameterAttributes="value" value="${index % 30}"/></SpeedActionTarget>
                </SpeedAction></LongitudinalAction></PrivateAction>
              </Action>
              <StartTrigger><ConditionGroup>
                <Condition parameterAttributes="delay" name="Start" delay="0" conditionEdge="rising">
                  <ByValueCondition><SimulationTimeCondition parameterAttributes="value" value="${group + 1}" rule="greaterThan"/></ByValueCondition>
                </Condition>
              </ConditionGroup></StartTrigger>
            </Event>
          </Maneuver>
        </ManeuverGroup>`,
    )
    .join('\n');
  return `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="simple ${index}" author="bench"/>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities><ScenarioObject name="ego">${vehicle}</ScenarioObject></Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S">
      <Act name="A">
${groups}
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
}

/**
 * @param {number} index
 * @param {number} simpleCount
 */
function referenceGroup(index, simpleCount) {
  return `        <ManeuverGroup name="Car${index}" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="car${index % 50}"/>
          </Actors>
          <ScenarioReference scenarioFileName="simple_${index % simpleCount}.xosc">
            <ManeuverGroupReference maneuverGroupName="G${index % 3}">
              <ParameterReference key="AbsoluteTargetSpeed.value" value="${index % 40}"/>
              <ParameterReference key="delay" value="${index % 7}"/>
              <ParameterReference key="entityRef" value="car${index % 50}"/>
            </ManeuverGroupReference>
          </ScenarioReference>
        </ManeuverGroup>`;
}

/**
 * @param {number} references
 * @param {number} simpleCount
 * @param {number} [padLines]
 */
function mainScenario(references, simpleCount, padLines = 0) {
  const entities = Array.from({ length: 50 }, (_, i) => `    <ScenarioObject name="car${i}">${vehicle}</ScenarioObject>`).join('\n');
  // Plain OpenSCENARIO content (Init actions) pads a file to a realistic size without references.
  const padding = Array.from(
    { length: Math.ceil(padLines / 3) },
    (_, i) =>
      `      <Private entityRef="car${i % 50}">\n        <PrivateAction><TeleportAction><Position><WorldPosition x="${i}" y="${i % 9}" z="0" h="0"/></Position></TeleportAction></PrivateAction>\n      </Private>`,
  ).join('\n');
  const groups = Array.from({ length: references }, (_, i) => referenceGroup(i, simpleCount)).join('\n');
  return `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="main" author="bench"/>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
${entities}
  </Entities>
  <Storyboard>
    <Init><Actions>
${padding}
    </Actions></Init>
    <Story name="Main">
      <Act name="Act">
${groups}
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
}

/** @param {number} n */
const fmt = (n) => n.toFixed(1).padStart(8);
/**
 * @param {string} label
 * @param {string} value
 */
const line = (label, value) => console.log(`  ${label.padEnd(52)}${value}`);
/**
 * @param {string} label
 * @param {{ median: number, p95: number }} figures
 * @param {number} target
 */
const row = (label, { median, p95 }, target) =>
  line(label, `${fmt(median)} ${fmt(p95)}   ${p95 <= target ? 'within' : 'OVER'} ${target} ms p95`);

console.log(`language server benchmark (${samples} samples per latency; node ${process.version}; dist/server.js over stdio)`);
console.log(`  ${''.padEnd(52)}  median      p95`);

// ---- 1. a generated workspace of 1,000 files with a 15,000-line main file -----------------------

const workspace = realpathSync(mkdtempSync(path.join(tmpdir(), 'm2s-lsp-bench-')));
const simpleCount = 400;
for (let i = 0; i < simpleCount; i++) writeFileSync(path.join(workspace, `simple_${i}.xosc`), simpleScenario(i));
mkdirSync(path.join(workspace, 'mains'));
for (let i = 0; i < 1000 - simpleCount - 1; i++)
  writeFileSync(path.join(workspace, 'mains', `main_${i}.xosc`), mainScenario(4, simpleCount).replace(/simple_/g, '../simple_'));
let bigMain = mainScenario(400, simpleCount);
const padLines = 15_000 - bigMain.split('\n').length;
bigMain = mainScenario(400, simpleCount, padLines);
const bigPath = path.join(workspace, 'big_main.xosc');
writeFileSync(bigPath, bigMain);
const bigLines = bigMain.split('\n').length - 1;

const session = await start(workspace);
line('index 1,000 files (start to $/progress end)', `${fmt(session.indexMs)} ms   ${session.indexMs <= 2000 ? 'within' : 'OVER'} 2000 ms`);

const indexMemory = residentMb(session.child.pid);
line('server resident memory, 1,000 files indexed', `${fmt(indexMemory.rss)} MB   ${indexMemory.rss <= 150 ? 'within' : 'OVER'} 150 MB`);

/**
 * Opens a file, then changes one override value at a time (as typing does) and waits for its diagnostics.
 * @param {string} filePath
 * @param {string} text
 * @param {string} label
 */
async function editLatency(filePath, text, label) {
  const uri = uriOf(filePath);
  let version = 1;
  let started = now();
  let pending = session.diagnosticsFor(uri, version);
  await session.connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'xml', version, text } });
  const first = await pending;
  line(`open ${label} to diagnostics`, `${fmt(now() - started)} ms   (${first.length} diagnostics)`);
  const references = text.split('key="AbsoluteTargetSpeed.value" value="').length - 1;
  const times = [];
  const edits = Math.min(samples, Number(process.env.BENCH_EDITS ?? 60));
  const cpuBefore = cpuMs(session.child.pid);
  for (let i = 0; i < edits; i++) {
    const position = positionAfter(text, 'key="AbsoluteTargetSpeed.value" value="', (i * 37) % references);
    version++;
    pending = session.diagnosticsFor(uri, version);
    started = now();
    await session.connection.sendNotification('textDocument/didChange', {
      textDocument: { uri, version },
      contentChanges: [
        { range: { start: position, end: { line: position.line, character: position.character + 1 } }, text: String(i % 10) },
      ],
    });
    await pending;
    times.push(now() - started);
  }
  const cpuPerEdit = (cpuMs(session.child.pid) - cpuBefore) / edits;
  row(`edit -> diagnostics, ${label}`, stats(times), 30);
  line('  server CPU per edit (user + system, 10 ms ticks)', `${fmt(cpuPerEdit)} ms`);
  if (process.env.BENCH_TIMES) console.log(times.map((t) => t.toFixed(0)).join(' '));
  return { uri, version };
}

// The same 15,000 lines with a tenth of the references: most of a large main file is plain OpenSCENARIO.
let fewReferences = mainScenario(40, simpleCount);
fewReferences = mainScenario(40, simpleCount, 15_000 - fewReferences.split('\n').length);
const fewPath = path.join(workspace, 'big_main_40.xosc');
writeFileSync(fewPath, fewReferences);
const { uri: fewUri } = await editLatency(fewPath, fewReferences, `${fewReferences.split('\n').length - 1} lines, 40 references`);
await session.connection.sendNotification('textDocument/didClose', { textDocument: { uri: fewUri } });
const { uri: bigUri, version: bigVersion } = await editLatency(bigPath, bigMain, `${bigLines} lines, 400 references`);
const bigPreview = await previewLatency(session.connection, bigUri, bigMain, 'key="AbsoluteTargetSpeed.value" value="', {
  samples: Math.min(samples, 40),
  version: bigVersion,
});
row(`edit -> preview text and line map, ${bigLines} lines`, stats(bigPreview.times), 300);

const completionPositions = Array.from({ length: 20 }, (_, i) => ({
  textDocument: { uri: bigUri },
  position: positionAfter(bigMain, 'key="', (i * 61) % 1200),
}));
const completion = await timeRequests(session.connection, 'textDocument/completion', completionPositions);
row(`completion of keys, ${bigLines} lines`, completion, 20);
const definitionPositions = Array.from({ length: 20 }, (_, i) => ({
  textDocument: { uri: bigUri },
  position: positionAfter(bigMain, 'maneuverGroupName="G', (i * 19) % 400),
}));
const definition = await timeRequests(session.connection, 'textDocument/definition', definitionPositions);
row(`definition of maneuverGroupName, ${bigLines} lines`, definition, 20);
const hover = await timeRequests(
  session.connection,
  'textDocument/hover',
  completionPositions.map((params) => ({ ...params, position: { ...params.position, character: params.position.character + 3 } })),
);
row(`hover on keys, ${bigLines} lines`, hover, 20);
const busy = residentMb(session.child.pid);
line('server resident memory right after the requests', `${fmt(busy.rss)} MB`);
// The server collects garbage (compacting) once the editor has been quiet for 1.5 s; memory at rest is what stays.
await new Promise((resolve) => setTimeout(resolve, 2500));
const memory = residentMb(session.child.pid);
line(
  '  after the 15,000-line edits, at rest (now / peak)',
  `${fmt(memory.rss)} MB ${fmt(memory.peak)} MB   ${memory.rss <= 200 && memory.peak <= 300 ? 'within' : 'OVER'} 200 / 300 MB`,
);
await session.stop();
rmSync(workspace, { recursive: true, force: true });
if (process.env.BENCH_LSP_EDITS_ONLY === '1') process.exit(0);

// ---- 2. the bundled examples: edit to preview ------------------------------------------------------

{
  const examples = realpathSync(mkdtempSync(path.join(tmpdir(), 'm2s-preview-bench-')));
  cpSync(path.join(root, 'examples'), examples, { recursive: true });
  const session = await start(examples);
  const mainPath = path.join(examples, 'main.xosc');
  const text = readFileSync(mainPath, 'utf8');
  const uri = uriOf(mainPath);
  const opened = session.diagnosticsFor(uri, 1);
  await session.connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'xosc', version: 1, text } });
  await opened;
  const preview = await previewLatency(session.connection, uri, text, '.value" value="', { samples, version: 1 });
  row('edit -> preview text and line map, examples/main.xosc', stats(preview.times), 100);
  await session.stop();
  rmSync(examples, { recursive: true, force: true });
}

// ---- 3. the largest corpus scenario --------------------------------------------------------------

if (!existsSync(library)) {
  console.log(`  (corpus part skipped: ${library} is absent)`);
} else {
  const largest = path.join(library, 'modular_hero_right_left_front_back_pedestrian', 'main.xosc');
  const text = readFileSync(largest, 'utf8');
  const corpus = await start(library, { scenarioPath: [library] });
  line(`index the library (${path.basename(library)}/, 95 files)`, `${fmt(corpus.indexMs)} ms`);
  const uri = uriOf(largest);
  let started = now();
  let pending = corpus.diagnosticsFor(uri, 1);
  await corpus.connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'xml', version: 1, text } });
  await pending;
  line(`open largest corpus main (${text.split('\n').length} lines) to diagnostics`, `${fmt(now() - started)} ms`);
  const edits = [];
  for (let i = 0; i < Math.min(samples, 60); i++) {
    const position = positionAfter(text, 'value="', i % 20);
    pending = corpus.diagnosticsFor(uri, i + 2);
    started = now();
    await corpus.connection.sendNotification('textDocument/didChange', {
      textDocument: { uri, version: i + 2 },
      contentChanges: [{ range: { start: position, end: position }, text: '' }],
    });
    await pending;
    edits.push(now() - started);
  }
  row('edit -> diagnostics, largest corpus main', stats(edits), 50);
  const keys = Array.from({ length: 10 }, (_, i) => ({ textDocument: { uri }, position: positionAfter(text, 'key="', i) }));
  row('completion of keys, largest corpus main', await timeRequests(corpus.connection, 'textDocument/completion', keys), 20);
  const groups = Array.from({ length: 5 }, (_, i) => ({ textDocument: { uri }, position: positionAfter(text, 'maneuverGroupName="', i) }));
  row('definition of maneuverGroupName, largest corpus main', await timeRequests(corpus.connection, 'textDocument/definition', groups), 20);
  const corpusMemory = residentMb(corpus.child.pid);
  line(
    'server resident memory, largest corpus main (now / peak)',
    `${fmt(corpusMemory.rss)} MB ${fmt(corpusMemory.peak)} MB   ${corpusMemory.peak <= 150 ? 'within' : 'OVER'} 150 MB`,
  );
  await corpus.stop();
}

// ---- 3. OpenSCENARIO schema: validation after an edit, completion, four schemas in memory ----------

/**
 * A schema-valid scenario of about `lines` lines: Init actions of one entity, each a speed change.
 * @param {string} minor
 * @param {number} lines
 */
function schemaScenario(minor, lines) {
  const head = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="${minor}" date="2024-01-01T00:00:00" description="schema benchmark" author="bench"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="Speed" parameterType="double" value="10"/>
  </ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="ego">
      <CatalogReference catalogName="VehicleCatalog" entryName="car"/>
    </ScenarioObject>
  </Entities>
  <Storyboard>
    <Init>
      <Actions>
`;
  /** @param {number} i */
  const action = (i) => `        <Private entityRef="ego">
          <PrivateAction>
            <LongitudinalAction>
              <SpeedAction>
                <SpeedActionDynamics dynamicsShape="step" value="$Speed" dynamicsDimension="time"/>
                <SpeedActionTarget>
                  <AbsoluteTargetSpeed value="${i % 50}"/>
                </SpeedActionTarget>
              </SpeedAction>
            </LongitudinalAction>
          </PrivateAction>
        </Private>
`;
  const tail = `      </Actions>
    </Init>
    <Story name="story">
      <Act name="act">
        <ManeuverGroup maximumExecutionCount="1" name="group">
          <Actors selectTriggeringEntities="false"/>
        </ManeuverGroup>
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
  const count = Math.max(1, Math.floor((lines - 30) / 12));
  return head + Array.from({ length: count }, (_, i) => action(i)).join('') + tail;
}

{
  const folder = realpathSync(mkdtempSync(path.join(tmpdir(), 'm2s-schema-bench-')));
  const schemaSession = await start(folder);
  const memoryBefore = residentMb(schemaSession.child.pid);
  // One small file per version, each asked for a completion: all four schemas are loaded.
  for (const minor of ['0', '1', '2', '3']) {
    const text = schemaScenario(minor, 40);
    const file = path.join(folder, `v1_${minor}.xosc`);
    writeFileSync(file, text);
    const pending = schemaSession.diagnosticsFor(uriOf(file), 1);
    await schemaSession.connection.sendNotification('textDocument/didOpen', {
      textDocument: { uri: uriOf(file), languageId: 'xosc', version: 1, text },
    });
    const diagnostics = await pending;
    if (diagnostics.length > 0) throw new Error(`the 1.${minor} scenario is not schema-valid: ${diagnostics[0].message}`);
    await schemaSession.connection.sendRequest('textDocument/completion', {
      textDocument: { uri: uriOf(file) },
      position: positionAfter(text, '<Actions>'),
    });
  }
  const big = schemaScenario('2', 15_000);
  const bigFile = path.join(folder, 'big_schema.xosc');
  writeFileSync(bigFile, big);
  const uri = uriOf(bigFile);
  let version = 1;
  let started = now();
  let pending = schemaSession.diagnosticsFor(uri, version);
  await schemaSession.connection.sendNotification('textDocument/didOpen', {
    textDocument: { uri, languageId: 'xosc', version, text: big },
  });
  const opened = await pending;
  const bigLineCount = big.split('\n').length - 1;
  line(`open a schema-valid ${bigLineCount}-line 1.2 file to diagnostics`, `${fmt(now() - started)} ms   (${opened.length} diagnostics)`);
  const actions = big.split('<AbsoluteTargetSpeed value="').length - 1;
  const times = [];
  for (let i = 0; i < Math.min(samples, 60); i++) {
    const position = positionAfter(big, '<AbsoluteTargetSpeed value="', (i * 37) % actions);
    version++;
    pending = schemaSession.diagnosticsFor(uri, version);
    started = now();
    // Every other edit makes the value invalid, so the schema check both finds and clears a problem.
    await schemaSession.connection.sendNotification('textDocument/didChange', {
      textDocument: { uri, version },
      contentChanges: [
        { range: { start: position, end: { line: position.line, character: position.character + 1 } }, text: i % 2 ? 'x' : String(i % 10) },
      ],
    });
    await pending;
    times.push(now() - started);
  }
  row(`edit -> schema diagnostics, ${bigLineCount} lines`, stats(times), 50);
  const childPositions = Array.from({ length: 20 }, (_, i) => ({
    textDocument: { uri },
    position: positionAfter(big, '<SpeedAction>', (i * 53) % actions),
  }));
  row(
    `schema completion of child elements, ${bigLineCount} lines`,
    await timeRequests(schemaSession.connection, 'textDocument/completion', childPositions),
    20,
  );
  const valuePositions = Array.from({ length: 20 }, (_, i) => ({
    textDocument: { uri },
    position: positionAfter(big, 'dynamicsShape="', (i * 53) % actions),
  }));
  row(
    `schema completion of enumeration values, ${bigLineCount} lines`,
    await timeRequests(schemaSession.connection, 'textDocument/completion', valuePositions),
    20,
  );
  await new Promise((resolve) => setTimeout(resolve, 2500));
  const schemaMemory = residentMb(schemaSession.child.pid);
  line('server memory before any file was opened', `${fmt(memoryBefore.rss)} MB`);
  line(
    'server memory, four schemas loaded, 15,000-line file (now / peak)',
    `${fmt(schemaMemory.rss)} MB ${fmt(schemaMemory.peak)} MB   ${schemaMemory.rss <= 150 ? 'within' : 'OVER'} 150 MB`,
  );
  await schemaSession.stop();
  rmSync(folder, { recursive: true, force: true });
}

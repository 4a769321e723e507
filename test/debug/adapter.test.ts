import { DebugClient } from '@vscode/debugadapter-testsupport';
import { DebugProtocol } from '@vscode/debugprotocol';
import * as assert from 'node:assert/strict';
import { ChildProcess } from 'node:child_process';
import { once } from 'node:events';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { storyboardTimeline } from '../../common/src/storyboardTimeline';
import { followStoryboard, type LiveTrace, STORYBOARD_EVENT, type StoryboardEventBody } from '../../common/src/trace';
import { DEBUG_STATE_EVENT, type DebugState } from '../../common/src/debugState';
import { esminiBinary, esminiCatalogs, esminiRoads } from '../support/esmini';
import { requireEsminiLibrary, requireEsminiProgram } from '../support/esminiBinaries';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { repoRoot } from '../support/paths';
import { runBounded } from '../support/processes';
import { temporaryFolder } from '../support/temporaryDirectory';
import {
  writeAddedEntityCrash,
  writeClearanceCrash,
  writeNestedCutIn,
  writeNestedCutInPackage,
  writeTwoCutIns,
} from '../support/debugScenarios';
import { SESSION_ARGUMENT } from '../../server/src/debug/supervisor';

const cutIn = path.join(openscenarioDir, 'esmini', 'cut-in.xosc');
const roadPath = [esminiRoads, path.join(esminiCatalogs, 'Vehicles')];
const adapterSource = path.join(repoRoot, 'server', 'src', 'debugAdapter.ts');

function lineOf(file: string, text: string): number {
  const index = fs
    .readFileSync(file, 'utf8')
    .split('\n')
    .findIndex((line) => line.includes(text));
  assert.ok(index >= 0, `${text} in ${file}`);
  return index + 1;
}

/**
 * The adapter as VS Code starts it: a process of its own speaking DAP on stdio (from the sources, through tsx), which
 * runs the session in a child (server/src/debug/supervisor.ts). `exited` settles when the adapter's process has ended.
 */
async function startClient(): Promise<{ client: DebugClient; stderr: () => string; exited: Promise<unknown>; pid: number }> {
  const client = new DebugClient(process.execPath, adapterSource, 'modular2simple', {
    env: { ...process.env, NODE_OPTIONS: `${process.env.NODE_OPTIONS ?? ''} --import=tsx`.trim() },
    stdio: ['pipe', 'pipe', 'pipe'],
  });
  client.defaultTimeout = 30_000;
  await client.start();
  let stderr = '';
  const adapter = (client as unknown as { _adapterProcess?: ChildProcess })._adapterProcess;
  assert.ok(adapter);
  // 'close', not 'exit': what the adapter wrote to stderr last may be read after its exit, and afterEach checks it.
  const exited = adapter.exitCode !== null && adapter.stderr?.closed !== false ? Promise.resolve() : once(adapter, 'close');
  // The adapter's stderr carries its logged exceptions: a test fails when there is one.
  adapter.stderr?.on('data', (chunk: Buffer) => {
    stderr += chunk.toString();
  });
  return { client, stderr: () => stderr, exited, pid: adapter.pid ?? 0 };
}

/** The session's process: the adapter's child started with SESSION_ARGUMENT (server/src/debug/supervisor.ts). */
function sessionProcess(adapter: number): number {
  const children = fs.readFileSync(`/proc/${adapter}/task/${adapter}/children`, 'utf8').trim().split(/\s+/).filter(Boolean).map(Number);
  const sessions = children.filter((pid) => fs.readFileSync(`/proc/${pid}/cmdline`, 'utf8').split('\0').includes(SESSION_ARGUMENT));
  assert.equal(sessions.length, 1, `one session process among ${children.join(', ')}`);
  return sessions[0];
}

async function variablesOf(client: DebugClient, reference: number): Promise<DebugProtocol.Variable[]> {
  return (await client.variablesRequest({ variablesReference: reference })).body.variables;
}

async function scope(client: DebugClient, name: string): Promise<DebugProtocol.Variable[]> {
  const frames = (await client.stackTraceRequest({ threadId: 1 })).body.stackFrames;
  const scopes = (await client.scopesRequest({ frameId: frames[0].id })).body.scopes;
  const found = scopes.find((candidate) => candidate.name === name);
  assert.ok(found, `scope ${name} in ${scopes.map((candidate) => candidate.name).join(', ')}`);
  return variablesOf(client, found.variablesReference);
}

async function evaluate(client: DebugClient, expression: string): Promise<string> {
  return (await client.evaluateRequest({ expression, context: 'watch' })).body.result;
}

/** esmini's own headless run of a scenario: its log and CSV (the reference the adapter is compared with). */
async function esminiReference(scenario: string): Promise<{ log: string; csv: string[][] }> {
  const folder = temporaryFolder();
  const args = ['--headless', '--osc', scenario, '--fixed_timestep', '0.05', '--seed', '1', '--csv_logger', path.join(folder, 'run.csv')];
  args.push('--logfile_path', path.join(folder, 'log.txt'));
  for (const folderOfPath of roadPath) args.push('--path', folderOfPath);
  const { code, output } = await runBounded(esminiBinary, args, { cwd: folder }, 120_000);
  assert.equal(code, 0, output.slice(-2000));
  const csv = fs
    .readFileSync(path.join(folder, 'run.csv'), 'utf8')
    .split(/\r?\n/)
    .slice(6)
    .filter((line) => line.trim())
    .map((line) => line.split(',').map((cell) => cell.trim()));
  return { log: fs.readFileSync(path.join(folder, 'log.txt'), 'utf8'), csv };
}

/** An entity's fields in esmini's CSV row at a time. */
function csvEntity(csv: string[][], time: number, entity: string): { x: number; y: number; speed: number; lane: number } {
  const header = csv[0];
  const row = csv.slice(1).find((cells) => Math.abs(Number(cells[1]) - time) < 1e-6);
  assert.ok(row, `a CSV row at ${time}`);
  const at = row.indexOf(entity);
  const offset = (column: string) => header.indexOf(`#1 ${column}`) - header.indexOf('#1 Entity_Name [-]');
  return {
    x: Number(row[at + offset('World_Position_X [m]')]),
    y: Number(row[at + offset('World_Position_Y [m]')]),
    speed: Number(row[at + offset('Current_Speed [m/s]')]),
    lane: Number(row[at + offset('lane_id')]),
  };
}

/**
 * cut-in.xosc made by `write` into a scenario esmini aborts on (RelativeLaneRange from 1 to -1), in a temporary folder:
 * esmini's own program dies on it too, after 3 s; its CSV's last row is the last step it finished, the start of the one
 * it died in.
 */
async function esminiAborts(name: string, write: (cutIn: string) => string): Promise<{ scenario: string; esminiLast: number }> {
  const folder = temporaryFolder();
  const scenario = path.join(folder, name);
  fs.writeFileSync(scenario, write(fs.readFileSync(cutIn, 'utf8')));
  const csvFile = path.join(folder, 'run.csv');
  const args = ['--headless', '--osc', scenario, '--fixed_timestep', '0.05', '--disable_log', '--csv_logger', csvFile];
  for (const folderOfPath of roadPath) args.push('--path', folderOfPath);
  const esminiRun = await runBounded(esminiBinary, args, { cwd: folder }, 120_000);
  assert.equal(esminiRun.code, null, `esmini ends by a signal, not an exit code: ${esminiRun.output.slice(-500)}`);
  assert.match(esminiRun.output, /what\(\):.*Wrong from and to value in RelativeLaneRange element/);
  const rows = fs.readFileSync(csvFile, 'utf8').trim().split('\n');
  const esminiLast = Number(rows[rows.length - 1].split(',')[1]);
  assert.ok(esminiLast > 3, `esmini died at ${esminiLast}, after 3 s`);
  return { scenario, esminiLast };
}

describe('debug adapter through the Debug Adapter Protocol', function () {
  this.timeout(180_000);
  let client: DebugClient;
  let stderr: () => string;
  let exited: Promise<unknown>;
  let adapterPid: number;
  /** What a test expects on the adapter's stderr (esmini's own last words when it crashes); nothing otherwise. */
  let expectedStderr: RegExp | undefined;
  /** The test disconnected itself and saw the adapter exit (a request to it now would wait for ever). */
  let disconnected: boolean;

  before(function () {
    requireEsminiLibrary(this);
    requireEsminiProgram(this, 'esmini');
    if (!fs.existsSync(cutIn)) {
      console.log(`    (skipped: ${cutIn} is absent)`);
      this.skip();
    }
  });

  /** Ends the configuration of a launched session and waits for its first stop, on a breakpoint; returns its stack. */
  async function firstStop(launched: Promise<unknown>): Promise<DebugProtocol.StackFrame[]> {
    const stop = client.waitForEvent('stopped');
    await client.configurationDoneRequest();
    await launched;
    assert.equal(((await stop) as DebugProtocol.StoppedEvent).body.reason, 'breakpoint');
    return (await client.stackTraceRequest({ threadId: 1 })).body.stackFrames;
  }

  beforeEach(async () => {
    expectedStderr = undefined;
    disconnected = false;
    ({ client, stderr, exited, pid: adapterPid } = await startClient());
  });

  afterEach(async () => {
    if (!disconnected) await client.stop();
    // Its temporary files go with it: the run's check of the temporary folder counts what is left.
    await exited;
    if (expectedStderr) assert.match(stderr(), expectedStderr);
    else assert.equal(stderr(), '', 'the adapter logged an exception');
  });

  /** A session of `scenario` run from its launch until the adapter says terminated: its output events. */
  async function runToTheEnd(scenario: string): Promise<DebugProtocol.OutputEvent[]> {
    const outputs: DebugProtocol.OutputEvent[] = [];
    client.on('output', (event: DebugProtocol.OutputEvent) => outputs.push(event));
    const terminated = client.waitForEvent('terminated');
    const launched = client.launch({ type: 'modular2simple', request: 'launch', program: scenario, roadPath });
    await client.waitForEvent('initialized');
    await client.configurationDoneRequest();
    await launched;
    await terminated;
    return outputs;
  }

  it("stops on an Event of cut-in.xosc when esmini's log starts it, with the entities of esmini's CSV; step over; continue to the end", async () => {
    const reference = await esminiReference(cutIn);
    const started = /^\[([\d.]+)\] \[info\] CutInEvent standbyState -> startTransition -> runningState/m.exec(reference.log);
    assert.ok(started, "esmini's log starts CutInEvent");
    const esminiTime = Number(started[1]);
    const eventLine = lineOf(cutIn, '<Event name="CutInEvent"');

    // The bird's-eye view's feed: the state the adapter publishes with each stop (common/src/debugState.ts).
    const states: DebugState[] = [];
    client.on(DEBUG_STATE_EVENT, (event: DebugProtocol.Event) => states.push(event.body as DebugState));
    const outputs: string[] = [];
    client.on('output', (event: DebugProtocol.OutputEvent) => outputs.push(event.body.output));
    await client.hitBreakpoint({ type: 'modular2simple', request: 'launch', program: cutIn, roadPath }, { path: cutIn, line: eventLine });
    const frames = (await client.stackTraceRequest({ threadId: 1 })).body.stackFrames;
    assert.equal(frames[0].name, 'Event CutInEvent (running)');
    assert.equal(frames[0].line, eventLine);
    assert.deepEqual(
      frames.slice(1, 5).map((frame) => frame.name),
      ['Maneuver CutInManeuver', 'ManeuverGroup CutInAndBrakeSequence', 'Act CutInAndBrakeAct', 'Story CutInAndBrakeStory'],
    );
    // The stop is at the time esmini's log starts the event, not one step later: esmini weighs the trigger and starts the
    // event at a step's start, then moves the entities on (Simulation.holdStepStart).
    const time = Number(await evaluate(client, 'time'));
    assert.ok(esminiTime > 0.05 && Math.abs(time - esminiTime) < 1e-6, `stopped at ${time}, esmini's log starts it at ${esminiTime}`);

    const published = states[states.length - 1];
    assert.ok(published?.paused, 'a state published with the stop');
    assert.ok(Math.abs(published.time - time) < 1e-6, `published at ${published.time}, stopped at ${time}`);
    assert.ok(
      published.running.some(
        (element) => element.name === 'CutInEvent' && element.type === 'Event' && Math.abs(element.since - esminiTime) < 1e-6,
      ),
      JSON.stringify(published.running),
    );
    const entities = await scope(client, 'Entities');
    for (const name of ['Ego', 'OverTaker']) {
      const entity = entities.find((variable) => variable.name === name);
      assert.ok(entity, `${name} in Entities`);
      const fields = Object.fromEntries(
        (await variablesOf(client, entity.variablesReference)).map((field) => [field.name, Number(field.value)]),
      );
      const expected = csvEntity(reference.csv, time, name);
      assert.ok(Math.abs(fields.x - expected.x) < 1e-3, `${name}.x ${fields.x} vs CSV ${expected.x}`);
      assert.ok(Math.abs(fields.y - expected.y) < 1e-3, `${name}.y ${fields.y} vs CSV ${expected.y}`);
      assert.ok(Math.abs(fields.speed - expected.speed) < 1e-3, `${name}.speed ${fields.speed} vs CSV ${expected.speed}`);
      assert.equal(fields.lane, expected.lane);
      for (const field of ['h', 'road', 's', 't', 'acceleration']) assert.ok(Number.isFinite(fields[field]), `${name}.${field}`);
      const drawn = published.entities.find((candidate) => candidate.name === name);
      assert.ok(
        drawn && Math.abs(drawn.x - expected.x) < 1e-3 && Math.abs(drawn.y - expected.y) < 1e-3,
        `${name} published at its CSV place`,
      );
      assert.ok(drawn.length > 0 && drawn.width > 0, `${name}'s box`);
    }
    // Why it fired: the condition that started the event, with esmini's measure and the threshold.
    const why = await scope(client, 'Why it fired');
    assert.equal(why[0].name, 'CutInStartCondition');
    assert.equal(why[0].value, 'HWT: 0.41 > 0.4');
    const details = Object.fromEntries((await variablesOf(client, why[0].variablesReference)).map((field) => [field.name, field.value]));
    assert.equal(details.type, 'TimeHeadwayCondition');
    assert.equal(details.rule, 'greaterThan');
    assert.equal(details.threshold, '0.4');
    assert.match(details.measured, /^0\.41/);
    assert.equal(await evaluate(client, '$EgoSpeed'), '108');
    assert.equal(await evaluate(client, 'Ego.speed > 20'), 'true');
    const pairs = await scope(client, 'Gaps and TTC');
    assert.ok(
      pairs.some((pair) => pair.name === 'Ego → OverTaker' && /^gap -?\d/.test(pair.value)),
      JSON.stringify(pairs),
    );

    // Step over: to the next storyboard transition, the brake event esmini starts at 8.00 s.
    const brake = /^\[([\d.]+)\] \[info\] OvertakerBrakeEvent standbyState -> startTransition -> runningState/m.exec(reference.log);
    assert.ok(brake);
    await Promise.all([client.nextRequest({ threadId: 1 }), client.waitForEvent('stopped')]);
    const brakeTime = Number(await evaluate(client, 'time'));
    assert.ok(Math.abs(brakeTime - Number(brake[1])) < 1e-6, `stepped over to ${brakeTime}, esmini's log starts the brake at ${brake[1]}`);
    const afterStep = (await client.stackTraceRequest({ threadId: 1 })).body.stackFrames;
    assert.match(afterStep[0].name, /OvertakerBrake/);
    const ego = (await scope(client, 'Entities')).find((variable) => variable.name === 'Ego');
    assert.ok(ego);
    const egoX = Number((await variablesOf(client, ego.variablesReference)).find((field) => field.name === 'x')?.value);
    assert.ok(Math.abs(egoX - csvEntity(reference.csv, brakeTime, 'Ego').x) < 1e-3, `Ego.x ${egoX} at the brake's start`);

    // One simulation step.
    const before = Number(await evaluate(client, 'time'));
    await Promise.all([client.stepInRequest({ threadId: 1 }), client.waitForEvent('stopped')]);
    assert.equal((Number(await evaluate(client, 'time')) - before).toFixed(3), '0.050');

    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);
    // Going back to a step's start reports nothing twice: one line per transition, as esmini's log has one.
    for (const name of ['CutInEvent', 'OvertakerBrakeEvent'])
      assert.equal(
        outputs.filter((output) => output.includes(`] Event ${name} running`)).length,
        1,
        `${name} started once: ${outputs.join('')}`,
      );
    const ended = /The scenario ended at ([\d.]+) s/.exec(outputs.join(''));
    const esminiEnd = Math.max(...[...reference.log.matchAll(/^\[([\d.]+)\]/gm)].map((match) => Number(match[1])));
    assert.ok(ended && Math.abs(Number(ended[1]) - esminiEnd) <= 0.05 + 1e-9, `ended at ${ended?.[1]}, esmini's log at ${esminiEnd}`);
  });

  it('stops on the simple scenario line for each flattened copy of a group a main imports twice', async () => {
    const folder = temporaryFolder();
    writeTwoCutIns(folder);
    const simple = path.join(folder, 'lane_change.xosc');
    const line = lineOf(simple, '<Event name="ChangeLane"');
    const main = path.join(folder, 'main.xosc');
    // The timeline follows the session through the adapter's storyboard events.
    const bodies: StoryboardEventBody[] = [];
    client.on(STORYBOARD_EVENT, (event: DebugProtocol.Event) => bodies.push(event.body as StoryboardEventBody));
    const launched = client.launch({ type: 'modular2simple', request: 'launch', program: main, roadPath, duration: 30 });
    await client.waitForEvent('initialized');
    const set = await client.setBreakpointsRequest({ source: { path: simple }, breakpoints: [{ line }, { line: line + 3 }] });
    assert.equal(set.body.breakpoints[0].verified, true);
    assert.match(set.body.breakpoints[0].message ?? '', /Event CutInVehicle\.CutIn::|Event ChangeLane \(2 flattened copies\)/);
    assert.equal(set.body.breakpoints[1].verified, false, 'a line with no storyboard element');
    // Each wait is armed before the request that leads to the event: the run can stop before the answer is read.
    let next: Promise<DebugProtocol.Event> = client.waitForEvent('stopped');
    await client.configurationDoneRequest();
    await launched;
    const stops: string[] = [];
    for (let copy = 0; copy < 2; copy++) {
      await next;
      const frames = (await client.stackTraceRequest({ threadId: 1 })).body.stackFrames;
      assert.equal(frames[0].source?.path, simple);
      assert.equal(frames[0].line, line);
      stops.push(frames.map((frame) => frame.name).join(' < '));
      next = client.waitForEvent(copy === 0 ? 'stopped' : 'terminated');
      await client.continueRequest({ threadId: 1 });
    }
    assert.notEqual(stops[0], stops[1], 'two different copies');
    assert.ok(
      stops.some((stop) => stop.includes('CutInVehicle.CutIn')) && stops.some((stop) => stop.includes('CutInLead.CutIn')),
      stops.join('\n'),
    );
    await next;
    const rows = storyboardTimeline(bodies.flatMap((body) => body.records)).rows;
    const changeLanes = rows.filter((row) => row.type === 'Event' && row.name === 'ChangeLane');
    assert.deepEqual(
      changeLanes.map((row) => [row.group, row.spans[0]?.start, row.file, row.line]),
      [
        ['CutInVehicle.CutIn', 4.4, simple, line],
        ['CutInLead.CutIn', 2.35, simple, line],
      ],
    );
    // Each stop tells the timeline the time of the stop: the time esmini started the event.
    assert.ok(
      bodies.some((body) => body.records.length === 0 && Math.abs(body.time - 2.35) < 1e-6),
      JSON.stringify(bodies.map((body) => [body.time, body.records.length])),
    );
  });

  it("stops on the main's ManeuverGroup line that imports a group, when the group's copy starts", async () => {
    const folder = temporaryFolder();
    writeTwoCutIns(folder);
    const main = path.join(folder, 'main.xosc');
    const line = lineOf(main, '<ManeuverGroup maximumExecutionCount="1" name="CutInVehicle">');
    const launched = client.launch({ type: 'modular2simple', request: 'launch', program: main, roadPath, duration: 30 });
    await client.waitForEvent('initialized');
    const set = await client.setBreakpointsRequest({ source: { path: main }, breakpoints: [{ line }] });
    assert.equal(set.body.breakpoints[0].verified, true, set.body.breakpoints[0].message);
    assert.match(set.body.breakpoints[0].message ?? '', /^ManeuverGroup CutInVehicle\.CutIn$/);
    const frames = await firstStop(launched);
    // VS Code shows the first frame of a breakpoint's stop: the line the breakpoint is on.
    assert.deepEqual([frames[0].name, frames[0].source?.path, frames[0].line], ['ManeuverGroup CutInVehicle.CutIn (running)', main, line]);
    assert.deepEqual(
      frames.slice(1, 3).map((frame) => [frame.name, frame.source?.path]),
      [
        ['Act EncounterAct', main],
        ['Story EncounterStory', main],
      ],
    );
    // The copy, where the simple scenario writes it, is among the running elements.
    const simple = path.join(folder, 'lane_change.xosc');
    const copy = frames.find((frame) => frame.name.startsWith('ManeuverGroup CutInVehicle.CutIn (running since '));
    assert.deepEqual([copy?.source?.path, copy?.line], [simple, lineOf(simple, '<ManeuverGroup name="CutIn"')]);
    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);
  });

  it("stops on an intermediate main's ManeuverGroup line that imports a group, when the top main's copy of it starts", async () => {
    const folder = temporaryFolder();
    const { top, inner, simple } = writeNestedCutIn(folder);
    const line = lineOf(inner, '<ManeuverGroup maximumExecutionCount="1" name="CutInVehicle">');
    const launched = client.launch({ type: 'modular2simple', request: 'launch', program: top, roadPath, duration: 30 });
    await client.waitForEvent('initialized');
    const leadLine = lineOf(inner, '<ManeuverGroup maximumExecutionCount="1" name="CutInLead">');
    const set = await client.setBreakpointsRequest({ source: { path: inner }, breakpoints: [{ line }, { line: leadLine }] });
    assert.equal(set.body.breakpoints[0].verified, true, set.body.breakpoints[0].message);
    assert.equal(set.body.breakpoints[0].message, 'ManeuverGroup Outer.CutInVehicle.CutIn');
    // A group of the intermediate main that the top main does not import: no copy of it runs, and the breakpoint says why.
    assert.equal(set.body.breakpoints[1].verified, false);
    assert.equal(
      set.body.breakpoints[1].message,
      'ManeuverGroup CutInLead is not in the scenario being debugged: no reference of main.xosc imports it',
    );
    const frames = await firstStop(launched);
    // The breakpoint's line first, then the top main's group that imports from the intermediate main.
    assert.deepEqual(
      frames.slice(0, 4).map((frame) => [frame.name, frame.source?.path, frame.line]),
      [
        ['ManeuverGroup Outer.CutInVehicle.CutIn (running)', inner, line],
        ['ManeuverGroup Outer (imports CutInVehicle.CutIn from inner/main.xosc)', top, lineOf(top, 'name="Outer"')],
        ['Act EncounterAct', top, lineOf(top, '<Act name="EncounterAct"')],
        ['Story EncounterStory', top, lineOf(top, '<Story name="EncounterStory"')],
      ],
    );
    const copy = frames.find((frame) => frame.name.startsWith('ManeuverGroup Outer.CutInVehicle.CutIn (running since '));
    assert.deepEqual([copy?.source?.path, copy?.line], [simple, lineOf(simple, '<ManeuverGroup name="CutIn"')]);
    // A stop inside the copy: its stack climbs from the simple scenario through each group that imports it.
    const eventLine = lineOf(simple, '<Event name="ChangeLane"');
    const next = client.waitForEvent('stopped');
    await client.setBreakpointsRequest({ source: { path: simple }, breakpoints: [{ line: eventLine }] });
    await client.continueRequest({ threadId: 1 });
    await next;
    const inside = (await client.stackTraceRequest({ threadId: 1 })).body.stackFrames;
    assert.deepEqual(
      inside.slice(0, 6).map((frame) => [frame.name, frame.source?.path, frame.line]),
      [
        ['Event ChangeLane (running)', simple, eventLine],
        ['Maneuver CutInManeuver', simple, lineOf(simple, '<Maneuver name="CutInManeuver"')],
        ['ManeuverGroup Outer.CutInVehicle.CutIn', simple, lineOf(simple, '<ManeuverGroup name="CutIn"')],
        ['ManeuverGroup CutInVehicle (imports CutIn from lane_change.xosc)', inner, line],
        ['ManeuverGroup Outer (imports CutInVehicle.CutIn from inner/main.xosc)', top, lineOf(top, 'name="Outer"')],
        ['Act EncounterAct', top, lineOf(top, '<Act name="EncounterAct"')],
      ],
    );
    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);
  });

  it("stops on an importing ManeuverGroup line inside a .mosc package, and takes breakpoints set by the package file's source reference alone", async () => {
    const folder = temporaryFolder();
    const { top, pack, innerText } = await writeNestedCutInPackage(folder);
    const lineIn = (text: string, needle: string) => text.split('\n').findIndex((line) => line.includes(needle)) + 1;
    const line = lineIn(innerText, '<ManeuverGroup maximumExecutionCount="1" name="CutInVehicle">');
    assert.ok(line > 0);
    // The package's main as the adapter names it (the path of a stack frame's source), as VS Code sends it back.
    const innerPath = path.join(pack, 'main.xosc');
    const launched = client.launch({ type: 'modular2simple', request: 'launch', program: top, roadPath, duration: 30 });
    await client.waitForEvent('initialized');
    const set = await client.setBreakpointsRequest({ source: { path: innerPath }, breakpoints: [{ line }] });
    assert.equal(set.body.breakpoints[0].verified, true, set.body.breakpoints[0].message);
    assert.equal(set.body.breakpoints[0].message, 'ManeuverGroup Outer.CutInVehicle.CutIn');
    const frames = await firstStop(launched);
    assert.deepEqual(
      frames.slice(0, 2).map((frame) => [frame.name, frame.source?.path, frame.line]),
      [
        ['ManeuverGroup Outer.CutInVehicle.CutIn (running)', innerPath, line],
        ['ManeuverGroup Outer (imports CutInVehicle.CutIn from inner.mosc)', top, lineOf(top, 'name="Outer"')],
      ],
    );
    // A file inside a package has no path on disk: the editor reads its text through the source request.
    const reference = frames[0].source?.sourceReference ?? 0;
    assert.ok(reference > 0, 'the package file has a source reference');
    assert.equal((await client.sourceRequest({ sourceReference: reference })).body.content, innerText);
    // The copy where the package's lane_change.xosc writes it; a breakpoint set by that source's reference alone.
    const copy = frames.find((frame) => frame.name.startsWith('ManeuverGroup Outer.CutInVehicle.CutIn (running since '));
    const simpleReference = copy?.source?.sourceReference ?? 0;
    assert.equal(copy?.source?.path, path.join(pack, 'lane_change.xosc'));
    assert.ok(simpleReference > 0);
    const simpleText = (await client.sourceRequest({ sourceReference: simpleReference })).body.content;
    const eventLine = lineIn(simpleText, '<Event name="ChangeLane"');
    const byReference = await client.setBreakpointsRequest({
      source: { sourceReference: simpleReference },
      breakpoints: [{ line: eventLine }],
    });
    assert.equal(byReference.body.breakpoints[0].verified, true, byReference.body.breakpoints[0].message);
    const next = client.waitForEvent('stopped');
    await client.continueRequest({ threadId: 1 });
    await next;
    const inside = (await client.stackTraceRequest({ threadId: 1 })).body.stackFrames;
    assert.deepEqual(
      inside.slice(0, 5).map((frame) => [frame.name, frame.source?.path, frame.line]),
      [
        ['Event ChangeLane (running)', path.join(pack, 'lane_change.xosc'), eventLine],
        ['Maneuver CutInManeuver', path.join(pack, 'lane_change.xosc'), lineIn(simpleText, '<Maneuver name="CutInManeuver"')],
        ['ManeuverGroup Outer.CutInVehicle.CutIn', path.join(pack, 'lane_change.xosc'), lineIn(simpleText, '<ManeuverGroup name="CutIn"')],
        ['ManeuverGroup CutInVehicle (imports CutIn from lane_change.xosc)', innerPath, line],
        ['ManeuverGroup Outer (imports CutInVehicle.CutIn from inner.mosc)', top, lineOf(top, 'name="Outer"')],
      ],
    );
    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);
  });

  it("makes a restart a new run: the timeline's and the bird's-eye view's events number it, and the timeline shows it alone", async () => {
    const eventLine = lineOf(cutIn, '<Event name="CutInEvent"');
    const bodies: StoryboardEventBody[] = [];
    client.on(STORYBOARD_EVENT, (event: DebugProtocol.Event) => bodies.push(event.body as StoryboardEventBody));
    const states: DebugState[] = [];
    client.on(DEBUG_STATE_EVENT, (event: DebugProtocol.Event) => states.push(event.body as DebugState));
    const launch: DebugProtocol.LaunchRequestArguments & Record<string, unknown> = {
      type: 'modular2simple',
      request: 'launch',
      program: cutIn,
      roadPath,
    };
    await client.hitBreakpoint(launch, { path: cutIn, line: eventLine });
    const firstRun = bodies.length;
    assert.ok(firstRun > 0 && bodies.every((body) => body.run === 1), JSON.stringify(bodies.map((body) => body.run)));
    // VS Code's restart button sends restart with the launch configuration; the session (and its id) stays.
    const stopped = client.waitForEvent('stopped');
    await client.restartRequest({ arguments: launch });
    await stopped;
    const restartTime = Number(await evaluate(client, 'time'));
    assert.equal(restartTime, 6.5, 'the restarted run stops on the same breakpoint at the time esmini starts CutInEvent');
    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);

    const secondRun = bodies.slice(firstRun);
    assert.ok(secondRun.length > 0 && secondRun.every((body) => body.run === 2), JSON.stringify(secondRun.map((body) => body.run)));
    assert.equal(secondRun[0].time, 0, 'the new run starts at 0 s');
    // The timeline's model over every event of the session keeps the second run's records alone.
    let trace: LiveTrace | undefined;
    for (const body of bodies) trace = followStoryboard(trace, body);
    assert.ok(trace);
    assert.equal(trace.run, 2);
    assert.deepEqual(
      trace.records,
      secondRun.flatMap((body) => body.records),
    );
    const rows = storyboardTimeline(trace.records, trace.time).rows;
    const cutInEvent = rows.find((row) => row.type === 'Event' && row.name === 'CutInEvent');
    assert.deepEqual(
      cutInEvent?.spans.map((span) => span.start),
      [6.5],
    );
    assert.ok(cutInEvent?.spans[0].end !== undefined, 'CutInEvent ends in the run that went to the end');
    const story = rows.find((row) => row.type === 'Story');
    assert.deepEqual(
      story?.spans.map((span) => span.start),
      [0],
    );
    // Each element's records once: the first run's CutInEvent start is not among them.
    assert.equal(trace.records.filter((record) => record.element.endsWith('::CutInEvent') && record.state === 'running').length, 1);
    // The bird's-eye view's states say the run too.
    const stateRuns = [...new Set(states.map((state) => state.run))];
    assert.deepEqual(stateRuns, [1, 2]);
  });

  it('pauses a run where it is, says that time, and continues from there to the outcome of a run left alone', async () => {
    // A small step, so that the run lasts (about 217,000 steps) and the pause lands in it.
    const launch = { type: 'modular2simple', request: 'launch', program: cutIn, roadPath, timeStep: 0.0001 };
    /** The Debug Console's transition lines of a session, and the time it ended at. */
    const follow = (session: DebugClient) => {
      const transitions: string[] = [];
      let ended: number | undefined;
      session.on('output', (event: DebugProtocol.OutputEvent) => {
        if (/^\[[\d.]+\] /.test(event.body.output)) transitions.push(event.body.output);
        const end = /The scenario ended at ([\d.]+) s/.exec(event.body.output);
        if (end) ended = Number(end[1]);
      });
      return { transitions, ended: () => ended };
    };
    const paused = follow(client);
    const states: DebugState[] = [];
    client.on(DEBUG_STATE_EVENT, (event: DebugProtocol.Event) => states.push(event.body as DebugState));
    const running = new Promise<void>((resolve) =>
      client.on(DEBUG_STATE_EVENT, (event: DebugProtocol.Event) => (event.body as DebugState).paused || resolve()),
    );
    const launched = client.launch(launch);
    await client.waitForEvent('initialized');
    await client.configurationDoneRequest();
    await launched;
    // Paused once the session says it is stepping (its state, published while running).
    await running;
    const stop = client.waitForEvent('stopped');
    await client.pauseRequest({ threadId: 1 });
    const stopped = (await stop) as DebugProtocol.StoppedEvent;
    assert.equal(stopped.body.reason, 'pause');
    const time = Number(await evaluate(client, 'time'));
    assert.ok(time > 0, `paused at ${time}`);
    assert.equal(stopped.body.description, `Paused at ${time.toFixed(2)} s`);
    const published = states[states.length - 1];
    assert.ok(published.paused && Math.abs(published.time - time) < 1e-9, `published at ${published.time}, paused at ${time}`);
    // Still there after a look at the entities, and one step on is one step later.
    await scope(client, 'Entities');
    assert.equal(Number(await evaluate(client, 'time')), time);
    await Promise.all([client.stepInRequest({ threadId: 1 }), client.waitForEvent('stopped')]);
    const stepped = Number(await evaluate(client, 'time'));
    assert.equal((stepped - time).toFixed(4), '0.0001');
    const before = paused.transitions.length;
    const afterPause = states.length;
    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);
    // Continued from there, not from 0: what it reported afterwards comes later than the pause.
    const laterTimes = paused.transitions.slice(before).map((line) => Number(/^\[([\d.]+)\]/.exec(line)?.[1]));
    assert.ok(
      laterTimes.every((later) => later >= Number(stepped.toFixed(2))),
      `after the pause at ${stepped}: ${laterTimes.join(', ')}`,
    );
    assert.ok(
      states.slice(afterPause).every((state) => state.time >= stepped - 1e-9),
      states
        .slice(afterPause)
        .map((state) => state.time)
        .join(', '),
    );

    // The same scenario left alone: the same transitions at the same times, the same end.
    const alone = await startClient();
    try {
      const unpaused = follow(alone.client);
      const terminated = alone.client.waitForEvent('terminated');
      const aloneLaunched = alone.client.launch(launch);
      await alone.client.waitForEvent('initialized');
      await alone.client.configurationDoneRequest();
      await aloneLaunched;
      await terminated;
      assert.ok(paused.ended() !== undefined && paused.ended() === unpaused.ended(), `ended at ${paused.ended()} and ${unpaused.ended()}`);
      assert.ok(paused.ended()! > time, `the pause at ${time} came before the end at ${paused.ended()}`);
      assert.deepEqual(paused.transitions, unpaused.transitions);
      assert.ok(unpaused.transitions.length > 20, unpaused.transitions.join(''));
    } finally {
      await alone.client.stop();
      await alone.exited;
    }
    assert.equal(alone.stderr(), '', 'the second adapter logged an exception');
  });

  it('keeps a conditional breakpoint that never holds from stopping, and stops at a time breakpoint', async () => {
    const eventLine = lineOf(cutIn, '<Event name="CutInEvent"');
    const launched = client.launch({ type: 'modular2simple', request: 'launch', program: cutIn, roadPath });
    await client.waitForEvent('initialized');
    await client.setBreakpointsRequest({ source: { path: cutIn }, breakpoints: [{ line: eventLine, condition: 'Ego.speed > 1000' }] });
    const functions = await client.setFunctionBreakpointsRequest({ breakpoints: [{ name: 't=5.0' }] });
    assert.equal(functions.body.breakpoints[0].verified, true);
    const stop = client.waitForEvent('stopped');
    await client.configurationDoneRequest();
    await launched;
    const stopped = (await stop) as DebugProtocol.StoppedEvent;
    assert.equal(stopped.body.reason, 'function breakpoint');
    assert.equal(Number(await evaluate(client, 'time')).toFixed(2), '5.00');
    await Promise.all([client.continueRequest({ threadId: 1 }), client.waitForEvent('terminated')]);
  });

  it("ends the session cleanly with esmini's message when the scenario does not load", async () => {
    const folder = temporaryFolder();
    const bad = path.join(folder, 'bad-road.xosc');
    fs.writeFileSync(bad, fs.readFileSync(cutIn, 'utf8').replace('../xodr/e6mini.xodr', 'no-such-road.xodr'));
    const outputs: string[] = [];
    client.on('output', (event: DebugProtocol.OutputEvent) => outputs.push(event.body.output));
    await client.initializeRequest();
    const terminated = client.waitForEvent('terminated');
    await assert.rejects(
      client.launch({ type: 'modular2simple', request: 'launch', program: bad, roadPath }),
      /esmini did not load the scenario/,
    );
    await terminated;
    assert.ok(
      outputs.some((output) => output.includes('bad-road.xosc:') && /no-such-road/.test(output)),
      outputs.join(''),
    );
  });

  it('refuses a seed esmini cannot take, as run --seed does, before anything is loaded', async () => {
    await client.initializeRequest();
    await assert.rejects(
      client.launch({ type: 'modular2simple', request: 'launch', program: cutIn, roadPath, seed: -1 }),
      /the launch configuration's seed takes a whole number from 0 to 4294967295, not -1/,
    );
  });

  it('names the build when the library is missing', async () => {
    await client.initializeRequest();
    await assert.rejects(
      client.launch({
        type: 'modular2simple',
        request: 'launch',
        program: cutIn,
        // Its catalogs found (a missing catalog directory is an error, refused before the library is looked for).
        roadPath,
        esminiLibrary: path.join(temporaryFolder(), 'nothing-here'),
      }),
      /bash \.\.\/shared\/esmini\/build\.sh \.cache\/esmini/,
    );
  });

  it("reports esmini aborting with the scenario, esmini's reason and the simulated time, and ends the session cleanly", async () => {
    // A RelativeClearanceCondition whose lane range runs backwards (from 1 to -1): valid OpenSCENARIO, which esmini
    // throws on while weighing it (OSCCondition.cpp, LOG_ERROR_AND_QUIT in TrigByRelativeClearance::CheckCondition),
    // out of SE_StepDT, uncaught: std::terminate, SIGABRT. Its Act starts after 3 s, so the crash comes in mid-run.
    const { scenario, esminiLast } = await esminiAborts('clearance-crash.xosc', writeClearanceCrash);

    expectedStderr = /Wrong from and to value in RelativeLaneRange element/;
    const outputs = await runToTheEnd(scenario);
    const important = outputs.filter((event) => event.body.category === 'important').map((event) => event.body.output);
    assert.equal(important.length, 1, JSON.stringify(outputs.map((event) => event.body.output)));
    const message = important[0];
    assert.match(message, /^The debug session of clearance-crash\.xosc ended: esmini's process was killed by SIGABRT/);
    assert.match(message, /esmini: QUITTING, Wrong from and to value in RelativeLaneRange element\./);
    const reached = /at ([\d.]+) s of simulated time \(the last it reported: ([^)]*)\)/.exec(message);
    assert.ok(reached, message);
    assert.equal(Number(reached[1]), Number(esminiLast.toFixed(2)), `the time esmini's CSV ends at: ${message}`);
    assert.equal(reached[2], 'Event E standby', 'the event whose condition esmini was weighing');
    // The session ends cleanly: requests are answered, disconnect too, and the adapter's process exits.
    await assert.rejects(client.threadsRequest(), /esmini crashed/);
    await client.disconnectRequest();
    await exited;
    disconnected = true;
  });

  it('reports the time of a real esmini abort in a step that reported nothing, from the progress page', async () => {
    // OverTaker deleted in the Init and added back after 3 s; a RelativeClearanceCondition towards it with a backwards
    // lane range throws once OverTaker is active, weighed before anything else in the next step (writeAddedEntityCrash).
    const { scenario, esminiLast } = await esminiAborts('added-entity-crash.xosc', writeAddedEntityCrash);

    expectedStderr = /Wrong from and to value in RelativeLaneRange element/;
    const outputs = await runToTheEnd(scenario);
    // The step esmini died in reported nothing: the last transition came a step earlier (OverTaker added).
    const reported = outputs.map((event) => /^\[([\d.]+)\] (.*)/.exec(event.body.output)).filter((match) => match !== null);
    const last = reported[reported.length - 1];
    assert.ok(last, outputs.map((event) => event.body.output).join(''));
    assert.equal((Number(last[1]) + 0.05).toFixed(2), esminiLast.toFixed(2), `the last transition: ${last[0]}`);
    assert.ok(
      reported.some((match) => /AddOverTaker running/.test(match[2])),
      reported.map((match) => match[0]).join('\n'),
    );
    const important = outputs.filter((event) => event.body.category === 'important').map((event) => event.body.output);
    assert.equal(important.length, 1, JSON.stringify(outputs.map((event) => event.body.output)));
    assert.match(important[0], /^The debug session of added-entity-crash\.xosc ended: esmini's process was killed by SIGABRT/);
    assert.match(important[0], /esmini: QUITTING, Wrong from and to value in RelativeLaneRange element\./);
    const reached = /at ([\d.]+) s of simulated time/.exec(important[0]);
    assert.ok(reached, important[0]);
    assert.equal(reached[1], esminiLast.toFixed(2), `the time esmini's CSV ends at: ${important[0]}`);
    await client.disconnectRequest();
    await exited;
    disconnected = true;
  });

  it('reports the simulated time exactly when the session dies in a step that reported nothing', async function () {
    if (process.platform !== 'linux') {
      console.log('    (skipped: the session process is found through /proc)');
      this.skip();
    }
    // A fault (a signal, not esmini's throw as above) in a step with no callback: the session's process killed at a
    // time breakpoint, then three steps on, in which cut-in.xosc starts and ends nothing.
    const outputs: DebugProtocol.OutputEvent[] = [];
    client.on('output', (event: DebugProtocol.OutputEvent) => outputs.push(event));
    const launched = client.launch({ type: 'modular2simple', request: 'launch', program: cutIn, roadPath });
    await client.waitForEvent('initialized');
    await client.setFunctionBreakpointsRequest({ breakpoints: [{ name: 't=5.0' }] });
    const stop = client.waitForEvent('stopped');
    await client.configurationDoneRequest();
    await launched;
    await stop;
    const transitions = () => outputs.filter((event) => /^\[[\d.]+\] /.test(event.body.output)).length;
    const before = transitions();
    for (let step = 0; step < 3; step++) await Promise.all([client.stepInRequest({ threadId: 1 }), client.waitForEvent('stopped')]);
    assert.equal(Number(await evaluate(client, 'time')).toFixed(2), '5.15');
    assert.equal(transitions(), before, 'the steps reported nothing');
    const terminated = client.waitForEvent('terminated');
    process.kill(sessionProcess(adapterPid), 'SIGSEGV');
    await terminated;
    const important = outputs.filter((event) => event.body.category === 'important').map((event) => event.body.output);
    assert.equal(important.length, 1, JSON.stringify(outputs.map((event) => event.body.output)));
    // The time the steps reached (the progress page), not the last progress line's (the step's start, 5.10 s).
    assert.match(
      important[0],
      /^The debug session of cut-in\.xosc ended: esmini's process was killed by SIGSEGV at 5\.15 s of simulated time/,
    );
    await client.disconnectRequest();
    await exited;
    disconnected = true;
  });
});

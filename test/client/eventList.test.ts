import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { eventRows, eventRowText, withTrace, type EventRow } from '../../client/src/birdsEye/eventList';
import type { RunTracks } from '../../client/src/birdsEye/messages';
import { RunTraceRequest, SceneRequest, type SceneEvent } from '../../common/src/sceneProtocol';
import type { TraceRecord } from '../../common/src/trace';
import { loggedStarts, programRun, TWO_CUT_INS_ROAD_PATH as roadPath, writeTwoCutIns } from '../support/debugScenarios';
import { requireEsmini } from '../support/esmini';
import { temporaryFolder } from '../support/temporaryDirectory';
import { fileUri, TestClient } from '../server/harness';

const NO_TRACKS: RunTracks = { label: 'run', times: [0, 8], entities: [], starts: {}, notes: [] };

const rowOf = (rows: EventRow[], name: string, actor: string) => {
  const found = rows.find((row) => row.name === name && row.actor === actor);
  assert.ok(found, `a ${name} row of ${actor} among ${rows.map(eventRowText).join(' | ')}`);
  return found;
};

describe("bird's-eye event list of a real esmini run: one cut-in group imported twice", function () {
  this.timeout(120_000);
  let client: TestClient | undefined;

  before(function () {
    requireEsmini(this);
  });

  after(async () => {
    await client?.stop();
  });

  /** The scene's events as the view gets them, and the trace the language server reads from a log (a run loaded from a CSV). */
  async function sceneAndTrace(folder: string, log: string): Promise<{ events: SceneEvent[]; trace: TraceRecord[] }> {
    await client?.stop();
    client = await TestClient.start({ root: folder });
    await client.indexed();
    const uri = fileUri(path.join(folder, 'main.xosc'));
    const scene = await client.connection.sendRequest(SceneRequest, { uri, roadPath });
    const trace = await client.connection.sendRequest(RunTraceRequest, { uri, log });
    return { events: scene.events, trace };
  }

  it('gives each copy its own start time, the times esmini logs, with its actor and group, in time order', async () => {
    const folder = temporaryFolder();
    writeTwoCutIns(folder);
    const program = await programRun(folder);
    const { events, trace } = await sceneAndTrace(folder, program.log);
    // The scene names each copy's path, actors and the group it was copied from.
    const changeLanes = events.filter((event) => event.name === 'ChangeLane');
    assert.deepEqual(
      changeLanes.map((event) => [event.path, event.actors, event.sourceGroup]),
      [
        [
          'EncounterStory::EncounterAct::CutInVehicle.CutIn::CutInManeuver::ChangeLane',
          ['adversary'],
          { name: 'CutIn', file: 'lane_change.xosc' },
        ],
        ['EncounterStory::EncounterAct::CutInLead.CutIn::CutInManeuver::ChangeLane', ['lead'], { name: 'CutIn', file: 'lane_change.xosc' }],
      ],
    );

    const logged = loggedStarts(program.log, 'ChangeLane');
    assert.equal(logged.length, 2, "esmini's log starts ChangeLane twice");
    assert.notEqual(logged[0], logged[1], 'at two different times');
    // A run loaded from its CSV and log (the server reads the log) and a Run in esmini (its own trace) list the same.
    for (const [label, records] of [
      ['log read by the server', trace],
      ['Run in esmini trace', program.trace],
    ] as const) {
      const rows = eventRows(events, withTrace(NO_TRACKS, records), 'finished');
      const lead = rowOf(rows, 'ChangeLane', 'lead');
      const adversary = rowOf(rows, 'ChangeLane', 'adversary');
      assert.deepEqual([lead.start, adversary.start], logged, label);
      assert.deepEqual([lead.group, lead.importedBy, lead.groupFile], ['CutIn', 'CutInLead', 'lane_change.xosc'], label);
      assert.deepEqual([adversary.group, adversary.importedBy], ['CutIn', 'CutInVehicle'], label);
      assert.equal(lead.cause, 'RelativeDistanceCondition: rel_dist 30.12 > 30', label);
      assert.equal(
        eventRowText(lead),
        `ChangeLane · lead · CutIn (lane_change.xosc, imported by CutInLead) · started ${logged[0].toFixed(2)} s · RelativeDistanceCondition: rel_dist 30.12 > 30`,
      );
      // Time order: every started row by its start, each no earlier than the one before.
      const starts = rows.map((row) => row.start);
      assert.ok(
        starts.every((start) => start !== undefined),
        `every event starts in this run: ${rows.map(eventRowText).join(' | ')}`,
      );
      assert.deepEqual(
        starts,
        [...starts].sort((a, b) => a! - b!),
        label,
      );
    }
  });

  it('lists an event that never started after the ones that did, saying so', async () => {
    const folder = temporaryFolder();
    writeTwoCutIns(folder, 500);
    const program = await programRun(folder);
    const { events, trace } = await sceneAndTrace(folder, program.log);
    const rows = eventRows(events, withTrace(NO_TRACKS, trace), 'finished');
    assert.deepEqual(loggedStarts(program.log, 'ChangeLane').length, 1, "esmini's log starts one ChangeLane");
    const never = rowOf(rows, 'ChangeLane', 'lead');
    assert.equal(never.state, 'never');
    assert.match(
      eventRowText(never),
      /^ChangeLane · lead · CutIn \(lane_change\.xosc, imported by CutInLead\) · never started · RelativeDistance greaterThan 500$/,
    );
    assert.equal(rows[rows.length - 1], never, 'listed last');
    assert.equal(rowOf(rows, 'ChangeLane', 'adversary').state, 'started');
    // Before a run the same rows are planned or wait for their condition; while a debug session runs, "not started yet".
    assert.ok(eventRows(events, undefined, 'none').every((row) => row.state === 'planned' || row.state === 'waiting'));
    assert.equal(rowOf(eventRows(events, { starts: {} }, 'live'), 'ChangeLane', 'lead').when, 'not started yet');
  });
});

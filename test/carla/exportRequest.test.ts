import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { exportSummary, placedByUri } from '../../client/src/placed';
import { ExportForCarlaRequest, type ProblemSummary } from '../../common/src/protocol';
import { fileUri, TestClient } from '../server/harness';
import { SERVER_WAIT_MS } from '../support/wait';
import { lineMatching } from '../support/carla';
import { esminiRoads } from '../support/esmini';
import { drivingScenario, packageOf } from '../support/fixtures';
import { repoRoot } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

function losses(problems: ProblemSummary[]): ProblemSummary[] {
  return problems.filter((problem) => problem.code?.startsWith('carla-export-'));
}

/** A server on a fresh copy of the bundled examples, with `settings`, for the calling suite. */
function serveExamples(settings: Record<string, unknown>): { root: () => string; client: () => TestClient } {
  let root = '';
  let client: TestClient | undefined;
  before(async function () {
    root = temporaryWorkspace({}, 'm2s-carla-examples-');
    fs.cpSync(path.join(repoRoot, 'examples'), root, { recursive: true });
    client = await TestClient.start({ root, settings });
    await client.indexed();
  });
  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });
  return {
    root: () => root,
    client: () => {
      if (!client) throw new Error('the server has not started');
      return client;
    },
  };
}

describe('Export for CARLA over JSON-RPC: the loss report at the modular sources (ScenarioRunner 0.9.15)', function () {
  this.timeout(60_000);
  const examples = serveExamples({ carla: { release: '0.9.15' } });

  it("places an imported group's losses in its simple scenario, with the range of the element, and writes the file", async () => {
    const root = examples.root();
    const client = examples.client();
    const output = path.join(root, 'main.carla.xosc');
    const laneChange = path.join(root, 'lane_change.xosc');
    // Under 0.9.15 the AcquirePositionAction of crossing.xosc builds, so the main is written.
    try {
      const result = await client.send(ExportForCarlaRequest, { uri: fileUri(path.join(root, 'main.xosc')), outputPath: output });
      assert.equal(result.written, output);
      assert.match(fs.readFileSync(output, 'utf8'), /revMajor="1" revMinor="0"/);
      const found = losses(result.problems);
      const priority = found.find((loss) => loss.message.startsWith('Event/@priority') && loss.uri === fileUri(laneChange));
      assert.ok(priority, JSON.stringify(found, null, 1));
      assert.equal(priority.line, lineMatching(laneChange, /<Event .*priority=/));
      assert.equal(priority.severity, 'warning');
      assert.ok(priority.end && priority.end.line >= priority.line, 'the loss has the range of its element');
      assert.match(priority.message, /ScenarioRunner runs every event in parallel/);
      assert.equal(
        found.some((loss) => loss.uri === fileUri(path.join(root, 'main.xosc')) && loss.message.startsWith('Event/@priority')),
        false,
        'not in the main, which only imports the group',
      );
      assert.match(exportSummary(result.written, result.problems), /^wrote main\.carla\.xosc; \d+ losses in .*lane_change\.xosc/);
    } finally {
      fs.rmSync(output, { force: true });
    }
  });

  it('writes into a folder that does not exist yet, as the save dialog offered to create it (was: ENOENT on a temporary file, nothing written)', async () => {
    const root = examples.root();
    const exports = path.join(root, 'exports');
    const output = path.join(exports, 'carla', 'main.carla.xosc');
    try {
      const result = await examples
        .client()
        .send(ExportForCarlaRequest, { uri: fileUri(path.join(root, 'main.xosc')), outputPath: output });
      assert.equal(result.written, output, JSON.stringify(result.problems.filter((problem) => problem.severity === 'error')));
      assert.match(fs.readFileSync(output, 'utf8'), /revMajor="1" revMinor="0"/);
      assert.deepEqual(fs.readdirSync(path.dirname(output)), ['main.carla.xosc'], 'no temporary file left');
    } finally {
      fs.rmSync(exports, { recursive: true, force: true });
    }
  });
});

describe('Export for CARLA over JSON-RPC: a refusal (ScenarioRunner 0.9.16)', function () {
  this.timeout(60_000);
  const examples = serveExamples({});

  it('refuses a main whose imported group crashes ScenarioRunner 0.9.16: the refusal at the simple scenario, nothing written', async () => {
    const root = examples.root();
    const output = path.join(root, 'main.carla.xosc');
    const result = await examples.client().send(ExportForCarlaRequest, { uri: fileUri(path.join(root, 'main.xosc')), outputPath: output });
    assert.equal(result.written, null);
    assert.equal(fs.existsSync(output), false, 'nothing is written for a refused export');
    assert.deepEqual(
      fs.readdirSync(root).filter((name) => name.includes('carla') || name.startsWith('.')),
      [],
      'no temporary file is left beside it',
    );
    const crossing = fileUri(path.join(root, 'crossing.xosc'));
    const refusal = losses(result.problems).find((loss) => loss.severity === 'error');
    assert.ok(refusal, JSON.stringify(result.problems, null, 1));
    assert.equal(refusal.uri, crossing, 'the refusal is in the simple scenario that wrote the action, not the main');
    assert.equal(refusal.line, lineMatching(path.join(root, 'crossing.xosc'), /<AcquirePositionAction/));
    assert.match(refusal.message, /AcquirePositionAction: crashes ScenarioRunner 0\.9\.16/);
    // The losses of the groups imported from lane_change.xosc land there; the editor groups them per file.
    const byUri = placedByUri(result.problems);
    assert.ok(byUri.get(fileUri(path.join(root, 'lane_change.xosc')))?.some((placed) => placed.code === 'carla-export-approximated'));
    assert.ok(
      result.problems.some((problem) => problem.severity === 'error' && /not exported: /.test(problem.message)),
      'the refusal is named in a sentence',
    );
  });
});

describe("Export for CARLA over JSON-RPC: roads from modular2simple.esmini.roadPath, as Run in esmini's", function () {
  this.timeout(60_000);
  let root = '';
  let client: TestClient | undefined;
  before(async function () {
    // The library's crossing names roads/straight_1000m.xodr, which is not beside it here but in the workspace's myroads/.
    root = temporaryWorkspace(
      {
        'scenarios/crossing.xosc': fs.readFileSync(path.join(repoRoot, 'library', 'pedestrian-crossing.xosc'), 'utf8'),
        'myroads/straight_1000m.xodr': fs.readFileSync(path.join(repoRoot, 'library', 'roads', 'straight_1000m.xodr'), 'utf8'),
      },
      'm2s-carla-roadpath-',
    );
    client = await TestClient.start({ root, settings: { carla: { release: '0.9.15' } } });
    await client.indexed();
  });
  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  it('refuses the road without the setting, and with it writes the road relative to the export', async () => {
    if (!client) throw new Error('the server has not started');
    const uri = fileUri(path.join(root, 'scenarios', 'crossing.xosc'));
    const output = path.join(root, 'out', 'crossing.carla.xosc');
    fs.mkdirSync(path.dirname(output));
    const refused = await client.send(ExportForCarlaRequest, { uri, outputPath: output });
    assert.equal(refused.written, null);
    assert.ok(
      refused.problems.some((problem) =>
        /straight_1000m\.xodr'?, which is neither a CARLA town nor a readable \.xodr/.test(problem.message),
      ),
      JSON.stringify(refused.problems, null, 1),
    );
    await client.settingsChanged({ carla: { release: '0.9.15' }, esmini: { roadPath: ['myroads'] } });
    // The server pulls the new settings after the notification: asked again until they apply (a refusal writes nothing).
    let result = await client.send(ExportForCarlaRequest, { uri, outputPath: output });
    for (const deadline = Date.now() + SERVER_WAIT_MS; result.written === null && Date.now() < deadline;) {
      await new Promise((resolve) => setTimeout(resolve, 200));
      result = await client.send(ExportForCarlaRequest, { uri, outputPath: output });
    }
    assert.equal(result.written, output, JSON.stringify(result.problems, null, 1));
    assert.match(fs.readFileSync(output, 'utf8'), /<LogicFile filepath="\.\.\/myroads\/straight_1000m\.xodr"\/>/);
  });
});

describe("Export for CARLA over JSON-RPC: a road packed in the scenario's .mosc (issue 27)", function () {
  this.timeout(60_000);

  it("writes the package's road beside the export, which names it; before, the export was refused as naming no road", async () => {
    const road = fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'));
    const scenario = drivingScenario('roads/straight_500m.xodr', 'Drive');
    const root = temporaryWorkspace({
      'pkg.mosc': await packageOf({ 'main.xosc': scenario, 'roads/straight_500m.xodr': road.toString('utf8') }),
    });
    const client = await TestClient.start({ root });
    try {
      await client.indexed();
      const output = path.join(root, 'out', 'pkg.carla.xosc');
      fs.mkdirSync(path.dirname(output));
      const result = await client.send(ExportForCarlaRequest, { uri: `mosc:${path.join(root, 'pkg.mosc')}/main.xosc`, outputPath: output });
      assert.equal(result.written, output, JSON.stringify(result.problems, null, 1));
      assert.match(fs.readFileSync(output, 'utf8'), /<LogicFile filepath="pkg\.carla\.files\/roads\/straight_500m\.xodr"\/>/);
      assert.deepEqual(fs.readFileSync(path.join(root, 'out', 'pkg.carla.files', 'roads', 'straight_500m.xodr')), road);
    } finally {
      await client.stop();
      fs.rmSync(root, { recursive: true, force: true });
    }
  });
});

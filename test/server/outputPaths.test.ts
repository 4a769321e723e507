import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { FlattenToFileRequest, PackRequest } from '../../common/src/protocol';
import { EsminiStep, requireEsmini } from '../support/esmini';
import { scenario, simpleGroup } from '../support/fixtures';
import { assertSameRun, cutInWorkspace, namedPaths, runAlone } from '../support/outputPaths';
import { temporaryFolder } from '../support/temporaryDirectory';
import { temporaryWorkspace } from '../support/workspace';
import { fileUri, TestClient } from './harness';

/** SPEC 11.6 through the editor's commands: Flatten to .xosc and Pack into .mosc write outputs that reach the sources' files. */
const withRoad = (groups: string) =>
  scenario(groups).replace('<Entities>', '<RoadNetwork>\n    <LogicFile filepath="../xodr/road.xodr"/>\n  </RoadNetwork>\n  <Entities>');

describe('language server: written outputs rebase their file paths (SPEC 11.6)', function () {
  let root: string;
  let client: TestClient;

  before(async function () {
    root = temporaryWorkspace({
      'ws/xodr/road.xodr': '<OpenDRIVE/>',
      'ws/xosc/simple.xosc': scenario(simpleGroup('Go')),
      'ws/xosc/main.xosc': withRoad(
        '        <ManeuverGroup maximumExecutionCount="1" name="Outer">\n          <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>\n          <ScenarioReference scenarioFileName="simple.xosc"><ManeuverGroupReference maneuverGroupName="Go"/></ScenarioReference>\n        </ManeuverGroup>\n',
      ),
    });
    client = await TestClient.start({ root });
    await client.indexed();
  });

  after(async () => client.stop());

  it('Flatten to .xosc one folder up names the road from there', async () => {
    const output = path.join(root, 'ws', 'xosc.flattened.xosc');
    const result = await client.send(FlattenToFileRequest, {
      uri: fileUri(path.join(root, 'ws', 'xosc', 'main.xosc')),
      outputPath: output,
    });
    assert.equal(result.written, output, JSON.stringify(result.problems));
    assert.match(fs.readFileSync(output, 'utf8'), /<LogicFile filepath="xodr\/road\.xodr"\/>/);
  });

  it('Pack into .mosc rebases onto the package and warns; self-contained stores the road', async () => {
    const output = path.join(root, 'packages', 'deeper', 'main.mosc');
    fs.mkdirSync(path.dirname(output), { recursive: true });
    const outside = await client.send(PackRequest, { inputs: [fileUri(path.join(root, 'ws', 'xosc'))], outputPath: output });
    assert.equal(outside.written, output, JSON.stringify(outside.problems));
    assert.ok(
      outside.problems.some(
        (problem) =>
          problem.severity === 'warning' &&
          problem.message.includes(`reaches the file ${path.join(root, 'ws', 'xodr', 'road.xodr')} outside itself`),
      ),
      JSON.stringify(outside.problems),
    );
    const packed = await JSZip.loadAsync(fs.readFileSync(output));
    assert.match((await packed.file('main.xosc')?.async('string')) ?? '', /<LogicFile filepath="\.\.\/\.\.\/ws\/xodr\/road\.xodr"\/>/);

    const contained = await client.send(PackRequest, {
      inputs: [fileUri(path.join(root, 'ws', 'xosc'))],
      outputPath: output,
      selfContained: true,
    });
    assert.equal(contained.written, output, JSON.stringify(contained.problems));
    assert.deepEqual(
      contained.problems.filter((problem) => problem.severity === 'warning'),
      [],
    );
    const zip = await JSZip.loadAsync(fs.readFileSync(output));
    assert.deepEqual(Object.keys(zip.files).sort(), ['files/road.xodr', 'main.xosc', 'simple.xosc']);
    assert.match((await zip.file('main.xosc')?.async('string')) ?? '', /<LogicFile filepath="files\/road\.xodr"\/>/);

    // Flattening the package writes the road it holds beside the output, where the output names it.
    const flat = path.join(root, 'flat', 'main.xosc');
    fs.mkdirSync(path.dirname(flat), { recursive: true });
    const flattened = await client.send(FlattenToFileRequest, { uri: `mosc:${output}/main.xosc`, outputPath: flat });
    assert.equal(flattened.written, flat, JSON.stringify(flattened.problems));
    assert.match(fs.readFileSync(flat, 'utf8'), /<LogicFile filepath="main\.files\/files\/road\.xodr"\/>/);
    assert.equal(fs.readFileSync(path.join(root, 'flat', 'main.files', 'files', 'road.xodr'), 'utf8'), '<OpenDRIVE/>');
  });
});

describe('language server: Flatten and Pack to folders of other depths write outputs that esmini runs as the original (SPEC 11.6)', function () {
  let ws: string;
  let client: TestClient;
  let original: EsminiStep[];
  let expectedPaths: string[];
  const main = () => fileUri(path.join(ws, 'xosc', 'main.xosc'));

  before(async function () {
    requireEsmini(this);
    ws = cutInWorkspace();
    original = (await runAlone(path.join(ws, 'xosc', 'cut-in.xosc'))).steps;
    expectedPaths = [path.join(ws, 'xosc', 'Catalogs', 'Vehicles'), path.join(ws, 'xodr', 'e6mini.xodr')];
    client = await TestClient.start({ root: ws });
    await client.indexed();
  });

  after(async () => client?.stop());

  // outsideWorkspace: the user's confirmation, which a folder outside the workspace (a temporary one) needs.
  const places: [string, () => string][] = [
    ['one folder up', () => path.join(ws, 'xosc.flattened.xosc')],
    ['two folders deeper', () => path.join(ws, 'xosc', 'out', 'deep', 'flat.xosc')],
    ['an unrelated temporary folder', () => path.join(temporaryFolder('m2s-paths-server-'), 'a', 'flat.xosc')],
  ];
  for (const [where, output] of places) {
    it(`Flatten to .xosc ${where}: loads the same road and catalogs and moves as the original`, async () => {
      const target = output();
      fs.mkdirSync(path.dirname(target), { recursive: true });
      const result = await client.send(FlattenToFileRequest, { uri: main(), outputPath: target, outsideWorkspace: true });
      assert.equal(result.written, target, JSON.stringify(result.problems));
      assert.deepEqual(namedPaths(target), expectedPaths);
      assertSameRun((await runAlone(target)).steps, original, `Flatten ${where}`);
    });
  }

  it('Pack into .mosc at another depth, then Flatten the package to a third: moves as the original', async () => {
    const packed = path.join(ws, 'packages', 'deep', 'cut-in.mosc');
    fs.mkdirSync(path.dirname(packed), { recursive: true });
    const pack = await client.send(PackRequest, { inputs: [fileUri(path.join(ws, 'xosc'))], outputPath: packed });
    assert.equal(pack.written, packed, JSON.stringify(pack.problems));
    const flat = path.join(temporaryFolder('m2s-paths-server-'), 'x', 'y', 'cut-in.xosc');
    fs.mkdirSync(path.dirname(flat), { recursive: true });
    const flattened = await client.send(FlattenToFileRequest, {
      uri: `mosc:${packed}/main.xosc`,
      outputPath: flat,
      outsideWorkspace: true,
    });
    assert.equal(flattened.written, flat, JSON.stringify(flattened.problems));
    assert.deepEqual(namedPaths(flat), expectedPaths);
    assertSameRun((await runAlone(flat)).steps, original, 'flattened package');
  });

  it('Pack self-contained, copied alone to a fresh folder: its Flatten runs as the original', async () => {
    const packed = path.join(ws, 'packages', 'self', 'cut-in.mosc');
    fs.mkdirSync(path.dirname(packed), { recursive: true });
    const pack = await client.send(PackRequest, { inputs: [fileUri(path.join(ws, 'xosc'))], outputPath: packed, selfContained: true });
    assert.equal(pack.written, packed, JSON.stringify(pack.problems));
    const fresh = temporaryFolder('m2s-paths-fresh-');
    fs.copyFileSync(packed, path.join(fresh, 'cut-in.mosc'));
    const flat = path.join(fresh, 'out', 'cut-in.xosc');
    fs.mkdirSync(path.dirname(flat), { recursive: true });
    const flattened = await client.send(FlattenToFileRequest, {
      uri: `mosc:${path.join(fresh, 'cut-in.mosc')}/main.xosc`,
      outputPath: flat,
      outsideWorkspace: true,
    });
    assert.equal(flattened.written, flat, JSON.stringify(flattened.problems));
    for (const named of namedPaths(flat)) assert.ok(named.startsWith(fresh + path.sep), `${named} lies in the fresh folder`);
    assertSameRun((await runAlone(flat)).steps, original, 'self-contained package');
  });
});

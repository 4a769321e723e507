import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CodeAction, Diagnostic, DiagnosticSeverity, RenameFile, TextEdit } from 'vscode-languageserver/node';
import { EXPORT_FOR_CARLA_COMMAND, ExportForCarlaRequest, WriteResult } from '../../common/src/protocol';
import * as fs from 'node:fs';
import { fileUri, TestClient } from './harness';
import { afterASecond, parameterCondition, parameterStoryScenario, settingEvent, storyAct } from '../support/carlaStories';
import { problemCodeOf } from '../support/diagnostics';
import { applyEdits } from '../support/textEdits';
import { temporaryWorkspace } from '../support/workspace';
import { fileHeader, openScenarioFile } from '../support/fixtures';

const SCENARIO = openScenarioFile(
  `  <Entities/>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="s"><Act name="a"><ManeuverGroup name="g" maximumExecutionCount="1">
      <Actors selectTriggeringEntities="false"/>
      <Maneuver name="m"><Event name="e" priority="overwrite"><Action name="x">
        <PrivateAction><VisibilityAction graphics="false" traffic="true" sensors="true"/></PrivateAction>
      </Action></Event></Maneuver>
    </ManeuverGroup></Act></Story>
  </Storyboard>
`,
  fileHeader({ revMinor: '1', description: 'simulator' }),
);

describe('simulator profile in the language server', function () {
  let client: TestClient;
  let uri: string;

  before(async () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO });
    client = await TestClient.start({ root, settings: { simulator: 'carla' } });
    uri = await client.open(fileUri(path.join(root, 'scenario.xosc')), SCENARIO);
  });

  after(async () => {
    await client.stop();
  });

  it('publishes what CARLA refuses as errors and what it runs otherwise as warnings, at their source positions', async () => {
    const diagnostics = await client.diagnosticsOf(uri, (list) => list.some((diagnostic) => problemCodeOf(diagnostic) === 'simulator'));
    const simulator = diagnostics.filter((diagnostic) => problemCodeOf(diagnostic) === 'simulator');
    const version = simulator.find((diagnostic) =>
      /accepts only OpenSCENARIO 1\.0; this file states 1\.1/.test(String(diagnostic.message)),
    );
    assert.ok(version);
    assert.equal(version.severity, DiagnosticSeverity.Error);
    const road = simulator.find((diagnostic) => /names no LogicFile/.test(String(diagnostic.message)));
    assert.equal(road?.severity, DiagnosticSeverity.Error);
    assert.equal(version.range.start.line, 2);
    assert.equal(SCENARIO.split('\n')[2].slice(version.range.start.character, version.range.end.character), '1');
    const action = simulator.find((diagnostic) => /does not support VisibilityAction/.test(String(diagnostic.message)));
    assert.equal(action?.range.start.line, 9);
    assert.equal(action?.severity, DiagnosticSeverity.Error);
  });

  it('drops them when the setting goes back to asam', async () => {
    await client.settingsChanged({ simulator: 'asam' });
    const diagnostics = await client.diagnosticsOf(uri, (list) => !list.some((diagnostic) => problemCodeOf(diagnostic) === 'simulator'));
    assert.deepEqual(
      diagnostics.filter((diagnostic) => problemCodeOf(diagnostic) === 'simulator'),
      [],
    );
  });
});

const CATALOG = openScenarioFile(
  `  <Catalog name="cars"><Vehicle name="vehicle.tesla.model3" vehicleCategory="car">
    <BoundingBox><Center x="1" y="0" z="1"/><Dimensions width="2" length="4" height="1.5"/></BoundingBox>
    <Performance maxSpeed="50" maxAcceleration="5" maxDeceleration="9"/>
    <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.7" positionX="2.9" positionZ="0.3"/>
    <RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.7" positionX="0" positionZ="0.3"/></Axles>
    <Properties/>
  </Vehicle></Catalog>
`,
  fileHeader({ revMinor: '0', description: 'cars' }),
);

/** A 1.1 scenario for CARLA: its version, a \${...} speed and a catalog ScenarioRunner does not find by its file name. */
const FIXABLE = openScenarioFile(
  `  <ParameterDeclarations><ParameterDeclaration name="Speed" parameterType="double" value="36"/></ParameterDeclarations>
  <CatalogLocations><VehicleCatalog><Directory path="catalogs"/></VehicleCatalog></CatalogLocations>
  <RoadNetwork><LogicFile filepath="Town05"/></RoadNetwork>
  <Entities>
    <ScenarioObject name="hero"><CatalogReference catalogName="cars" entryName="vehicle.tesla.model3"/></ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions><Private entityRef="hero"><PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
      <SpeedActionTarget><AbsoluteTargetSpeed value="\${$Speed / 3.6}"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Private></Actions></Init>
    <StopTrigger/>
  </Storyboard>
`,
  fileHeader({ revMinor: '1', description: 'fixes' }),
);

describe('CARLA findings offer their fixes over JSON-RPC', function () {
  let client: TestClient;
  let root: string;
  let uri: string;

  before(async () => {
    root = temporaryWorkspace({ 'scenario.xosc': FIXABLE, 'catalogs/Cars.xosc': CATALOG });
    client = await TestClient.start({ root, settings: { simulator: 'carla' } });
    uri = await client.open(fileUri(path.join(root, 'scenario.xosc')), FIXABLE);
  });

  after(async () => {
    await client.stop();
  });

  const actionsFor = async (diagnostic: Diagnostic): Promise<CodeAction[]> =>
    client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri },
      range: diagnostic.range,
      context: { diagnostics: [diagnostic] },
    });

  const carlaDiagnostic = async (pattern: RegExp): Promise<Diagnostic> => {
    const diagnostics = await client.diagnosticsOf(uri, (list) => list.some((diagnostic) => pattern.test(String(diagnostic.message))));
    const found = diagnostics.find((diagnostic) => problemCodeOf(diagnostic) === 'simulator' && pattern.test(String(diagnostic.message)));
    assert.ok(found, diagnostics.map((diagnostic) => String(diagnostic.message)).join('\n'));
    assert.equal(found.severity, DiagnosticSeverity.Error);
    return found;
  };

  const editOf = (action: CodeAction | undefined): TextEdit | undefined => action?.edit?.changes?.[uri]?.[0];

  it('the version: write revMinor="0", or export for CARLA, which writes 1.0 and maps what 1.1 to 1.3 added', async () => {
    const version = await carlaDiagnostic(/accepts only OpenSCENARIO 1\.0/);
    const actions = await actionsFor(version);
    const write = actions.find((action) => action.title === "Write '0'");
    assert.equal(editOf(write)?.newText, '0');
    assert.deepEqual(editOf(write)?.range, version.range);
    assert.equal(write?.isPreferred, true);
    const exportAction = actions.find((action) => action.command?.command === EXPORT_FOR_CARLA_COMMAND);
    assert.equal(exportAction?.title, 'Export for CARLA…');
    assert.deepEqual(exportAction?.command?.arguments, [uri]);
  });

  it('a ${...} number: write its value, which the inlay hint shows, or export for CARLA', async () => {
    const expression = await carlaDiagnostic(/does not evaluate \$\{\.\.\.\}/);
    assert.match(String(expression.message), /value="\$\{\$Speed \/ 3\.6\}", which is 10/);
    const actions = await actionsFor(expression);
    assert.equal(editOf(actions.find((action) => action.title === "Write '10'"))?.newText, '10');
    const exportAction = actions.find((action) => action.command?.command === EXPORT_FOR_CARLA_COMMAND);
    assert.deepEqual(exportAction?.command?.arguments, [uri]);
  });

  it('a ${...} number edited in and Ctrl+. at once, before its diagnostic reached the client: the same two fixes (it offered none)', async () => {
    const edited = FIXABLE.replace('value="${$Speed / 3.6}"', 'value="10"');
    const other = await client.open(fileUri(path.join(root, 'edited.xosc')), edited);
    const line = edited.split('\n').findIndex((text) => text.includes('<AbsoluteTargetSpeed value="10"'));
    const character = edited.split('\n')[line].indexOf('"10"') + 1;
    await client.change(other, [
      { range: { start: { line, character }, end: { line, character: character + 2 } }, text: '${$Speed / 3.6}' },
    ]);
    // The cursor inside the new value; the client has no diagnostic there yet.
    const cursor = { line, character: character + 3 };
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri: other },
      range: { start: cursor, end: cursor },
      context: { diagnostics: [] },
    });
    const write = actions.find((action) => action.title === "Write '10'");
    assert.equal(write?.edit?.changes?.[other]?.[0]?.newText, '10', JSON.stringify(actions.map((action) => action.title)));
    assert.deepEqual(write?.edit?.changes?.[other]?.[0]?.range, {
      start: { line, character },
      end: { line, character: character + '${$Speed / 3.6}'.length },
    });
    assert.ok(actions.some((action) => action.command?.command === EXPORT_FOR_CARLA_COMMAND));
    await client.close(other);
  });

  it('a catalog in a file of another name: rename it to the name ScenarioRunner reads', async () => {
    const catalog = await carlaDiagnostic(/reads the Vehicle catalog only from .*VehicleCatalog\.xosc, which does not exist/);
    const actions = await actionsFor(catalog);
    const rename = actions.find((action) => action.title === 'Rename Cars.xosc to VehicleCatalog.xosc');
    const change = rename?.edit?.documentChanges?.[0] as RenameFile | undefined;
    assert.equal(change?.kind, 'rename');
    assert.equal(change?.oldUri, fileUri(path.join(root, 'catalogs', 'Cars.xosc')));
    assert.equal(change?.newUri, fileUri(path.join(root, 'catalogs', 'VehicleCatalog.xosc')));
    assert.equal(change?.options?.overwrite, false);
  });

  it('Export for CARLA through the server: writes OpenSCENARIO 1.0 with the catalog inlined, and never over its input', async () => {
    const output = path.join(root, 'out', 'scenario.carla.xosc');
    fs.mkdirSync(path.dirname(output));
    const result = await client.request<WriteResult>(ExportForCarlaRequest.method, { uri, outputPath: output });
    assert.equal(result.written, output, JSON.stringify(result.problems));
    const written = fs.readFileSync(output, 'utf8');
    assert.match(written, /revMajor="1" revMinor="0"/);
    assert.match(written, /<Vehicle name="vehicle\.tesla\.model3"/);
    assert.match(written, /<AbsoluteTargetSpeed value="10"/);
    const over = await client.request<WriteResult>(ExportForCarlaRequest.method, { uri, outputPath: path.join(root, 'scenario.xosc') });
    assert.equal(over.written, null);
    assert.match(over.problems[0].message, /refusing to overwrite .*scenario\.xosc, the scenario being exported/);
    assert.equal(fs.readFileSync(path.join(root, 'scenario.xosc'), 'utf8'), FIXABLE);
  });
});

/** A vehicle written in the scenario: its name (the blueprint) and what its Properties hold. */
function vehicle(properties: string): string {
  return `<Vehicle name="vehicle.tesla.model3" vehicleCategory="car">
      <BoundingBox><Center x="1" y="0" z="1"/><Dimensions width="2" length="4" height="1.5"/></BoundingBox>
      <Performance maxSpeed="50" maxAcceleration="5" maxDeceleration="9"/>
      <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.7" positionX="2.9" positionZ="0.3"/>
      <RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.7" positionX="0" positionZ="0.3"/></Axles>
      ${properties}
    </Vehicle>`;
}

/** A 1.0 scenario on Town05 with two vehicles and no ego marked: the first is no ego by name, the second is. */
const NO_EGO = openScenarioFile(
  `  <CatalogLocations/>
  <RoadNetwork><LogicFile filepath="Town05"/></RoadNetwork>
  <Entities>
    <ScenarioObject name="adversary">${vehicle('<Properties/>')}</ScenarioObject>
    <ScenarioObject name="myEgoCar">${vehicle(`<Properties>
        <Property name="color" value="0,0,255"/>
        <File filepath="car.fbx"/>
      </Properties>`)}</ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions>
      <Private entityRef="adversary"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="20" offset="0"/></Position></TeleportAction></PrivateAction></Private>
      <Private entityRef="myEgoCar"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="5" offset="0"/></Position></TeleportAction></PrivateAction></Private>
    </Actions></Init>
    <StopTrigger/>
  </Storyboard>
`,
  fileHeader({ revMinor: '0', description: 'no ego' }),
);

describe('CARLA: no ego marked, the quick fix marks the vehicle Export for CARLA marks, as it marks it', function () {
  let client: TestClient;
  let root: string;

  before(async () => {
    root = temporaryWorkspace({
      'scenario.xosc': NO_EGO,
      'catalogued.xosc': FIXABLE.replace('revMinor="1"', 'revMinor="0"').replace('value="${$Speed / 3.6}"', 'value="10"'),
      'catalogs/VehicleCatalog.xosc': CATALOG,
      'marked/scenario.xosc': FIXABLE.replace('revMinor="1"', 'revMinor="0"').replace('value="${$Speed / 3.6}"', 'value="10"'),
      'marked/catalogs/VehicleCatalog.xosc': CATALOG.replace(
        '<Properties/>',
        '<Properties><Property name="type" value="ego_vehicle"/></Properties>',
      ),
    });
    client = await TestClient.start({ root, settings: { simulator: 'carla' } });
  });

  after(async () => {
    await client.stop();
  });

  const noEgoOf = async (uri: string): Promise<Diagnostic | undefined> =>
    (await client.diagnosticsOf(uri, (list) => list.length > 0)).find((diagnostic) =>
      /this scenario marks none/.test(String(diagnostic.message)),
    );

  it("offers one fix, Mark 'myEgoCar' as the ego, whose edit is the Property the export writes (before the File); after it, no warning", async () => {
    const file = path.join(root, 'scenario.xosc');
    const uri = await client.open(fileUri(file), NO_EGO);
    const noEgo = await noEgoOf(uri);
    assert.ok(noEgo, 'no warning that no ego is marked');
    assert.match(String(noEgo.message), /'myEgoCar' is the vehicle Export for CARLA marks/);
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri },
      range: noEgo.range,
      context: { diagnostics: [noEgo] },
    });
    const mark = actions.filter((action) => action.edit);
    assert.deepEqual(
      mark.map((action) => action.title),
      [`Mark 'myEgoCar' as the ego: <Property name="type" value="ego_vehicle"/>`],
    );
    assert.equal(mark[0].isPreferred, true);
    const fixed = applyEdits(NO_EGO, mark[0].edit?.changes?.[uri] ?? []);
    assert.match(
      fixed,
      /<Property name="color" value="0,0,255"\/>\n {8}<Property name="type" value="ego_vehicle"\/>\n {8}<File filepath="car.fbx"\/>/,
    );

    // The export of the scenario as it was marks the same vehicle with the same Property.
    const output = path.join(root, 'out', 'scenario.carla.xosc');
    fs.mkdirSync(path.dirname(output), { recursive: true });
    const result = await client.request<WriteResult>(ExportForCarlaRequest.method, { uri, outputPath: output });
    assert.equal(result.written, output, JSON.stringify(result.problems));
    const exported = fs.readFileSync(output, 'utf8');
    const egoObject = /<ScenarioObject name="myEgoCar">[\s\S]*?<\/ScenarioObject>/.exec(exported)?.[0] ?? '';
    assert.match(egoObject, /<Property name="type" value="ego_vehicle"\/>/);
    assert.equal(exported.split('value="ego_vehicle"').length, 2, 'one vehicle marked');

    await client.close(uri);
    const after = await client.open(uri, fixed);
    const diagnostics = await client.diagnosticsOf(
      after,
      (list) => !list.some((diagnostic) => /marks none/.test(String(diagnostic.message))),
    );
    assert.deepEqual(
      diagnostics.filter((diagnostic) => /marks none/.test(String(diagnostic.message))).map((diagnostic) => diagnostic.message),
      [],
    );
    await client.close(after);
  });

  it('a vehicle from a catalog: no edit here (the entry is shared), Export for CARLA still offered; marked in the entry, no warning', async () => {
    const catalogued = path.join(root, 'catalogued.xosc');
    const uri = await client.open(fileUri(catalogued), fs.readFileSync(catalogued, 'utf8'));
    const noEgo = await noEgoOf(uri);
    assert.ok(noEgo, 'no warning that no ego is marked');
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri },
      range: noEgo.range,
      context: { diagnostics: [noEgo] },
    });
    assert.deepEqual(
      actions.map((action) => action.title),
      ['Export for CARLA…'],
    );
    await client.close(uri);
    const marked = path.join(root, 'marked', 'scenario.xosc');
    const markedUri = await client.open(fileUri(marked), fs.readFileSync(marked, 'utf8'));
    const diagnostics = await client.diagnosticsOf(markedUri);
    assert.deepEqual(
      diagnostics.filter((diagnostic) => /marks none/.test(String(diagnostic.message))).map((diagnostic) => diagnostic.message),
      [],
    );
  });
});

describe('CARLA: a town that does not exist, as a user misspells it (Town5)', function () {
  const text = FIXABLE.replace('filepath="Town05"', 'filepath="Town5"');
  let client: TestClient;
  let root: string;
  let uri: string;

  before(async () => {
    root = temporaryWorkspace({ 'scenario.xosc': text, 'catalogs/VehicleCatalog.xosc': CATALOG });
    client = await TestClient.start({ root, settings: { simulator: 'carla' } });
    uri = await client.open(fileUri(path.join(root, 'scenario.xosc')), text);
  });

  after(async () => {
    await client.stop();
  });

  it('is an error naming the town meant, with the quick fix that writes it', async () => {
    const diagnostics = await client.diagnosticsOf(uri, (list) =>
      list.some((diagnostic) => /'Town5' is neither/.test(String(diagnostic.message))),
    );
    const town = diagnostics.find((diagnostic) =>
      /'Town5' is neither a CARLA town nor an \.xodr path; did you mean 'Town05'\?/.test(String(diagnostic.message)),
    );
    assert.ok(town, diagnostics.map((diagnostic) => String(diagnostic.message)).join('\n'));
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri },
      range: town.range,
      context: { diagnostics: [town] },
    });
    const write = actions.find((action) => action.title === "Write 'Town05'");
    assert.equal(write?.edit?.changes?.[uri]?.[0]?.newText, 'Town05', JSON.stringify(actions.map((action) => action.title)));
  });

  it('Export for CARLA is refused saying what to do in the editor too (it named only --road and --road-path), nothing written', async () => {
    const output = path.join(root, 'scenario.carla.xosc');
    const result = await client.request<WriteResult>(ExportForCarlaRequest.method, { uri, outputPath: output });
    assert.equal(result.written, null);
    const refusal = result.problems.find((problem) => problem.severity === 'error' && /names the road 'Town5'/.test(problem.message));
    assert.ok(refusal, JSON.stringify(result.problems, null, 1));
    assert.match(refusal.message, /did you mean the town 'Town05'\?/);
    // One error for one refusal: no second 'not exported: ...' at the file's first line (both were in the Problems view).
    assert.deepEqual(
      result.problems.filter((problem) => problem.severity === 'error' && /Town5/.test(problem.message)).map((problem) => problem.line),
      [text.split('\n').findIndex((line) => line.includes('filepath="Town5"'))],
    );
    assert.match(
      refusal.message,
      /write a CARLA town .* in the LogicFile, or add the folder .* \(--road-path DIR, the modular2simple\.esmini\.roadPath setting\)/,
    );
    assert.equal(fs.existsSync(output), false);
  });
});

describe('CARLA: a ParameterCondition ticked before the story action that sets its parameter (issue 26)', function () {
  let client: TestClient;
  let root: string;
  let uri: string;
  // esmini's lane_change.xosc: an event starts on 'gap' < 2, and a later event of the maneuver sets it.
  const text = parameterStoryScenario([
    storyAct('A', [
      settingEvent('Checks', parameterCondition('GapBelow', 'lessThan', '2')),
      settingEvent('Sets', afterASecond('SetsStarts'), 'gap'),
    ]),
  ]);

  before(async () => {
    root = temporaryWorkspace({ 'scenario.xosc': text });
    client = await TestClient.start({ root, settings: { simulator: 'carla' } });
    uri = await client.open(fileUri(path.join(root, 'scenario.xosc')), text);
  });

  after(async () => {
    await client.stop();
  });

  it('is an error at the condition, pointing at the action, with Export for CARLA as its fix', async () => {
    const pattern = /only the stories' ParameterActions set/;
    const diagnostics = await client.diagnosticsOf(uri, (list) => list.some((diagnostic) => pattern.test(String(diagnostic.message))));
    const found = diagnostics.filter((diagnostic) => problemCodeOf(diagnostic) === 'simulator' && pattern.test(String(diagnostic.message)));
    const lines = text.split('\n');
    const conditionLine = lines.findIndex((line) => line.includes('name="GapBelow"'));
    assert.deepEqual(
      found.map((diagnostic) => [
        diagnostic.severity,
        diagnostic.range.start.line,
        lines[conditionLine].slice(diagnostic.range.start.character, diagnostic.range.end.character),
      ]),
      [[DiagnosticSeverity.Error, conditionLine, 'gap']],
    );
    assert.deepEqual(
      found[0].relatedInformation?.map((related) => [related.location.uri, related.location.range.start.line, related.message]),
      [[uri, lines.findIndex((line) => line.includes('name="SetsAction"')), "this ParameterAction sets 'gap' in a story"]],
    );
    const actions = await client.request<CodeAction[]>('textDocument/codeAction', {
      textDocument: { uri },
      range: found[0].range,
      context: { diagnostics: [found[0]] },
    });
    const exportAction = actions.find((action) => action.command?.command === EXPORT_FOR_CARLA_COMMAND);
    assert.equal(exportAction?.title, 'Export for CARLA…');
  });
});

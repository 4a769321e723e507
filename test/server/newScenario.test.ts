import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { CompletionItem, ErrorCodes, ResponseError } from 'vscode-languageserver/node';
import { NewScenarioRequest, RunEsminiRequest } from '../../common/src/protocol';
import { newMainScenario } from '../../server/src/core/newScenario';
import { laneCenterT, laneSectionIndexAt, parseOpenDrive, roadPoint } from '../../server/src/core/opendrive/road';
import { SCHEMA_VERSIONS } from '../../server/src/core/schema/model';
import { schemaFindingWords } from '../../server/src/core/diagnostics/schemaFindings';
import { checkSchema } from '../../server/src/core/schema/validate';
import { parseXml } from '../../server/src/core/xml';
import { esminiBinary, esminiRoads, readEsminiCsv, requireEsmini } from '../support/esmini';
import { SIMPLE } from './fixtures/scenarios';
import { fileUri, useServer } from './harness';

const ROAD = 'fabriksgatan.xodr';

describe('language server: New Modular Scenario builds a main with an ego on a road network (JSON-RPC)', function () {
  this.timeout(120_000);
  // The road two folders up and across from the new scenario: the path written must reach it from there.
  const server = useServer(
    {
      [`roads/town/${ROAD}`]: fs.readFileSync(path.join(esminiRoads, ROAD)),
      'scenarios/README.txt': 'new scenarios go here\n',
      'other.xosc': '<OpenSCENARIO/>',
      'brake.xosc': SIMPLE,
    },
    'other.xosc',
    {
      schema: true,
    },
  );

  it('writes a schema-valid main, with no diagnostics, that esmini runs with the ego on the lane chosen', async function () {
    const scenario = path.join(server.root, 'scenarios', 'cut-in', 'main.xosc');
    const road = path.join(server.root, 'roads', 'town', ROAD);
    const result = await server.client.send(NewScenarioRequest, { scenario: fileUri(scenario), roadNetwork: fileUri(road) });
    assert.equal(result.roadFile, `../../roads/town/${ROAD}`);
    assert.ok(result.text.includes(`<LogicFile filepath="../../roads/town/${ROAD}"/>`), result.text);
    const network = parseOpenDrive(fs.readFileSync(road, 'utf8'));
    const egoRoad = network.byId.get(result.ego.roadId);
    assert.ok(egoRoad, `road ${result.ego.roadId} exists`);
    const section = egoRoad.laneSections[laneSectionIndexAt(egoRoad, result.ego.s)];
    assert.equal(section.lanes.find((lane) => lane.id === result.ego.laneId)?.type, 'driving');
    for (const element of ['<Vehicle ', '<Story ', '<Act ', '<ManeuverGroup ', '<StopTrigger>'])
      assert.ok(result.text.includes(element), element);
    assert.doesNotMatch(result.text, /Catalog(Reference|Location )/, 'no catalog needed');
    assert.deepEqual(
      checkSchema(parseXml(result.text), { modular: true }).findings.map((finding) => schemaFindingWords(finding).message),
      [],
    );

    fs.mkdirSync(path.dirname(scenario), { recursive: true });
    fs.writeFileSync(scenario, result.text);
    const uri = await server.client.openFile(scenario);
    assert.deepEqual(await server.client.diagnosticsOf(uri), []);

    // Ready to import groups: where the comment invites it, `<` offers the ScenarioReference snippets of the workspace's simple scenarios.
    const comment = result.text.indexOf('<!-- Import behaviours');
    const line = result.text.slice(0, comment).split('\n').length - 1;
    const character = comment - result.text.lastIndexOf('\n', comment - 1) - 1;
    await server.client.change(uri, [{ range: { start: { line, character }, end: { line, character } }, text: '<' }]);
    const offered = await server.client.request<CompletionItem[]>('textDocument/completion', {
      textDocument: { uri },
      position: { line, character: character + 1 },
    });
    assert.ok(
      offered.some((item) => /^ScenarioReference brake\.xosc Brake$/.test(item.label)),
      offered.map((item) => item.label).join(', '),
    );
    await server.client.change(uri, [{ range: { start: { line, character }, end: { line, character: character + 1 } }, text: '' }]);
    assert.deepEqual(await server.client.diagnosticsOf(uri), []);

    requireEsmini(this);
    const run = await server.client.send(RunEsminiRequest, { uri, esminiPath: esminiBinary, roadPath: [], duration: 2 });
    assert.equal(run.outcome, 'ok', `${run.message}\n${run.log}`);
    assert.deepEqual(
      run.problems.filter((problem) => problem.severity === 'error'),
      [],
      run.log,
    );
    assert.ok(run.csvFile);
    const [first] = readEsminiCsv(run.csvFile);
    const placed = first.positions.Ego;
    assert.ok(placed, `the ego is in esmini's log: ${Object.keys(first.positions).join(', ')}`);
    const sectionIndex = laneSectionIndexAt(egoRoad, result.ego.s);
    const expected = roadPoint(egoRoad, result.ego.s, laneCenterT(egoRoad, sectionIndex, result.ego.laneId, result.ego.s));
    assert.ok(
      Math.hypot(placed[0] - expected.x, placed[1] - expected.y) < 1,
      `ego at ${placed.join(', ')}, the lane's centre at ${expected.x}, ${expected.y}`,
    );
    await server.client.close(uri);
  });

  it('the main it writes is schema-valid in every version', function () {
    const ego = { roadId: '0', laneId: -1, s: 10 };
    for (const version of SCHEMA_VERSIONS) {
      const text = newMainScenario({ version, roadFile: 'road.xodr', ego });
      assert.match(text, new RegExp(`revMajor="1" revMinor="${version.split('.')[1]}"`));
      assert.deepEqual(
        checkSchema(parseXml(text), { modular: true }).findings.map((finding) => schemaFindingWords(finding).message),
        [],
        version,
      );
    }
  });

  it('refuses a road network that is missing or has no driving lane, saying which, as invalid parameters', async function () {
    const scenario = fileUri(path.join(server.root, 'scenarios', 'main.xosc'));
    const refused = async (roadNetwork: string, pattern: RegExp) => {
      const error = await server.client.send(NewScenarioRequest, { scenario, roadNetwork }).then(
        () => undefined,
        (failure: unknown) => failure,
      );
      assert.ok(error instanceof ResponseError, String(error));
      assert.equal(error.code, ErrorCodes.InvalidParams);
      assert.match(error.message, pattern);
    };
    await refused(fileUri(path.join(server.root, 'roads', 'none.xodr')), /none\.xodr does not exist/);
    await refused(fileUri(path.join(server.root, 'other.xosc')), /no place for the ego .*not an OpenDRIVE file/);
    fs.writeFileSync(
      path.join(server.root, 'roads', 'footway.xodr'),
      '<OpenDRIVE><road id="1" length="50" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="50"><line/></geometry></planView><lanes><laneSection s="0"><center><lane id="0" type="none"/></center><right><lane id="-1" type="sidewalk"><width sOffset="0" a="2" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road></OpenDRIVE>',
    );
    await refused(fileUri(path.join(server.root, 'roads', 'footway.xodr')), /none of its 1 roads has a driving lane/);
    await refused('relative/road.xodr', /no absolute file path/);
  });
});

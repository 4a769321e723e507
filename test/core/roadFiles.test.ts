import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { parseEsminiLoadedRoad } from '../../common/src/esminiCsv';
import { locateRoadFile, logicFileOf, roadFileCandidates, roadFolders } from '../../server/src/core/semantics/roadFiles';
import { Evaluator, semanticModelOf } from '../../server/src/core/semantics/model';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { readEsminiLog } from '../../server/src/esmini/log';
import { withRoadFile } from '../../server/src/esmini/run';
import { temporaryWorkspace } from '../support/workspace';

describe("road files: one resolver for Run in esmini and the bird's-eye view", () => {
  it('looks beside the scenario first (the path as written, then its file name), then in each road folder the same way', () => {
    assert.deepEqual(roadFileCandidates('../xodr/e6mini.xodr', '/ws/xosc', ['/roads', '/more']), [
      '/ws/xodr/e6mini.xodr',
      '/ws/xosc/e6mini.xodr',
      // The path as written from /roads (and from /more, the same place, once).
      '/xodr/e6mini.xodr',
      '/roads/e6mini.xodr',
      '/more/e6mini.xodr',
    ]);
    assert.deepEqual(roadFileCandidates('Town05', '/ws', ['/roads']), ['/ws/Town05', '/roads/Town05']);
    assert.deepEqual(roadFileCandidates('/abs/road.xodr', '/ws', ['/roads']), ['/abs/road.xodr', '/ws/road.xodr', '/roads/road.xodr']);
    assert.deepEqual(roadFileCandidates('..\\xodr\\e6mini.xodr', '/ws/xosc', []).slice(1), ['/ws/xosc/e6mini.xodr']);
    assert.deepEqual(roadFolders(['roads', '', 3, '/abs'], '/ws'), ['/ws/roads', '/abs']);
  });

  it('resolves to the first regular file, and lists what it looked at otherwise', async () => {
    const root = temporaryWorkspace({
      'xosc/e6mini.xodr': '<OpenDRIVE/>',
      'roads/xodr/e6mini.xodr': '<OpenDRIVE/>',
      'folder/e6mini.xodr/inside': '',
    });
    const store = new ScenarioStore({ root });
    const locate = (filepath: string, folder: string, folders: string[]) => {
      const document = parseXml(`<OpenSCENARIO><RoadNetwork><LogicFile filepath="${filepath}"/></RoadNetwork></OpenSCENARIO>`);
      return locateRoadFile(
        store,
        diskRef(path.join(root, folder, 'main.xosc')),
        document,
        new Evaluator(semanticModelOf(document)),
        folders,
      );
    };
    const found = await locate('../xodr/e6mini.xodr', 'xosc', [path.join(root, 'roads')]);
    assert.equal(found?.resolved, path.join(root, 'xosc', 'e6mini.xodr'));
    const folderOnly = await locate('e6mini.xodr', 'folder', []);
    assert.equal(folderOnly?.resolved, undefined, 'a folder of that name is no road file');
    assert.deepEqual(folderOnly?.candidates, [path.join(root, 'folder', 'e6mini.xodr')]);
  });

  it('reads the LogicFile with its parameters evaluated, and hands esmini the resolved path in its place', () => {
    const text =
      '<OpenSCENARIO><ParameterDeclarations><ParameterDeclaration name="Road" parameterType="string" value="../xodr/e6mini.xodr"/></ParameterDeclarations><RoadNetwork><LogicFile filepath="$Road"/></RoadNetwork></OpenSCENARIO>';
    assert.equal(logicFileOf(parseXml(text))?.filepath, '../xodr/e6mini.xodr');
    assert.equal(logicFileOf(parseXml('<OpenSCENARIO><RoadNetwork/></OpenSCENARIO>')), undefined);
    assert.equal(withRoadFile(text, '/a & b/e6mini.xodr'), text.replace('"$Road"', '"/a &amp; b/e6mini.xodr"'));
    assert.equal(withRoadFile('<OpenSCENARIO/>', '/x.xodr'), '<OpenSCENARIO/>');
  });

  it("keeps esmini's remarks about its own files apart from what may concern the scenario, and reads which road it loaded", () => {
    const log = [
      '[] [error] Unsupported geo reference attr: +no_defs',
      '[] [info] Loaded OpenDRIVE: /ws/xodr/e6mini.xodr',
      '[] [error] Unsupported object type: rail-pole - interpret as NONE',
      '[] [error] Unsupported object type: rail-pole - interpret as NONE',
      '[] [warn] scene graph file ../models/e6mini.osgb not located, using specified file path',
      '[] [warn] 3D model car_white.osgb not located, using specified file path',
      '[1.500] [warn] Stopping object walker Walk on conflicting Longitudinal domain(s)',
    ].join('\n');
    const { messages, remarks } = readEsminiLog(log);
    assert.deepEqual(
      messages.map((message) => message.text),
      ['Stopping object walker Walk on conflicting Longitudinal domain(s)'],
    );
    assert.deepEqual(
      remarks.map((remark) => [remark.text, remark.count, remark.level]),
      [
        ['Unsupported geo reference attr: +no_defs', 1, 'error'],
        ['Unsupported object type: rail-pole - interpret as NONE', 2, 'error'],
        ['scene graph file ../models/e6mini.osgb not located, using specified file path', 1, 'warn'],
        ['3D model car_white.osgb not located, using specified file path', 1, 'warn'],
      ],
    );
    for (const remark of remarks) assert.match(remark.origin, /\.cpp:\d+ /);
    assert.equal(parseEsminiLoadedRoad(log), '/ws/xodr/e6mini.xodr');
    assert.equal(parseEsminiLoadedRoad('[] [warn] No OpenDRIVE file specified, continue without'), undefined);
  });
});

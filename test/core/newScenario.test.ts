import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { egoPlacement, newMainScenario } from '../../server/src/core/newScenario';
import { isDrivingLane, laneById, laneSectionIndexAt, laneWidth, parseOpenDrive } from '../../server/src/core/opendrive/road';
import { attributeValue, firstDescendant, parseXml } from '../../server/src/core/xml';
import { esminiXodrDir } from '../support/esminiBinaries';

describe('core: the main New Modular Scenario writes, and where it puts the ego', () => {
  it('places the ego on a driving lane at least a car wide, inside the road, on every esmini road network', function () {
    if (!fs.existsSync(esminiXodrDir)) this.skip();
    const files = fs.readdirSync(esminiXodrDir).filter((file) => file.endsWith('.xodr'));
    assert.ok(files.length > 10, `only ${files.length} road networks`);
    for (const file of files) {
      const network = parseOpenDrive(fs.readFileSync(path.join(esminiXodrDir, file), 'utf8'));
      const ego = egoPlacement(network);
      assert.ok(ego, file);
      const road = network.byId.get(ego.roadId);
      assert.ok(road && ego.s > 0 && ego.s < road.length, `${file}: s ${ego.s}`);
      const section = road.laneSections[laneSectionIndexAt(road, ego.s)];
      const lane = laneById(section, ego.laneId);
      assert.ok(lane && isDrivingLane(lane) && laneWidth(section, lane, ego.s) >= 1, `${file}: lane ${ego.laneId}`);
      // The right-hand side first: a driving lane -1 is taken when there is one.
      if (laneById(section, -1)?.type === 'driving') assert.equal(ego.laneId, -1, file);
    }
  });

  it('has no place for the ego on a network without a driving lane', () => {
    assert.equal(egoPlacement(parseOpenDrive('<OpenDRIVE/>')), undefined);
  });

  it('writes the road path and ids escaped, as read back', () => {
    const text = newMainScenario({ version: '1.2', roadFile: '../roads/a&b "x".xodr', ego: { roadId: '<1>', laneId: -2, s: 12.5 } });
    const root = parseXml(text).root;
    assert.ok(root);
    const logicFile = firstDescendant(root, 'LogicFile');
    const position = firstDescendant(root, 'LanePosition');
    assert.ok(logicFile && position);
    assert.equal(attributeValue(logicFile, 'filepath'), '../roads/a&b "x".xodr');
    assert.deepEqual(
      ['roadId', 'laneId', 's'].map((name) => attributeValue(position, name)),
      ['<1>', '-2', '12.5'],
    );
  });
});

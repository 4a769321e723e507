import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { LibraryModule, readModule } from '../../server/src/core/library';
import { entityOffers, exampleSpeedDifference, newEntityChanges, TextChange, TrafficRules } from '../../server/src/core/libraryEntities';
import { insertModuleGroup } from '../../server/src/core/libraryInsert';
import { newMainScenario } from '../../server/src/core/newScenario';
import { parseXml } from '../../server/src/core/xml';
import { checkCleanAndFlatten } from '../support/cliChecks';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const library = { folder: path.join(repoRoot, 'library'), label: 'built-in' };

function builtIn(name: string): { module: LibraryModule; example: string } {
  const file = path.join(library.folder, `${name}.xosc`);
  const { module } = readModule(fs.readFileSync(file, 'utf8'), file, library);
  assert.ok(module);
  return { module, example: fs.readFileSync(path.join(library.folder, 'examples', `${name}.xosc`), 'utf8') };
}

const newMain = () => newMainScenario({ version: '1.3', roadFile: 'road.xodr', ego: { roadId: '0', laneId: -1, s: 10 } });

function applied(text: string, changes: TextChange[]): string {
  return [...changes]
    .sort((a, b) => b.start - a.start)
    .reduce((result, change) => result.slice(0, change.start) + change.text + result.slice(change.end), text);
}

/** Issue 28: a module's actor added to a main as its example main declares and places it (core/libraryEntities). */
describe('Insert into main: a new entity as the example has it (core/libraryEntities)', () => {
  it('offers each role the example declares and places, under a name no entity of the main has, case aside', () => {
    const { module, example } = builtIn('cut-in');
    assert.deepEqual(entityOffers(module, example, ['Ego']), [
      { role: 'adversary', name: 'adversary' },
      { role: 'ego', name: 'ego2' },
    ]);
    assert.deepEqual(
      entityOffers(module, example, ['Adversary', 'adversary2']).map((offer) => offer.name),
      ['adversary3', 'ego'],
    );
    // An example without the role's entity offers nothing for it.
    assert.deepEqual(entityOffers(module, example.replace(/"adversary"/g, '"other"'), []), [{ role: 'ego', name: 'ego' }]);
  });

  it('keeps a main indented with tabs in tabs, and a self-closing Entities and Actions are opened; the result is well-formed', () => {
    const { module, example } = builtIn('lead-brake');
    const text = newMain()
      .replace(/<Entities>[\s\S]*<\/Entities>/, '<Entities/>')
      .replace(/<Actions>[\s\S]*<\/Actions>/, '<Actions/>');
    assert.throws(
      () => newEntityChanges(text, module, example, { lead: 'lead' }, { lead: 'lead', ego: 'Ego' }),
      /the main's Init does not place Ego: 'lead' is placed relative to it as in the example of lead-brake; place Ego first/,
    );
    // With no player for the ego, nothing to place it relative to: the example's placement is written as it is.
    const result = applied(text, newEntityChanges(text, module, example, { lead: 'lead' }, { lead: 'lead' }).changes);
    assert.deepEqual(parseXml(result).problems, []);
    assert.match(result, /\t<Entities>\n\t\t<ScenarioObject name="lead">\n\t\t\t<Vehicle name="vehicle\.audi\.tt"/);
    assert.match(result, /\t\t\t<Actions>\n\t\t\t\t<Private entityRef="lead">[\s\S]*<LanePosition roadId="0" laneId="-1" s="84.5"/);
  });

  it('says what to do, and changes nothing, where the main cannot take the new entity', () => {
    const { module, example } = builtIn('cut-in');
    const players = { adversary: 'adversary', ego: 'Ego' };
    const create = { adversary: 'adversary' };
    const refused: [string, string, RegExp][] = [
      ['no Storyboard', newMain().replace(/<Storyboard>[\s\S]*<\/Storyboard>/, ''), /the main has no Storyboard \(with an Init\)/],
      [
        'no Init',
        newMain().replace(/<Init>[\s\S]*<\/Init>/, ''),
        /has no Init with Actions to place a new entity in: add <Init><Actions\/><\/Init>/,
      ],
      ['no Entities', newMain().replace(/<Entities>[\s\S]*<\/Entities>/, ''), /the main has no Entities/],
      [
        'a name taken',
        newMain().replace(/"Ego"/g, '"ADVERSARY"'),
        /already declares an entity 'adversary': name the new one otherwise \(adversary2\)/,
      ],
      ['not well-formed', newMain().replace('</Entities>', ''), /not well-formed/],
    ];
    for (const [what, text, message] of refused)
      assert.throws(() => newEntityChanges(text, module, example, create, players), message, what);
    assert.throws(
      () => newEntityChanges(newMain(), module, example.replace(/"adversary"/g, '"other"'), create, players),
      /the example main of cut-in declares and places no entity 'adversary' to copy: pick an entity of the main to play it/,
    );
    // Behind the road's start: the lead-brake's lead would stand 34.5 m behind an ego at s 10 if the example had it behind.
    const behind = builtIn('lead-brake');
    assert.throws(
      () =>
        newEntityChanges(
          newMain(),
          behind.module,
          behind.example.replace('s="84.5"', 's="5"'),
          { lead: 'lead' },
          { lead: 'lead', ego: 'Ego' },
        ),
      /'lead' would stand at s -35, before the start of road 0 \(45 m behind Ego as in the example\): move Ego further along the road first/,
    );
  });

  it("an ego on the other side of the road from the example's: the placement turned half round, lanes counted the other way and ahead against s", () => {
    const onTheLeft = newMain().replace('laneId="-1"', 'laneId="1"').replace('s="10"', 's="500"');
    const place = (name: string, role: string) => {
      const { module, example } = builtIn(name);
      const result = newEntityChanges(onTheLeft, module, example, { [role]: role }, { [role]: role, ego: 'Ego' });
      return { text: applied(onTheLeft, result.changes), added: result.added };
    };
    // cut-in's example: the ego on lane -1 at s 50, the car on lane -2 (right of it) at s 85; here the ego on lane 1 at s 500.
    const cutIn = place('cut-in', 'adversary');
    assert.match(cutIn.text, /<Private entityRef="adversary">[\s\S]*?<LanePosition roadId="0" laneId="2" s="465"/);
    assert.deepEqual(cutIn.added, [
      "adversary (Vehicle, 35 m ahead of Ego, lane 2 (the example's placement turned round: Ego drives against the road's s, the example's ego along it), 7 m/s)",
    ]);
    // Across the centre: oncoming-vehicle's car on lane 1 at s 300, 250 m ahead of an ego on lane -1: here on lane -1, at s 250.
    assert.match(
      place('oncoming-vehicle', 'oncoming').text,
      /<Private entityRef="oncoming">[\s\S]*?<LanePosition roadId="0" laneId="-1" s="250"/,
    );
    // The pedestrian on the sidewalk (lane -4, three lanes right of the ego's, 0.75 m towards the road): lane 4, its offset
    // negated, as esmini adds it along the road's t on either side.
    assert.match(
      place('pedestrian-crossing', 'pedestrian').text,
      /<Private entityRef="pedestrian">[\s\S]*?<LanePosition roadId="0" laneId="4" s="420" offset="-0.75"/,
    );
    // An offset from the lane's centre that esmini takes along the road's t: the swerve's key is negated, to stay a swerve left.
    const swerving = builtIn('swerving-lead');
    const swerve = newEntityChanges(onTheLeft, swerving.module, swerving.example, { lead: 'lead' }, { lead: 'lead' });
    assert.deepEqual(swerve.values, { 'AbsoluteTargetLaneOffset.value': '-1.5' });
    assert.deepEqual(newEntityChanges(newMain(), swerving.module, swerving.example, { lead: 'lead' }, { lead: 'lead' }).values, {});
    // Ahead against s runs towards the road's start.
    const { module, example } = builtIn('lead-brake');
    assert.throws(
      () => newEntityChanges(onTheLeft.replace('s="500"', 's="20"'), module, example, { lead: 'lead' }, { lead: 'lead', ego: 'Ego' }),
      /'lead' would stand at s -14.5, before the start of road 0 \(34.5 m ahead of Ego as in the example, Ego driving against the road's s on lane 1\): move Ego further from the road's start first/,
    );
  });

  it('a main road of left-hand traffic: the placement mirrored (lanes on the other side, along s on the positive lanes), and the sides of lane changes and offsets swapped', () => {
    // Road 0 of the main's road file is rule="LHT": its lane 1 is driven along s, its lane -1 against it.
    const leftHand = { main: new Set(['0']) };
    const onLane1 = newMain().replace('laneId="-1"', 'laneId="1"').replace('s="10"', 's="500"');
    const place = (text: string, name: string, role: string, rules: TrafficRules = leftHand) => {
      const { module, example } = builtIn(name);
      const result = newEntityChanges(text, module, example, { [role]: role }, { [role]: role, ego: 'Ego' }, undefined, rules);
      return { text: applied(text, result.changes), added: result.added, values: result.values, changes: result.changes };
    };
    // cut-in's example: the ego on lane -1 at s 50, the car 35 m ahead on lane -2, on its right (the slower lane). Here the
    // ego drives along s on lane 1: the car 35 m ahead on lane 2, on its left (the slower lane there), cutting in from it.
    const cutIn = place(onLane1, 'cut-in', 'adversary');
    assert.match(cutIn.text, /<Private entityRef="adversary">[\s\S]*?<LanePosition roadId="0" laneId="2" s="535"/);
    assert.deepEqual(cutIn.added, [
      "adversary (Vehicle, 35 m ahead of Ego, lane 2 (the example's placement mirrored: road 0 is of left-hand traffic, the example's of right-hand), 7 m/s)",
    ]);
    // Unread rules (no road file found): right-hand traffic, OpenDRIVE's default, as before: turned half round.
    assert.match(place(onLane1, 'cut-in', 'adversary', {}).text, /<LanePosition roadId="0" laneId="2" s="465"/);
    // The oncoming car on the lane of the other direction: lane -1, driven against s there.
    assert.match(
      place(onLane1, 'oncoming-vehicle', 'oncoming').text,
      /<Private entityRef="oncoming">[\s\S]*?<LanePosition roadId="0" laneId="-1" s="750"/,
    );
    // The pedestrian on the sidewalk of the ego's side (lane 4), 0.75 m towards the road, facing the road (its heading
    // relative to the lane's direction mirrored).
    assert.match(
      place(onLane1, 'pedestrian-crossing', 'pedestrian').text,
      /<Private entityRef="pedestrian">[\s\S]*?<LanePosition roadId="0" laneId="4" s="580" offset="-0.75">\s*<Orientation type="relative" h="-1.571"/,
    );
    // The overtaking car passes on the right, towards the centre line, and the lane-changing car moves to the right.
    assert.deepEqual(place(onLane1, 'overtaking', 'overtaker').values, {
      'RelativeTargetLane.value': '-1',
      'AbsoluteTargetSpeed.value': '17',
    });
    assert.deepEqual(place(onLane1, 'cut-out', 'lead').values, { 'RelativeTargetLane.value': '1' });
    // The swerve (1.5 m left of the lane's centre, towards the centre line) goes 1.5 m right along the road's t, still towards it.
    assert.deepEqual(place(onLane1, 'swerving-lead', 'lead').values, { 'AbsoluteTargetLaneOffset.value': '-1.5' });
    // On lane -1 of that road the ego drives against s: mirrored and turned, the lanes count as in the example, ahead against s.
    const onLaneMinus1 = newMain().replace('s="10"', 's="500"');
    assert.match(
      place(onLaneMinus1, 'cut-in', 'adversary').text,
      /<Private entityRef="adversary">[\s\S]*?<LanePosition roadId="0" laneId="-2" s="465"/,
    );
    assert.deepEqual(place(onLaneMinus1, 'swerving-lead', 'lead').values, {});
    assert.deepEqual(place(onLaneMinus1, 'lane-change', 'adversary').values, { 'RelativeTargetLane.value': '-1' });
    assert.match(
      place(onLaneMinus1, 'pedestrian-crossing', 'pedestrian').text,
      /<LanePosition roadId="0" laneId="-4" s="420" offset="0.75">\s*<Orientation type="relative" h="-1.571"/,
    );
    // An entity of the main already plays the actor (nothing is added): the keys meaning a side are written for the road
    // all the same, the overtaking car passing on the right.
    const overtaking = builtIn('overtaking');
    const withOvertaker = applied(onLane1, place(onLane1, 'overtaking', 'overtaker').changes);
    const existing = (rules: TrafficRules) =>
      newEntityChanges(
        withOvertaker,
        overtaking.module,
        overtaking.example,
        {},
        { overtaker: 'overtaker', ego: 'Ego', egoGap: 'Ego', egoLane: 'Ego', self: 'overtaker' },
        undefined,
        rules,
      );
    assert.deepEqual(existing(leftHand), { changes: [], values: { 'RelativeTargetLane.value': '-1' }, added: [] });
    // On a road of right-hand traffic the same main's ego drives against s: turned, no side swapped.
    assert.deepEqual(existing({}).values, {});
    // A module whose example is on a road of left-hand traffic (a user's: its ego on lane 1, along s, the car on lane 2, on
    // its left), inserted into a main of right-hand traffic: mirrored too, the car on the ego's right.
    const userCutIn = builtIn('cut-in');
    const leftHandExample = userCutIn.example.replace('laneId="-1"', 'laneId="1"').replace('laneId="-2"', 'laneId="2"');
    const onRight = newMain();
    const fromLeftHand = newEntityChanges(
      onRight,
      userCutIn.module,
      leftHandExample,
      { adversary: 'adversary' },
      { adversary: 'adversary', ego: 'Ego' },
      undefined,
      {
        example: new Set(['0']),
      },
    );
    assert.match(
      applied(onRight, fromLeftHand.changes),
      /<Private entityRef="adversary">[\s\S]*?<LanePosition roadId="0" laneId="-2" s="45"/,
    );
    assert.match(fromLeftHand.added[0], /mirrored: road 0 is of right-hand traffic, the example's of left-hand/);
  });

  it('a lane across the centre keeps its count from the ego (lane ids skip 0), and a parameter gives the ego its place', () => {
    const { module, example } = builtIn('oncoming-vehicle');
    const text = newMain()
      .replace(
        '<ParameterDeclaration name="EgoSpeed"',
        '<ParameterDeclaration name="EgoS" parameterType="double" value="60"/>\n\t\t<ParameterDeclaration name="EgoSpeed"',
      )
      .replace('s="10"', 's="$EgoS"');
    const result = applied(
      text,
      newEntityChanges(text, module, example, { oncoming: 'oncoming' }, { oncoming: 'oncoming', ego: 'Ego' }).changes,
    );
    // The example: ego on lane -1 at s 50, the oncoming car on lane 1 at s 300; here the ego at s 60.
    assert.match(result, /<Private entityRef="oncoming">[\s\S]*?<LanePosition roadId="0" laneId="1" s="310"/);
  });

  it("a module whose keys name no ego stands to the main's ego as to the example's; one the main's slower ego would leave standing says so", () => {
    const swerving = builtIn('swerving-lead');
    assert.ok(!swerving.module.parameters.some((parameter) => parameter.defaultValue === 'ego'), 'swerving-lead names no ego');
    const text = newMain();
    const lead = newEntityChanges(text, swerving.module, swerving.example, { lead: 'lead' }, { lead: 'lead' });
    // Its example: the ego at s 50, the lead 30 m ahead, both at 15 m/s; this ego at s 10 and $EgoSpeed (10).
    assert.match(
      applied(text, lead.changes),
      /<Private entityRef="lead">[\s\S]*?<LanePosition roadId="0" laneId="-1" s="40"[\s\S]*?<AbsoluteTargetSpeed value="10"\/>/,
    );
    assert.deepEqual(lead.added, ['lead (Vehicle, 30 m ahead of Ego, lane -1, 10 m/s)']);
    const jam = builtIn('traffic-jam-end');
    const queue = newEntityChanges(text, jam.module, jam.example, { jam1: 'jam1' }, { jam1: 'jam1', ego: 'Ego' });
    assert.match(
      queue.added[0],
      /^jam1 \(Vehicle, 130 m ahead of Ego, lane -1, 0 m\/s \(standing: the example's ego drives 25 m\/s, Ego 10; a faster Ego gives the example's closing speed\)\)$/,
    );
  });

  it("a slower car in the ego's lane inserted after a car that enters that lane ahead of the ego goes behind it, no faster: a scripted car never brakes for the one ahead", () => {
    const cutIn = builtIn('cut-in');
    const lead = builtIn('lead-brake');
    assert.equal(cutIn.module.queue, 'enters');
    assert.equal(lead.module.queue, 'slower');
    const entering = new Set(['cut-in']);
    /** The main with a cut-in inserted (its car `adversary` at `s` on lane -2, at `speed`), then a lead brake; the lead's place and what it says. */
    const composed = (s: number, speed: number, set: ReadonlySet<string> | undefined = entering) => {
      let text = newMain();
      const car = newEntityChanges(text, cutIn.module, cutIn.example, { adversary: 'adversary' }, { adversary: 'adversary', ego: 'Ego' });
      text = applied(text, car.changes)
        .replace('laneId="-2" s="45"', `laneId="-2" s="${s}"`)
        .replace('<AbsoluteTargetSpeed value="7"/>', `<AbsoluteTargetSpeed value="${speed}"/>`);
      const group = insertModuleGroup(text, cutIn.module, { players: { adversary: 'adversary', ego: 'Ego' }, values: car.values });
      text = text.slice(0, group.offset) + group.text + text.slice(group.offset);
      const result = newEntityChanges(
        text,
        lead.module,
        lead.example,
        { lead: 'lead' },
        { lead: 'lead', ego: 'Ego' },
        undefined,
        undefined,
        set,
      );
      const placed =
        /<Private entityRef="lead">[\s\S]*?<LanePosition roadId="0" laneId="(-?\d+)" s="([\d.]+)"[\s\S]*?<AbsoluteTargetSpeed value="([^"]+)"\/>/.exec(
          applied(text, result.changes),
        );
      return { placed: placed?.slice(1), added: result.added };
    };
    // The example's lead: 34.5 m ahead of its ego, 2 m/s slower (16 and 14 m/s); the cut-in's car here 35 m ahead at 7 m/s.
    const behind = composed(45, 7);
    assert.deepEqual(behind.placed, ['-1', '44.5', '5']);
    assert.deepEqual(behind.added, [
      'lead (Vehicle, 34.5 m ahead of Ego, lane -1, 5 m/s (behind adversary, which enters the lane of Ego ahead of it: 2 m/s slower, so that adversary cuts in ahead of it and never runs into it))',
    ]);
    // A cut-in car nearer than the example's lead: the lead level with it, not ahead.
    assert.deepEqual(composed(30, 7).placed, ['-1', '30', '5']);
    // One that is slower than the lead would be 2 m/s below it: no faster than it (standing behind a standing one).
    assert.deepEqual(composed(45, 1).placed, ['-1', '44.5', '0']);
    // No module known to enter the lane (a library without the field): placed as if alone, 2 m/s slower than the ego.
    assert.deepEqual(composed(45, 7, new Set()).placed, ['-1', '44.5', '8']);
    // A car that enters the lane behind the ego is no member: the lead as if alone.
    assert.deepEqual(composed(5, 7).placed, ['-1', '44.5', '8']);
  });

  it("a car that enters the ego's lane inserted after slower cars ahead in it moves them behind it, no faster: the places the other order gives", () => {
    const cutIn = builtIn('cut-in');
    const entering = new Set(['cut-in']);
    // Each slower module's example difference to its follower: lead-brake's lead 2 m/s below its ego, slow-target's 4.
    const slower = new Map(
      ['lead-brake', 'slow-target'].map((name) => [name, exampleSpeedDifference(builtIn(name).module, builtIn(name).example) ?? NaN]),
    );
    assert.deepEqual([...slower.values()], [2, 4]);
    /** A new main with `first` inserted (its new actor `name`, its Init `s` and speed and its speed key set where given), then a cut-in. */
    const composed = (
      first: string,
      name: string,
      set: ReadonlyMap<string, number> = slower,
      at?: { s: string; speed: string },
      key?: string,
    ) => {
      const module = builtIn(first);
      let text = newMain();
      const players = { [name]: name, ego: 'Ego' };
      const car = newEntityChanges(text, module.module, module.example, { [name]: name }, players, undefined, undefined, entering, set);
      text = applied(text, car.changes);
      if (at)
        text = text.replace(
          new RegExp(`(<Private entityRef="${name}">[\\s\\S]*?s=")[^"]+("[\\s\\S]*?<AbsoluteTargetSpeed value=")[^"]+"`),
          `$1${at.s}$2${at.speed}"`,
        );
      const values = key === undefined ? car.values : { ...car.values, 'AbsoluteTargetSpeed.value': key };
      const group = insertModuleGroup(text, module.module, { players, values });
      text = text.slice(0, group.offset) + group.text + text.slice(group.offset);
      const result = newEntityChanges(
        text,
        cutIn.module,
        cutIn.example,
        { adversary: 'adversary' },
        { adversary: 'adversary', ego: 'Ego' },
        undefined,
        undefined,
        entering,
        set,
      );
      const after = applied(text, result.changes);
      const places = [
        ...after.matchAll(
          /<Private entityRef="([^"]+)">[\s\S]*?<LanePosition roadId="0" laneId="(-?\d+)" s="([\d.]+)"[\s\S]*?<AbsoluteTargetSpeed value="([^"]+)"\/>/g,
        ),
      ].map((match) => match.slice(1).join(' '));
      const speedKey = /<ParameterReference key="AbsoluteTargetSpeed.value" value="([^"]+)"\/>/.exec(after)?.[1];
      return { places, added: result.added, key: speedKey };
    };
    // The lead as if alone (34.5 m ahead, 8 m/s: 2 slower than the ego), then the cut-in's car 35 m ahead at 7 m/s: the lead
    // keeps its 2 m/s to its follower from that car, 5 m/s, as a lead inserted after the cut-in is placed (44.5 m, 5 m/s).
    const lead = composed('lead-brake', 'lead');
    assert.deepEqual(lead.places, ['Ego -1 10 $EgoSpeed', 'lead -1 44.5 5', 'adversary -2 45 7']);
    assert.deepEqual(lead.added, [
      'adversary (Vehicle, 35 m ahead of Ego, lane -2, 7 m/s (lead moved behind it: 5 m/s, was 8, so that adversary cuts in ahead of it and lead never runs into it))',
    ]);
    // Its braking's speed key (0, to a stop) is no speed of its Init: unchanged.
    assert.equal(lead.key, '0');
    // A lead further ahead than the cut-in's car: level with it, not ahead.
    assert.deepEqual(composed('lead-brake', 'lead', slower, { s: '70', speed: '8' }).places[1], 'lead -1 45 5');
    // A slow target 100 m ahead at 6 m/s (its example: 14 and 10 m/s): level with the car, 3 m/s, as the other order places
    // it; its speed key (0: standing from the start) is no speed of its Init: unchanged.
    const target = composed('slow-target', 'target');
    assert.deepEqual(target.places.slice(1), ['target -1 45 3', 'adversary -2 45 7']);
    assert.equal(target.key, '0');
    // Keyed to drive on at its Init speed, the key moves with it, else the group would set the old speed again at once.
    assert.equal(composed('slow-target', 'target', slower, undefined, '6').key, '3');
    // Already slower than that, or behind the ego: left where it is.
    assert.deepEqual(composed('lead-brake', 'lead', slower, { s: '44.5', speed: '1' }).places[1], 'lead -1 44.5 1');
    assert.deepEqual(composed('lead-brake', 'lead', slower, { s: '5', speed: '8' }).places[1], 'lead -1 5 8');
    // No module known to drive slower in the lane (a library without the field): the lead as if alone.
    assert.deepEqual(composed('lead-brake', 'lead', new Map()).places[1], 'lead -1 44.5 8');
    // Already behind a cut-in's car (as that order places it), a second cut-in leaves it there.
    assert.deepEqual(composed('lead-brake', 'lead', slower, { s: '44.5', speed: '5' }).places[1], 'lead -1 44.5 5');
  });

  it("a doc block's queue field is 'enters' or 'slower'; another value is reported on its line and the module left out", () => {
    const file = path.join(library.folder, 'cut-in.xosc');
    const text = fs.readFileSync(file, 'utf8').replace('queue: enters', 'queue: ahead');
    const { module, problems } = readModule(text, file, library);
    assert.equal(module, undefined);
    assert.deepEqual(
      problems.map((problem) => [problem.line, problem.message]),
      [
        [
          8,
          "'queue: ahead' is neither 'enters' (the actor enters the ego's lane ahead of it) nor 'slower' (it drives slower ahead in that lane)",
        ],
      ],
    );
  });

  it("a new entity that the example writes as a catalog reference brings the example's catalog location, rebased to the main's folder: the main checks clean", async () => {
    const { module, example } = builtIn('cut-in');
    const work = temporaryFolder('m2s-entities-');
    const vehicle = /<Vehicle name="vehicle\.audi\.tt"[\s\S]*?<\/Vehicle>/.exec(example)?.[0] ?? '';
    assert.ok(vehicle);
    // A user's library: the example's adversary is an entry of a vehicle catalog beside the library's examples.
    fs.mkdirSync(path.join(work, 'lib', 'Catalogs', 'Vehicles'), { recursive: true });
    fs.mkdirSync(path.join(work, 'lib', 'examples'));
    fs.mkdirSync(path.join(work, 'scenarios'));
    fs.writeFileSync(
      path.join(work, 'lib', 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'),
      `<?xml version="1.0" encoding="UTF-8"?>\n<OpenSCENARIO>\n  <FileHeader revMajor="1" revMinor="1" date="2026-11-29T00:00:00" description="cars" author="test"/>\n  <Catalog name="VehicleCatalog">\n    ${vehicle.replace('name="vehicle.audi.tt"', 'name="car_red"')}\n  </Catalog>\n</OpenSCENARIO>\n`,
    );
    const exampleFile = path.join(work, 'lib', 'examples', 'cut-in.xosc');
    const withCatalog = example
      .replace(
        '<CatalogLocations/>',
        '<CatalogLocations>\n    <VehicleCatalog>\n      <Directory path="../Catalogs/Vehicles"/>\n    </VehicleCatalog>\n  </CatalogLocations>',
      )
      .replace(vehicle, '<CatalogReference catalogName="VehicleCatalog" entryName="car_red"/>');
    fs.writeFileSync(exampleFile, withCatalog);
    const mainFile = path.join(work, 'scenarios', 'main.xosc');
    const text = newMainScenario({
      version: '1.3',
      roadFile: path.join(library.folder, 'roads', 'straight_1000m.xodr'),
      ego: { roadId: '0', laneId: -1, s: 10 },
    });
    const players = { adversary: 'adversary', ego: 'Ego' };
    const entities = newEntityChanges(text, module, withCatalog, { adversary: 'adversary' }, players, {
      main: mainFile,
      example: exampleFile,
    });
    const result = applied(text, entities.changes);
    assert.match(
      result,
      /<CatalogLocations>\n\t\t<VehicleCatalog>\n\t\t\t<Directory path="\.\.\/lib\/Catalogs\/Vehicles"\/>\n\t\t<\/VehicleCatalog>\n\t<\/CatalogLocations>/,
    );
    assert.match(
      result,
      /<ScenarioObject name="adversary">\s*<CatalogReference catalogName="VehicleCatalog" entryName="car_red"\/>\s*<\/ScenarioObject>/,
    );
    fs.writeFileSync(mainFile, result);
    await checkCleanAndFlatten(mainFile, path.join(work, 'flat.xosc'));
    // A main that locates its vehicle catalog already keeps its own.
    const own = text.replace(
      '<CatalogLocations/>',
      '<CatalogLocations>\n\t\t<VehicleCatalog>\n\t\t\t<Directory path="cars"/>\n\t\t</VehicleCatalog>\n\t</CatalogLocations>',
    );
    const kept = applied(
      own,
      newEntityChanges(own, module, withCatalog, { adversary: 'adversary' }, players, { main: mainFile, example: exampleFile }).changes,
    );
    assert.equal((kept.match(/<VehicleCatalog>/g) ?? []).length, 1);
    assert.match(kept, /<Directory path="cars"\/>/);
  });
});

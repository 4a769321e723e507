import { strict as assert } from 'node:assert';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { main } from '../../server/src/cli';
import { LibraryModule, listLibraries } from '../../server/src/core/library';
import { entityOffers, newEntityChanges } from '../../server/src/core/libraryEntities';
import { guessPlayer, insertModuleGroup, mainShape, moduleRoles } from '../../server/src/core/libraryInsert';
import { newMainScenario } from '../../server/src/core/newScenario';
import { openDriveSignals } from '../../server/src/core/opendrive/road';
import { nodeFileSystem } from '../../server/src/core/sources';
import { builtInLibraryFolder, libraryFolders } from '../../server/src/libraries';
import { harnessVerdicts, requireCarlaHarness } from '../support/carla';
import { runExample } from '../../scripts/library-pictures';
import { esminiBinary, requireEsmini } from '../support/esmini';
import { recordedEnvironments } from '../support/esminiDat';
import {
  arrivesStaysLeaves,
  BEHAVIOURS,
  lateralMoves,
  parameter,
  SiteVisit,
  speedAt,
  STEP,
  Track,
  trackOf,
  tracksOf,
  turnsAcrossAsSynchronized,
} from '../support/libraryBehaviours';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

/**
 * Every module of the built-in library, verified (issue 28): schema-valid with no warning under `check`, its example
 * main flattened and run in esmini with the behaviour asserted on esmini's own trajectories, from the parameters the
 * module documents (so a changed default is checked as it now is), and its CARLA export built by ScenarioRunner's loader.
 */

/**
 * A module's example main with a second actor (`ACTOR2`, 40 m further along its lane) whose copy of the group Insert into
 * Main writes; where the module has them, the second copy starts 3 s later and holds a quarter as long.
 */
function twoCopies(
  module: LibraryModule,
  library: string,
): { text: string; second: { actor: string; groupName: string; startTime: number; hold: number } } {
  const actor = module.actor.name;
  const second = `${actor}2`;
  let text = fs.readFileSync(module.example ?? '', 'utf8').replace(/filepath="\.\.\/roads\//, `filepath="${path.join(library, 'roads')}/`);
  const entity = new RegExp(`( *)<ScenarioObject name="${actor}">[\\s\\S]*?</ScenarioObject>\n`).exec(text)?.[0] ?? '';
  const init = new RegExp(`( *)<Private entityRef="${actor}">[\\s\\S]*?</Private>\n`).exec(text)?.[0] ?? '';
  assert.ok(entity && init, `${module.name}: its example has no entity or Init for ${actor}`);
  text = text
    .replace(entity, entity + entity.replace(`name="${actor}"`, `name="${second}"`))
    .replace(
      init,
      init +
        init.replace(`entityRef="${actor}"`, `entityRef="${second}"`).replace(/ s="([\d.]+)"/, (_, s: string) => ` s="${Number(s) + 40}"`),
    )
    .replace(
      /(<Condition name="End"[\s\S]*?<SimulationTimeCondition value=")([\d.]+)/,
      (_, head: string, time: string) => `${head}${Number(time) + 6}`,
    );
  const players = Object.fromEntries(moduleRoles(module).map((role) => [role.name, role.name === actor ? second : role.name]));
  const has = (name: string) => module.parameters.some((candidate) => candidate.name === name);
  const startTime = has('startTime') ? parameter(module, 'startTime') + 3 : NaN;
  const hold = has('hold') ? parameter(module, 'hold') / 4 : NaN;
  const inserted = insertModuleGroup(text, module, { players });
  const group = inserted.text
    .replace(/(key="SimulationTimeCondition\.value" value=")[^"]*/, `$1${startTime}`)
    .replace(/(key="Condition\.delay" value=")[^"]*/, `$1${hold}`);
  return {
    text: text.slice(0, inserted.offset) + group + text.slice(inserted.offset),
    second: { actor: second, groupName: inserted.groupName, startTime, hold },
  };
}

/** A road's left and right lanes swapped (ids negated): the other side of straight_1000m.xodr as its first. */
function swappedSides(road: string): string {
  const left = /<left>([\s\S]*?)<\/left>/.exec(road)?.[1] ?? '';
  const right = /<right>([\s\S]*?)<\/right>/.exec(road)?.[1] ?? '';
  assert.ok(left && right, 'the road has no left or right lanes');
  const negated = (lanes: string) => lanes.replace(/<lane id="(-?\d+)"/g, (_, id: string) => `<lane id="${-Number(id)}"`);
  // OpenDRIVE lists the left lanes outermost first, the right ones innermost first: reversed with the sides.
  const reversed = (lanes: string) => (lanes.match(/ *<lane [\s\S]*?<\/lane>\n/g) ?? []).reverse().join('');
  return road.replace(left, `\n${reversed(negated(right))}        `).replace(right, `\n${reversed(negated(left))}        `);
}

describe('library modules: each verified in esmini and CARLA (issue 28)', function () {
  this.timeout(600_000);
  const libraryFolder = builtInLibraryFolder();
  let modules: LibraryModule[] = [];
  const outputs = temporaryFolder('m2s-library-');

  before(async () => {
    assert.ok(libraryFolder, 'the built-in library is not found');
    const listing = await listLibraries(nodeFileSystem, libraryFolders([], {}));
    assert.deepEqual(listing.problems, []);
    modules = listing.modules;
  });

  it('the modules and example mains are what scripts/library-build.mjs writes, the roads what scripts/library-roads.mjs writes', () => {
    for (const script of ['library-build.mjs', 'library-roads.mjs']) {
      const run = spawnSync(process.execPath, [path.join(repoRoot, 'scripts', script), '--check'], { encoding: 'utf8' });
      assert.equal(run.status, 0, `${script} --check: ${run.stdout}${run.stderr}`);
    }
  });

  it('every module has a doc block, documented keys, an example main; and a behaviour checked here', () => {
    assert.ok(modules.length >= 5, `${modules.length} modules`);
    for (const module of modules) {
      assert.ok(module.example && fs.existsSync(module.example), `${module.name}: no example main`);
      assert.ok(BEHAVIOURS[module.name], `${module.name}: no behaviour assertion in this test`);
      for (const parameter of module.parameters)
        assert.ok(parameter.defaultValue !== undefined, `${module.name} ${parameter.key}: no default`);
    }
  });

  it('every module and example main: schema-valid, no error and no warning under check', async () => {
    const errors: string[] = [];
    const out: string[] = [];
    const files = modules.flatMap((module) => [module.file, module.example ?? '']);
    const code = await main(['check', ...files], { out: (text) => out.push(text), err: (text) => errors.push(text) });
    assert.equal(code, 0, errors.join('\n'));
    assert.match(errors.join('\n') + out.join('\n'), /0 errors, 0 warnings/);
  });

  it('every example main flattens and runs in esmini, the behaviour happens as its parameters say, and its picture is drawn from that run', async function () {
    requireEsmini(this);
    for (const module of modules) {
      const recording = path.join(outputs, `${module.name}.dat`);
      const { run, svg } = await runExample(module, outputs, esminiBinary, recording);
      const environments = recordedEnvironments(fs.readFileSync(recording));
      fs.rmSync(recording);
      BEHAVIOURS[module.name](module, tracksOf(run), environments);
      const picture = path.join(libraryFolder ?? '', 'pictures', `${module.name}.svg`);
      assert.ok(module.picture, `${module.name}: no picture (npx tsx scripts/library-pictures.ts draws them)`);
      assert.equal(
        svg,
        fs.readFileSync(picture, 'utf8'),
        `${module.name}: its picture is not what scripts/library-pictures.ts draws from this run`,
      );
    }
  });

  /** A module's example main changed to `variant` (its road path made absolute), flattened and run in esmini: its tracks. */
  async function runVariant(module: LibraryModule, variant: string): Promise<Map<string, Track>> {
    // Beside the run's files, not among them: runExample writes the flattened main as NAME.xosc in the folder it is given.
    const example = path.join(outputs, 'variant', `${module.name}.xosc`);
    fs.mkdirSync(path.dirname(example));
    fs.writeFileSync(example, variant.replace(/filepath="\.\.\/roads\//, `filepath="${path.join(libraryFolder ?? '', 'roads')}/`));
    try {
      const { run } = await runExample({ ...module, example }, outputs, esminiBinary);
      return tracksOf(run);
    } finally {
      fs.rmSync(path.dirname(example), { recursive: true });
    }
  }

  it("turn-across-path keeps its synchronization when the main changes the ego's speed, the time gap and the turning speed", async function () {
    requireEsmini(this);
    const module = modules.find((candidate) => candidate.name === 'turn-across-path');
    assert.ok(module?.example, 'no turn-across-path module with an example');
    const text = fs.readFileSync(module.example, 'utf8');
    for (const [egoSpeed, egoAt, turnSpeed] of [
      // The ego at 14 m/s instead of 10, and 10 m short of the conflict point (x 1.63) as the turning vehicle arrives: a time gap of 0.83 s.
      [14, -10, parameter(module, 'turnSpeed')],
      // The ego at 12 m/s and 7.63 m short (0.64 s), the turning vehicle crossing at 4 m/s (with its target resolved on the
      // ego's road 101, esmini ended the synchronization as the turn began and it crossed 1.2 s late).
      [12, -6, 4],
    ]) {
      const variant = text
        .replace(/(<Private entityRef="ego">[\s\S]*?<AbsoluteTargetSpeed value=")[^"]*/, `$1${egoSpeed}`)
        .replace(/(key="WorldPosition\.x" value=")[^"]*/, `$1${egoAt}`)
        .replace(/(key="AbsoluteSpeed\.value" value=")[^"]*/, `$1${turnSpeed}`);
      assert.notEqual(variant, text);
      const tracks = await runVariant(module, variant);
      assert.ok(Math.abs(speedAt(trackOf(tracks, 'ego'), 1) - egoSpeed) < 0.01, "the variant did not change the ego's speed");
      turnsAcrossAsSynchronized(tracks, egoAt, turnSpeed);
    }
  });

  it('arrive-leave-site does what other keys ask, and what its defaults ask is not what that run shows (esmini)', async function () {
    requireEsmini(this);
    const module = modules.find((candidate) => candidate.name === 'arrive-leave-site');
    assert.ok(module?.example, 'no arrive-leave-site module with an example');
    const keys: Record<string, [keyof SiteVisit, number]> = {
      'RelativeDistanceCondition.value': ['brakeGap', 50],
      'SpeedActionDynamics.value': ['brakingDistance', 40],
      'Condition.delay': ['stay', 1.5],
      'AbsoluteTargetSpeed.value': ['leaveSpeed', 6],
      'AbsoluteTargetLaneOffset.value': ['passOffset', -3.5],
      'LaneOffsetActionDynamics.maxLateralAcc': ['lateralAcceleration', 1],
    };
    const text = fs.readFileSync(module.example, 'utf8');
    let variant = text;
    for (const [key, [, value]] of Object.entries(keys)) {
      const before = variant;
      variant = variant.replace(new RegExp(`(key="${key.replace(/\./g, '\\.')}" value=")[^"]*`), `$1${value}`);
      assert.notEqual(variant, before, `the example sets no ${key}`);
    }
    const tracks = await runVariant(module, variant);
    const asked = Object.fromEntries(Object.values(keys)) as SiteVisit;
    arrivesStaysLeaves(tracks, asked);
    // Each value is checked: the run fails the assertions with any one of them at its default instead.
    for (const [name] of Object.values(keys)) {
      const defaults = { ...asked, [name]: parameter(module, name) };
      assert.throws(() => arrivesStaysLeaves(tracks, defaults), assert.AssertionError, `${name} at its default passes too`);
    }
  });

  it('modules whose later event waits for their earlier one by name: two copies in one main, each waits for its own (esmini)', async function () {
    requireEsmini(this);
    // Which modules those are is read from their files: a StoryboardElementStateCondition naming an element of the module's own group.
    const waiting = modules.filter((module) => {
      const text = fs.readFileSync(module.file, 'utf8');
      return [...text.matchAll(/storyboardElementRef="([^"]+)"/g)].some((match) => text.includes(`name="${match[1]}"`));
    });
    assert.deepEqual(
      waiting.map((module) => module.name),
      ['arrive-leave-site', 'double-lane-change', 'overtaking', 'swerving-lead'],
    );
    for (const module of waiting) {
      const { text, second } = twoCopies(module, libraryFolder ?? '');
      const flat = path.join(outputs, `${module.name}-twice.xosc`);
      fs.writeFileSync(path.join(outputs, `${module.name}-twice.main.xosc`), text);
      const errors: string[] = [];
      const code = await main(['flatten', path.join(outputs, `${module.name}-twice.main.xosc`), '-o', flat, '-q'], {
        out: () => {},
        err: (line) => errors.push(line),
      });
      assert.equal(code, 0, errors.join('\n'));
      // Each copy's condition names its own copy's event, which no other element is named.
      const flatText = fs.readFileSync(flat, 'utf8');
      for (const outer of [module.maneuverGroup, second.groupName]) {
        const reference = new RegExp(`storyboardElementRef="(${outer.replace('.', '\\.')}\\.[^"]+)"`).exec(flatText)?.[1];
        assert.ok(reference, `${module.name}: the copy ${outer} names no element of its own in its condition:\n${flatText}`);
        assert.equal(flatText.split(`name="${reference}"`).length - 1, 1, `${module.name}: one element is named ${reference}`);
      }
      // Their own waits in esmini: overtaking's depends on the gap, arrive-leave-site's on the site (the test above runs it).
      if (module.name === 'overtaking' || module.name === 'arrive-leave-site') continue;
      const example = path.join(outputs, 'twice', `${module.name}.xosc`);
      fs.mkdirSync(path.dirname(example), { recursive: true });
      fs.writeFileSync(example, text);
      const { run } = await runExample({ ...module, example }, outputs, esminiBinary);
      fs.rmSync(path.dirname(example), { recursive: true });
      const tracks = tracksOf(run);
      for (const [actor, startTime, hold] of [
        [module.actor.name, parameter(module, 'startTime'), parameter(module, 'hold')],
        [second.actor, second.startTime, second.hold],
      ] as const) {
        const moves = lateralMoves(trackOf(tracks, actor));
        const track = trackOf(tracks, actor);
        assert.ok(moves.length >= 2, `${module.name} ${actor}: ${moves.length} sideways moves, not out and back`);
        const [out, back] = moves;
        assert.ok(
          Math.abs(track[out.start].time - startTime) <= STEP * 2.5,
          `${module.name} ${actor} moves out at ${track[out.start].time} s`,
        );
        const waited = track[back.start].time - track[out.end].time;
        assert.ok(
          Math.abs(waited - hold) <= STEP * 2.5,
          `${module.name} ${actor} moves back ${waited.toFixed(2)} s after its own move out ended, not its hold ${hold} s`,
        );
      }
    }
  });

  /**
   * Each module whose example has an ego (but the weather's) inserted into a main with only an ego, as New Modular Scenario
   * writes it, the ego the example's car and speed 10 m further along its lane, its actors added by Insert into Main; each
   * main checks clean and behaves in esmini as its example. `turned`: the ego on the other side of the road (its lane id
   * negated, on `straight_1000m.xodr` with its sides swapped, so that both have three lanes and a sidewalk), driving
   * against s, and esmini's tracks turned back half round (x 1000 - x, y -y) for the example's assertions. `leftHand`: the
   * ego on the same road for left-hand traffic (`test/fixtures/library/straight_lht_1000m.xodr`, rule="LHT", its sides
   * swapped likewise), on the lane of the other side driven along s, and esmini's tracks mirrored back (y -y).
   * What each new entity was told, as Insert into Main says it.
   */
  async function composedWithAnEgo(side: 'same' | 'turned' | 'leftHand'): Promise<string[]> {
    const turned = side === 'turned';
    const placed: string[] = [];
    const composed = path.join(outputs, 'composed');
    fs.mkdirSync(composed, { recursive: true });
    const straight = path.join(libraryFolder ?? '', 'roads', 'straight_1000m.xodr');
    const leftHandRoad = path.join(repoRoot, 'test', 'fixtures', 'library', 'straight_lht_1000m.xodr');
    const swapped = path.join(composed, 'straight_1000m_swapped.xodr');
    fs.writeFileSync(swapped, swappedSides(fs.readFileSync(straight, 'utf8')));
    // The weather's behaviour is read from a recording, and its only role is the ego.
    for (const module of modules.filter((candidate) => candidate.name !== 'weather-light-change')) {
      const exampleText = fs.readFileSync(module.example ?? '', 'utf8');
      const egoPosition = /<Private entityRef="ego">[\s\S]*?<LanePosition roadId="([^"]+)" laneId="(-?\d+)" s="([\d.]+)"/.exec(exampleText);
      const egoSpeed = /<Private entityRef="ego">[\s\S]*?<AbsoluteTargetSpeed value="([^"]+)"/.exec(exampleText)?.[1];
      const egoVehicle = /<ScenarioObject name="ego">\s*(<Vehicle[\s\S]*?<\/Vehicle>)/.exec(exampleText)?.[1];
      const end = /<Condition name="End"[\s\S]*?<SimulationTimeCondition value="([^"]+)"/.exec(exampleText)?.[1];
      // arrive-leave-site, rear-end-collision and ttc-brake have no ego: their actors stand where their examples say.
      if (!egoPosition) continue;
      assert.ok(egoSpeed && egoVehicle && end, `${module.name}: its example's ego has no speed, car or end`);
      const road = path.resolve(path.dirname(module.example ?? ''), /<LogicFile filepath="([^"]+)"/.exec(exampleText)?.[1] ?? '');
      // Turned round or mirrored on the straight road only: the on-ramp and the crossroads have no other side to turn to.
      if (side !== 'same' && road !== straight) continue;
      const [laneId, s] = [Number(egoPosition[2]), Number(egoPosition[3]) + 10];
      // The ego drives as the example's (its car, its speed, its end), 10 m further along its lane.
      let text = newMainScenario({
        version: '1.1',
        roadFile: { same: road, turned: swapped, leftHand: leftHandRoad }[side],
        ego: { roadId: egoPosition[1], laneId: side === 'same' ? laneId : -laneId, s: turned ? 1000 - s : s },
      })
        .replace(/<Vehicle name="car"[\s\S]*?<\/Vehicle>/, egoVehicle)
        .replace('name="EgoSpeed" parameterType="double" value="10"', `name="EgoSpeed" parameterType="double" value="${egoSpeed}"`)
        .replace('<SimulationTimeCondition value="20"', `<SimulationTimeCondition value="${end}"`);
      const shape = mainShape(text);
      const offers = entityOffers(module, exampleText, shape.entities);
      const players: Record<string, string> = {};
      const create: Record<string, string> = {};
      for (const role of moduleRoles(module)) {
        const offer = offers.find((candidate) => candidate.role === role.name);
        players[role.name] = guessPlayer(role, shape.entities) ?? offer?.name ?? '';
        if (players[role.name] === offer?.name) create[role.name] = offer.name;
      }
      const mainFile = path.join(composed, `${module.name}.xosc`);
      const rules = { main: openDriveSignals(fs.readFileSync(side === 'leftHand' ? leftHandRoad : road, 'utf8')).leftHandRoads };
      const entities = newEntityChanges(
        text,
        module,
        exampleText,
        create,
        players,
        { main: mainFile, example: module.example ?? '' },
        rules,
      );
      placed.push(...entities.added.map((added) => `${module.name}: ${added}`));
      const group = insertModuleGroup(text, module, { players, values: entities.values });
      for (const change of [...entities.changes, { start: group.offset, end: group.offset, text: group.text }].sort(
        (a, b) => b.start - a.start,
      ))
        text = text.slice(0, change.start) + change.text + text.slice(change.end);
      fs.writeFileSync(mainFile, text);
      const said: string[] = [];
      const code = await main(['check', mainFile], { out: (line) => said.push(line), err: (line) => said.push(line) });
      assert.equal(code, 0, said.join('\n'));
      assert.match(said.join('\n'), /0 errors, 0 warnings/, `${module.name}:\n${said.join('\n')}`);
      const { run } = await runExample({ ...module, example: mainFile }, outputs, esminiBinary);
      const tracks = tracksOf(run);
      tracks.set('ego', tracks.get('Ego') ?? []);
      if (side !== 'same')
        for (const [name, track] of tracks)
          tracks.set(
            name,
            track.map((point) => ({ time: point.time, x: turned ? 1000 - point.x : point.x, y: -point.y })),
          );
      try {
        BEHAVIOURS[module.name](module, tracks, []);
      } catch (error) {
        const where = { same: '', turned: ', the ego on the other side of the road', leftHand: ', on a road of left-hand traffic' }[side];
        throw new Error(`${module.name}${where}: ${(error as Error).message}`);
      }
    }
    fs.rmSync(composed, { recursive: true, force: true });
    return placed;
  }

  it('every module inserted into a main with only an ego (as New Modular Scenario writes it, 10 m further on), its actors added by Insert into Main: clean, and it behaves as in its example in esmini', async function () {
    requireEsmini(this);
    const placed = await composedWithAnEgo('same');
    // Each actor 10 m further on, as its example places it from the ego (those of modules that name no ego where it says).
    assert.ok(placed.filter((added) => / m (ahead of|behind) Ego/.test(added)).length >= 14, placed.join('\n'));
  });

  it("the same with the ego on the other side of the road from the example's (a left lane): each placement turned half round, and it behaves as in its example in esmini", async function () {
    requireEsmini(this);
    const placed = await composedWithAnEgo('turned');
    assert.ok(placed.filter((added) => /the example's placement turned round/.test(added)).length >= 12, placed.join('\n'));
  });

  it('the same on a road of left-hand traffic (rule="LHT"), the ego on its left lane driven along s: each placement mirrored, the sides of lane changes and offsets swapped, and it behaves as in its example in esmini, mirrored', async function () {
    requireEsmini(this);
    const placed = await composedWithAnEgo('leftHand');
    assert.ok(
      placed.filter((added) => /the example's placement mirrored: road 0 is of left-hand traffic/.test(added)).length >= 12,
      placed.join('\n'),
    );
  });

  it("every example main's CARLA export builds in ScenarioRunner's loader, and check --simulator carla finds no error in it", async function () {
    requireCarlaHarness(this);
    const exported: string[] = [];
    for (const module of modules) {
      const output = path.join(outputs, `${module.name}.carla.xosc`);
      const errors: string[] = [];
      const code = await main(['export', module.example ?? '', '--target', 'carla', '-o', output, '-q'], {
        out: () => {},
        err: (text) => errors.push(text),
      });
      assert.equal(code, 0, `${module.name}: ${errors.join('\n')}`);
      exported.push(output);
    }
    const verdicts = await harnessVerdicts(exported);
    for (const file of exported) {
      const verdict = verdicts.get(path.resolve(file));
      assert.equal(verdict?.status, 'OK', `${path.basename(file)}: ${verdict?.stage} ${verdict?.reason}`);
      // check --simulator carla agrees with the harness: nothing ScenarioRunner refuses (its warnings say what it runs otherwise).
      const said: string[] = [];
      const code = await main(['check', file, '--simulator', 'carla'], { out: (text) => said.push(text), err: (text) => said.push(text) });
      assert.equal(code, 0, said.join('\n'));
      assert.match(said.join('\n'), /checked 1 file: 0 errors/);
    }
  });
});

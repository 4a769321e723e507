import { strict as assert } from 'node:assert';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { main } from '../../server/src/cli';
import { builtInLibraryFolder, listTemplates } from '../../server/src/libraries';
import { readModule } from '../../server/src/core/library';
import { insertModuleGroup } from '../../server/src/core/libraryInsert';
import { templateFiles } from '../../scripts/library-templates';
import { esminiCollisions, requireEsmini, runEsmini, tracksOf } from '../support/esmini';
import { BEHAVIOURS } from '../support/libraryBehaviours';
import { temporaryFolder } from '../support/temporaryDirectory';

type Track = { time: number; x: number; y: number }[];

const library = builtInLibraryFolder() ?? '';
const templatesFolder = path.join(library, 'templates');
/** The library's cars: the bounding box's front is 3.75 m ahead of the reference point, its rear 0.75 m behind. */
const FRONT = 3.75;
const REAR = 0.75;

async function cli(args: string[]): Promise<{ code: number; out: string; err: string }> {
  const out: string[] = [];
  const err: string[] = [];
  const code = await main(args, { out: (text) => out.push(text), err: (text) => err.push(text) });
  return { code, out: out.join('\n'), err: err.join('\n') };
}

/** The scenario flattened into `folder` and run in esmini: each entity's track. */
async function run(scenario: string, folder: string, seconds: number): Promise<Map<string, Track>> {
  const flat = path.join(folder, `${path.basename(scenario, '.xosc')}.flat.xosc`);
  const flattened = await cli(['flatten', scenario, '-o', flat, '-q']);
  assert.equal(flattened.code, 0, flattened.err);
  const steps = await runEsmini(flat, seconds + 1);
  assert.ok(steps[steps.length - 1].time >= seconds - 0.1, `esmini ran ${scenario} to ${steps[steps.length - 1].time} s only`);
  return tracksOf(steps);
}

function track(tracks: Map<string, Track>, name: string): Track {
  const found = tracks.get(name);
  assert.ok(found && found.length > 2, `no track for ${name}`);
  return found;
}

const speedAt = (track: Track, index: number) => (track[index + 1].x - track[index].x) / (track[index + 1].time - track[index].time);

/** The templates (issue 28, item 3): written by scripts/library-templates.ts, valid, each run in esmini as written. */
describe('library templates: mains composed from library modules for test protocols', function () {
  this.timeout(240_000);
  let work: string;
  before(() => {
    work = temporaryFolder('m2s-templates-');
  });

  it('are what scripts/library-templates.ts writes (composed by Insert into Main), and each is listed', async function () {
    for (const [name, text] of await templateFiles(library))
      assert.equal(
        fs.readFileSync(path.join(templatesFolder, name), 'utf8'),
        text,
        `${name} differs: npx tsx scripts/library-templates.ts`,
      );
    const { templates, problems } = listTemplates(library);
    assert.deepEqual(problems, []);
    for (const name of ['ncap-ccrb', 'ncap-cpna', 'alks-cut-in', 'composition-bench'])
      assert.ok(
        templates.some((template) => template.name === name),
        name,
      );
    assert.equal(templates.find((template) => template.name === 'alks-cut-in')?.distribution, 'alks-cut-in.distribution.xosc');
  });

  it('check finds no error and no warning in any template or distribution', async function () {
    const checked = await cli(['check', templatesFolder, '--format', 'json']);
    assert.equal(checked.code, 0, checked.out + checked.err);
    const report = JSON.parse(checked.out) as { summary?: { errors: number; warnings: number }; errors?: number; warnings?: number };
    const summary = report.summary ?? report;
    assert.equal(summary.errors, 0, checked.out);
    assert.equal(summary.warnings, 0, checked.out);
  });

  it('car-to-car rear braking: the lead car brakes to a stop at the deceleration its parameter gives', async function () {
    requireEsmini(this);
    const text = fs.readFileSync(path.join(templatesFolder, 'ncap-ccrb.xosc'), 'utf8');
    const deceleration = Number(/name="Deceleration" parameterType="double" value="([^"]+)"/.exec(text)?.[1]);
    const lead = track(await run(path.join(templatesFolder, 'ncap-ccrb.xosc'), work, 6), 'Lead');
    const speeds = lead.slice(0, -1).map((_, index) => speedAt(lead, index));
    const from = speeds.findIndex((speed) => speed < 12);
    const to = speeds.findIndex((speed) => speed < 2);
    assert.ok(from >= 0 && to > from, `the lead car never braked: ${speeds.slice(0, 10).join(', ')}`);
    const measured = (speeds[from] - speeds[to]) / (lead[to].time - lead[from].time);
    assert.ok(Math.abs(measured - deceleration) < 0.3, `the lead car brakes at ${measured.toFixed(2)} m/s², not ${deceleration}`);
    assert.ok(speeds[speeds.length - 1] < 0.05, 'it stops');
  });

  it("car-to-pedestrian nearside: the pedestrian reaches the middle of the ego's lane as the ego's front arrives", async function () {
    requireEsmini(this);
    const tracks = await run(path.join(templatesFolder, 'ncap-cpna.xosc'), work, 10);
    const [ego, pedestrian] = [track(tracks, 'Ego'), track(tracks, 'Pedestrian')];
    const laneMiddle = ego[0].y;
    const onPath = pedestrian.findIndex((point) => point.y >= laneMiddle);
    assert.ok(onPath > 0, `the pedestrian never reached y ${laneMiddle}`);
    const arrives = ego.findIndex((point) => point.x + FRONT >= pedestrian[onPath].x);
    assert.ok(arrives > 0, 'the ego never reached the crossing line');
    const apart = Math.abs(ego[arrives].time - pedestrian[onPath].time);
    assert.ok(
      apart < 0.5,
      `the pedestrian is on the ego's path at ${pedestrian[onPath].time} s, the ego's front there at ${ego[arrives].time} s`,
    );
  });

  it('ALKS cut-in: its distribution makes 9 concrete scenarios (vary); the first and the last cut in at their gap and end in the ego lane', async function () {
    requireEsmini(this);
    const distribution = path.join(templatesFolder, 'alks-cut-in.distribution.xosc');
    const count = await cli(['vary', distribution, '--count']);
    assert.equal(count.code, 0, count.err);
    assert.match(count.out, /^9\b/);
    for (const index of [0, 8]) {
      const concrete = path.join(work, `alks-cut-in_${index}.xosc`);
      const varied = await cli(['vary', distribution, '--index', String(index), '-o', concrete, '-q']);
      assert.equal(varied.code, 0, varied.err);
      const text = fs.readFileSync(concrete, 'utf8');
      const gap = Number(/name="Gap" parameterType="double" value="([^"]+)"/.exec(text)?.[1]);
      const tracks = await run(concrete, work, 15);
      const [ego, car] = [track(tracks, 'Ego'), track(tracks, 'CutInCar')];
      const start = car.findIndex((point) => Math.abs(point.y - car[0].y) > 1e-5) - 1;
      assert.ok(start > 0, `concrete ${index}: the car never changed lanes`);
      const measured = car[start].x - REAR - (ego[start].x + FRONT);
      assert.ok(
        Math.abs(measured - gap) < 0.6,
        `concrete ${index}: the lane change starts at a gap of ${measured.toFixed(2)} m, not ${gap}`,
      );
      const end = car[car.length - 1];
      assert.ok(Math.abs(end.y - ego[ego.length - 1].y) < 0.05, `concrete ${index}: the car ends at y ${end.y}, not in the ego lane`);
    }
  });

  it('the composition bench runs with every entity in its lane, doing nothing', async function () {
    requireEsmini(this);
    const tracks = await run(path.join(templatesFolder, 'composition-bench.xosc'), work, 12);
    for (const name of ['ego', 'adversary', 'lead', 'pedestrian']) {
      const each = track(tracks, name);
      assert.ok(Math.abs(each[each.length - 1].y - each[0].y) < 1e-6, `${name} moved sideways`);
    }
  });

  it("the composition bench with a cut-in, a lead brake and a pedestrian crossing inserted at their defaults, in any order: each behaves as in its example in its 12 s, and no two scripted actors touch (the cut-in's car passes the crossing before the pedestrian reaches its lane)", async function () {
    requireEsmini(this);
    const bench = fs.readFileSync(path.join(templatesFolder, 'composition-bench.xosc'), 'utf8');
    // Each module's actor, an entity of the bench of the role's name.
    const actors = { 'cut-in': 'adversary', 'lead-brake': 'lead', 'pedestrian-crossing': 'pedestrian' } as const;
    const modules = new Map(
      Object.keys(actors).map((name) => {
        const file = path.join(library, `${name}.xosc`);
        const { module } = readModule(fs.readFileSync(file, 'utf8'), file, { folder: library, label: 'built-in' });
        assert.ok(module, name);
        return [name, module];
      }),
    );
    // The editor's order (the view's walk) and its reverse: the bench's entities stand where it places them either way.
    for (const order of [
      ['cut-in', 'lead-brake', 'pedestrian-crossing'],
      ['pedestrian-crossing', 'lead-brake', 'cut-in'],
    ] as const) {
      let text = bench;
      // As Insert into Main does it: the bench's entities play the modules' roles, every key at its default.
      for (const name of order) {
        const module = modules.get(name);
        assert.ok(module, name);
        const group = insertModuleGroup(text, module, { players: { ego: 'ego', [actors[name]]: actors[name] } });
        text = text.slice(0, group.offset) + group.text + text.slice(group.offset);
      }
      const composed = path.join(work, 'composed-bench.xosc');
      // Written elsewhere than the template, its road named where it is.
      fs.writeFileSync(composed, text.replace('../roads/straight_1000m.xodr', path.join(library, 'roads', 'straight_1000m.xodr')));
      const tracks = await run(composed, work, 12);
      for (const [name, module] of modules) BEHAVIOURS[name](module, tracks, []);
      const collisions = await esminiCollisions(path.join(work, 'composed-bench.flat.xosc'));
      assert.ok(collisions.length > 0, "esmini's collision detection names the ego's collisions (it ran)");
      // Before 30 November 2026 the cut-in's car touched the pedestrian at 7.75 s and the lead at 10.05 s.
      assert.deepEqual(
        collisions
          .filter((collision) => !collision.entities.includes('ego'))
          .map((collision) => `${collision.entities.join(' and ')} at ${collision.time} s`),
        [],
        `scripted actors touch (inserted ${order.join(', ')})`,
      );
    }
  });

  it('library new TEMPLATE -o FILE writes the scenario, its road and its distribution, clean under check; it never replaces a file', async function () {
    const folder = temporaryFolder('m2s-new-');
    const scenario = path.join(folder, 'cut-in-test.xosc');
    const made = await cli(['library', 'new', 'alks-cut-in', '-o', scenario]);
    assert.equal(made.code, 0, made.err);
    assert.deepEqual(fs.readdirSync(folder).sort(), ['cut-in-test.distribution.xosc', 'cut-in-test.xosc', 'straight_1000m.xodr']);
    assert.match(fs.readFileSync(scenario, 'utf8'), /<LogicFile filepath="straight_1000m.xodr"\/>/);
    assert.match(
      fs.readFileSync(path.join(folder, 'cut-in-test.distribution.xosc'), 'utf8'),
      /<ScenarioFile filepath="cut-in-test.xosc"\/>/,
    );
    const checked = await cli(['check', folder]);
    assert.equal(checked.code, 0, checked.out + checked.err);
    const before = fs.readFileSync(scenario, 'utf8');
    fs.writeFileSync(scenario, before + '<!-- mine -->\n');
    const again = await cli(['library', 'new', 'alks-cut-in', '-o', scenario]);
    assert.equal(again.code, 1);
    assert.match(again.err, /cut-in-test.xosc exists: nothing was written/);
    assert.equal(fs.readFileSync(scenario, 'utf8'), before + '<!-- mine -->\n');
    const misspelt = await cli(['library', 'new', 'ncap-ccr', '-o', path.join(folder, 'other.xosc')]);
    assert.equal(misspelt.code, 1);
    assert.match(misspelt.err, /did you mean 'ncap-ccrb'/);
    assert.ok(!fs.existsSync(path.join(folder, 'other.xosc')));
  });
});

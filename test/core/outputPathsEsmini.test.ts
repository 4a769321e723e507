import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { descendants, parseXml } from '../../server/src/core/xml';
import { esminiBinary, EsminiStep, readEsminiCsv, requireEsmini } from '../support/esmini';
import { esminiXodrDir } from '../support/esminiBinaries';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { runBounded } from '../support/processes';
import { temporaryFolder } from '../support/temporaryDirectory';

/**
 * SPEC 11.6 on esmini's own scenarios: each becomes a composition (ws/xosc/NAME.main.xosc importing every
 * group of ws/xosc/NAME.xosc, the roads in ws/xodr, as esmini's resources lie), flattened one folder deeper
 * than its main; esmini runs the output (fixed step, seed 1, no --path, from an unrelated folder) and every
 * entity is where it is in the run of the original at every step.
 */
const esminiCorpus = path.join(openscenarioDir, 'esmini');
const scenarios = fs.existsSync(esminiCorpus)
  ? fs
      .readdirSync(esminiCorpus)
      .filter((name) => name.endsWith('.xosc'))
      .sort()
  : [];

/** The composition's main file: every ManeuverGroup of a name of its own replaced by one of the same name and actors importing it from `sourceName`. */
function compositionOf(text: string, sourceName: string): string {
  const document = parseXml(text);
  const groups = document.root ? descendants(document.root).filter((element) => element.name === 'ManeuverGroup') : [];
  const nameOf = (group: (typeof groups)[number]) => group.attributes.find((attribute) => attribute.name === 'name')?.value;
  let out = '';
  let position = 0;
  for (const group of groups) {
    const name = nameOf(group);
    const actors = group.children.find((child) => child.name === 'Actors');
    // A name two groups share would import the first one twice: such groups stay as written.
    // So do groups without an actor (an outer group needs one to give its imports).
    if (
      !name ||
      !actors?.children.some((child) => child.name === 'EntityRef') ||
      groups.filter((other) => nameOf(other) === name).length > 1
    )
      continue;
    out += text.slice(position, group.start);
    out += `${text.slice(group.start, group.startTagEnd)}\n${text.slice(actors.start, actors.end)}\n<ScenarioReference scenarioFileName="${sourceName}"><ManeuverGroupReference maneuverGroupName="${name}"/></ScenarioReference>\n</ManeuverGroup>`;
    position = group.end;
  }
  return out + text.slice(position);
}

async function runAlone(scenario: string, cwd: string): Promise<{ steps: EsminiStep[] | undefined; log: string }> {
  const csv = path.join(cwd, `${path.basename(scenario)}.csv`);
  const args = ['--headless', '--osc', scenario, '--fixed_timestep', '0.05', '--seed', '1', '--csv_logger', csv, '--disable_log'];
  const { code, output } = await runBounded(esminiBinary, args, { cwd }, 120_000);
  const steps = code === 0 && fs.existsSync(csv) ? readEsminiCsv(csv) : undefined;
  fs.rmSync(csv, { force: true });
  return { steps, log: output };
}

describe("core: compositions of esmini's scenarios flattened one folder deeper run as the originals (SPEC 11.6)", function () {
  this.timeout(600_000);
  let ws: string;
  let cwd: string;

  before(function () {
    requireEsmini(this);
    if (scenarios.length === 0) this.skip();
    ws = path.join(temporaryFolder('m2s-paths-corpus-'), 'ws');
    fs.cpSync(esminiCorpus, path.join(ws, 'xosc'), { recursive: true });
    fs.cpSync(esminiXodrDir, path.join(ws, 'xodr'), { recursive: true });
    fs.mkdirSync(path.join(ws, 'out', 'deeper'), { recursive: true });
    cwd = temporaryFolder('m2s-paths-corpus-cwd-');
  });

  for (const name of scenarios) {
    it(name, async function () {
      const source = path.join(ws, 'xosc', name);
      const original = await runAlone(source, cwd);
      // A scenario esmini itself cannot run here (it names a road on another machine) says nothing about outputs.
      if (!original.steps) return this.skip();
      const main = path.join(ws, 'xosc', name.replace(/\.xosc$/, '.main.xosc'));
      fs.writeFileSync(main, compositionOf(fs.readFileSync(source, 'utf8'), name));
      const output = path.join(ws, 'out', 'deeper', name);
      const result = await new Flattener(new ScenarioStore({ scenarioPath: [], root: ws })).flatten(diskRef(main), { outputPath: output });
      // Whether an expression esmini accepts blocks flattening is the severity policy's part, not this test's.
      if (result.text === undefined) {
        console.log(
          `      (skipped: ${name} does not flatten: ${result.problems.find((problem) => problem.severity === 'error')?.message})`,
        );
        return this.skip();
      }
      fs.writeFileSync(output, result.text);
      const flattened = await runAlone(output, cwd);
      assert.ok(flattened.steps, `esmini failed on the flattened ${name}:\n${flattened.log.slice(-2000)}`);
      assert.equal(flattened.steps.length, original.steps.length, `${name}: number of steps`);
      for (let index = 0; index < original.steps.length; index++) {
        assert.deepEqual(flattened.steps[index], original.steps[index], `${name}: step ${index} (t=${original.steps[index].time})`);
      }
    });
  }
});

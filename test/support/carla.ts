import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot, sharedDir } from './paths';
import { runBounded } from './processes';
import { temporaryFolder } from './temporaryDirectory';

/** CARLA's ScenarioRunner 0.9.16, offline, as ../shared/carla/README.md describes: the tests' oracle. */
export const carlaCheckScript = path.join(sharedDir, 'carla', 'check.py');
export const carlaCache = path.join(repoRoot, '.cache', 'carla');

let ready: string | undefined;

/**
 * Skips the calling suite with a message when the harness cannot run here; with M2S_REQUIRE_CARLA set,
 * fails instead. Unpacks it into .cache/carla on first use (`check.py setup`, idempotent; scripts/test-all.sh runs it first).
 */
export function requireCarlaHarness(context: Mocha.Context): void {
  if (ready === 'yes') return;
  const why = ready ?? whyHarnessUnavailable();
  ready = why ?? 'yes';
  if (why === undefined) return;
  if (process.env.M2S_REQUIRE_CARLA) throw new Error(`M2S_REQUIRE_CARLA is set, but ${why}`);
  console.log(`    (skipped: ${why})`);
  context.skip();
}

function whyHarnessUnavailable(): string | undefined {
  if (!fs.existsSync(carlaCheckScript)) return `${carlaCheckScript} is absent`;
  // pyenv's shim alone took 3 s at a load of 12 on two cores: the bound is for a python3 that hangs, not a busy one.
  const python = spawnSync('python3', ['--version'], { encoding: 'utf8', timeout: 120_000 });
  if (python.status !== 0)
    return python.signal
      ? `python3 --version did not answer within 120 s (${python.signal})`
      : `python3 --version failed: ${python.error?.message ?? (python.stderr || python.stdout).trim()}`;
  if (!fs.existsSync(path.join(carlaCache, 'scenario_runner', 'scenario_runner.py'))) {
    const setup = spawnSync('python3', [carlaCheckScript, 'setup'], {
      cwd: repoRoot,
      env: { ...process.env, CARLA_ORACLE_CACHE: carlaCache },
      encoding: 'utf8',
      timeout: 300_000,
    });
    if (setup.status !== 0)
      return `the ScenarioRunner harness is not set up (python3 ../shared/carla/check.py setup, as root: ${(setup.stderr || setup.stdout).trim().split('\n').slice(-1)[0]})`;
  }
  return undefined;
}

/** One file's verdict: OK, FAIL (with the stage and reason) or SKIP. */
export interface HarnessVerdict {
  status: 'OK' | 'FAIL' | 'SKIP';
  stage: string | null;
  reason: string | null;
  tree_nodes?: number;
  egos?: string[];
  town?: string;
  /**
   * With `tree: true`: what of the storyboard ScenarioRunner's built tree holds, as [kind, name] pairs
   * (kind ACT, SCENE = ManeuverGroup, MANEUVER, EVENT, ACTION by their OpenSCENARIO names; NODE, every
   * behaviour's name, where conditions appear; CLASS, every behaviour's class), read by ./carlaTree.py.
   */
  tree?: [string, string][];
  /**
   * With `tree: true`: each CheckParameter of the built tree (a condition on a parameter) by its name, ticked
   * after the Init's ChangeParameters and again after every other one: 'RUNNING', 'SUCCESS' or 'raises ...'.
   */
  parameter_ticks?: [string, string, string][];
  /**
   * With `storyTicks: true`: the Init's parameters and the stories ticked as a run ticks them (10 frames of 0.05 s, from the
   * parameters as declared): 'frame N raises ...' for the first exception, or null. Conditions that need the world never hold.
   */
  story_ticks?: string | null;
  /** With `tree: true`: where ScenarioRunner spawns each actor, by role name: [x, y, z, yaw°] in CARLA's coordinates (y negated). */
  spawns?: Record<string, [number, number, number, number]>;
  /** With `tree: true`: each ChangeActorWaypoints built, as [its parent's name, its name, waypoints, times (null: none), the last time]. */
  waypoints?: [string | null, string, number, number | null, number | null][];
  /** With `tree: true`: each ChangeLateralDistance built, as [its name, its offset: positive to the right, negative to the left]. */
  lateral_offsets?: [string, number][];
}

/** ./carlaTree.py: check.py run unchanged, its results also listing each built tree's story elements. */
const treeScript = path.join(__dirname, 'carlaTree.py');

/**
 * ScenarioRunner's verdict on each file, from one run of the harness over all of them (it imports
 * ScenarioRunner once and forks per file). `fixSrBugs` sets aside 0.9.16's route crash: 0.9.15's verdicts;
 * `tree` lists what of each storyboard reached the built tree; `storyTicks` (with `tree`) also ticks the stories, every
 * action included (only for the tests' own scenarios: a CustomCommandAction would run its command).
 */
export async function harnessVerdicts(
  files: string[],
  options: { fixSrBugs?: boolean; timeoutSeconds?: number; tree?: boolean; storyTicks?: boolean } = {},
): Promise<Map<string, HarnessVerdict>> {
  const json = path.join(temporaryFolder('m2s-carla-'), 'verdicts.json');
  try {
    const perFile = options.timeoutSeconds ?? 60;
    const script = options.tree ? [treeScript, carlaCheckScript] : [carlaCheckScript];
    const args = [...script, '--json', json, '--timeout', String(perFile), '--jobs', '2'];
    if (options.fixSrBugs) args.push('--fix-sr-bugs');
    // Whatever happens inside, the harness as a whole is bounded: a file per (timeout / 2 jobs), plus start-up.
    const { code, output } = await runBounded(
      'python3',
      [...args, ...files],
      {
        cwd: repoRoot,
        env: { ...process.env, CARLA_ORACLE_CACHE: carlaCache, ...(options.storyTicks ? { M2S_CARLA_STORY_TICKS: '1' } : {}) },
      },
      (files.length * perFile * 1000) / 2 + 60_000,
    );
    if ((code !== 0 && code !== 1) || !fs.existsSync(json))
      throw new Error(`the ScenarioRunner harness failed (exit ${code}):\n${output.slice(-2000)}`);
    const parsed = JSON.parse(fs.readFileSync(json, 'utf8')) as { results: (HarnessVerdict & { file: string })[] };
    return new Map(parsed.results.map((result) => [path.resolve(result.file), result]));
  } finally {
    fs.rmSync(path.dirname(json), { recursive: true, force: true });
  }
}

/** ScenarioRunner 0.9.16's own source, as the harness unpacks it: what a user names in `modular2simple.carla.scenarioRunnerPath`. */
export const scenarioRunnerFolder = path.join(carlaCache, 'scenario_runner');

/**
 * A Python that has ScenarioRunner's requirements, as a user's would (pip installs them): the harness's
 * interpreter with py_trees 0.8.3 and the XSD library versions ScenarioRunner pins on its path, as a wrapper
 * script in `folder`. Without them it lacks py_trees (`bare: true`): the "no requirements" case.
 */
export function scenarioRunnerPython(folder: string, bare = false): string {
  const interpreter = process.env.CARLA_ORACLE_PYTHON ?? '/usr/bin/python3';
  const libraries = ['py_trees-0.8.3', 'xmlschema-1.0.18', 'elementpath-1.3.3'].map((name) => path.join(carlaCache, name));
  const wrapper = path.join(folder, bare ? 'python-bare' : 'python-scenario-runner');
  const pythonPath = bare ? '' : `PYTHONPATH='${libraries.join(':')}' `;
  fs.writeFileSync(wrapper, `#!/bin/sh\n${pythonPath}exec '${interpreter}' "$@"\n`, { mode: 0o755 });
  return wrapper;
}

/** The zero-based line of the first line of `file` matching `pattern` (failing the test when none does). */
export function lineMatching(file: string, pattern: RegExp): number {
  const index = fs
    .readFileSync(file, 'utf8')
    .split('\n')
    .findIndex((line) => pattern.test(line));
  if (index < 0) throw new Error(`${String(pattern)} is not in ${file}`);
  return index;
}

/** A vehicle as ScenarioRunner's examples write one (1.0 needs every part). */
export const scenarioRunnerVehicle = (name: string, type: string): string => `
    <ScenarioObject name="${name}">
      <Vehicle name="vehicle.tesla.model3" vehicleCategory="car">
        <ParameterDeclarations/>
        <Performance maxSpeed="69.444" maxAcceleration="200" maxDeceleration="10.0"/>
        <BoundingBox><Center x="1.5" y="0.0" z="0.9"/><Dimensions width="2.1" length="4.5" height="1.8"/></BoundingBox>
        <Axles>
          <FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.8" positionX="3.1" positionZ="0.3"/>
          <RearAxle maxSteering="0.0" wheelDiameter="0.6" trackWidth="1.8" positionX="0.0" positionZ="0.3"/>
        </Axles>
        <Properties><Property name="type" value="${type}"/></Properties>
      </Vehicle>
    </ScenarioObject>`;

/**
 * An exported file as ScenarioRunner places its LanePositions, written back in OpenSCENARIO's reading, so that esmini
 * runs what ScenarioRunner would: ScenarioRunner moves a LanePosition by `offset` to the right of CARLA's waypoint
 * heading turned by the Orientation's h (srunner/tools/openscenario_parser.py convert_position_to_transform:
 * (-forward.y, forward.x) in CARLA's left-handed frame), and that heading runs along the road on a negative lane,
 * against it on a positive one (LibCarla road/Lane.cpp Lane::ComputeTransform); OpenSCENARIO's offset is along t. A
 * point ScenarioRunner moves along the road (more than 1 cm) is left as it is: the tests compare no such file.
 */
export function asScenarioRunnerPlacesLanePositions(xml: string): string {
  return xml.replace(
    /<LanePosition\b([^>]*?)(\/>|>([\s\S]*?)<\/LanePosition>)/g,
    (whole: string, attributes: string, _end: string, inner?: string) => {
      const value = (source: string, name: string): number | undefined => {
        const found = new RegExp(`\\b${name}="([^"]*)"`).exec(source);
        return found ? Number(found[1]) : undefined;
      };
      const offset = value(attributes, 'offset') ?? 0;
      const laneId = value(attributes, 'laneId') ?? 0;
      const orientation = inner ? /<Orientation\b[^>]*>/.exec(inner)?.[0] : undefined;
      const heading = (orientation ? (value(orientation, 'h') ?? 0) : 0) + (laneId > 0 ? Math.PI : 0);
      if (offset === 0 || Math.abs(offset * Math.sin(heading)) > 0.01) return whole;
      const alongT = -offset * Math.cos(heading);
      return whole.replace(/\boffset="[^"]*"/, `offset="${Number(alongT.toFixed(6))}"`);
    },
  );
}

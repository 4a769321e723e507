// `npx tsx scripts/library-templates.ts [--check]`: writes the scenario templates (library/templates/), each a main
// composed from library modules by the same code as the editor's Insert into Main (server/src/core/libraryInsert.ts),
// with the values of the test protocol it follows. --check writes nothing and lists the templates that differ (exit
// 1 if any). test/cli/libraryTemplates.test.ts checks each one and runs it in esmini.
import * as fs from 'node:fs';
import * as path from 'node:path';
import { LibraryModule, listLibraries } from '../server/src/core/library';
import { insertModuleGroup } from '../server/src/core/libraryInsert';
import { nodeFileSystem } from '../server/src/core/sources';
import { builtInLibraryFolder, libraryFolders } from '../server/src/libraries';

interface Placement {
  entity: string;
  /** The module and its entity whose ScenarioObject the entity copies. */
  from: [string, string];
  lane: number;
  s: number;
  offset?: number;
  /** Heading relative to the lane, radians. */
  heading?: number;
  speed: string;
}

interface Use {
  module: string;
  players: Record<string, string>;
  /** Keys set to other values than the module's defaults. */
  values?: Record<string, string>;
}

interface Template {
  name: string;
  title: string;
  summary: string;
  parameters: { name: string; type: string; value: string; about: string }[];
  entities: Placement[];
  uses: Use[];
  stopTime: string;
  distribution?: { about: string; sets: Record<string, string[]> };
}

const ROAD = '../roads/straight_1000m.xodr';
const INDENT = '  ';

const TEMPLATES: Template[] = [
  {
    name: 'composition-bench',
    title: 'Composition bench',
    summary:
      'An ego driving at 18 m/s in the leftmost lane of this direction, with a car 25.5 m ahead in the lane to its right (17 m/s), a slower lead car (12 m/s) ahead in its lane and a pedestrian on the right sidewalk 180 m ahead, none of them doing anything yet: Insert into Main gives them library behaviours (adversary, lead, pedestrian), and with a cut-in, a lead brake and a pedestrian crossing at their defaults no two of them touch.',
    parameters: [{ name: 'EgoSpeed', type: 'double', value: '18', about: 'the ego speed [m/s]' }],
    // Placed so that a cut-in, a lead brake and a pedestrian crossing at their defaults have no scripted actors touch (docs/library.md).
    entities: [
      { entity: 'ego', from: ['cut-in', 'ego'], lane: -1, s: 50, speed: '$EgoSpeed' },
      { entity: 'adversary', from: ['cut-in', 'adversary'], lane: -2, s: 80, speed: '17' },
      { entity: 'lead', from: ['lead-brake', 'lead'], lane: -1, s: 100, speed: '12' },
      { entity: 'pedestrian', from: ['pedestrian-crossing', 'pedestrian'], lane: -4, s: 230, offset: 0.75, heading: 1.5708, speed: '0' },
    ],
    uses: [],
    stopTime: '12',
  },
  {
    name: 'ncap-ccrb',
    title: 'Car-to-car rear, braking (Euro NCAP CCRb style)',
    summary:
      'The ego follows a lead car, both at 50 km/h, 12 m apart; the lead car brakes at once at 6 m/s² to a stop (its headway, 0.86 s, is below the 1 s the lead-brake module waits for). Euro NCAP varies the gap (12, 40 m) and the deceleration (2, 6 m/s²).',
    parameters: [
      { name: 'Speed', type: 'double', value: '13.889', about: 'both cars at the start [m/s] (50 km/h)' },
      { name: 'Deceleration', type: 'double', value: '6', about: 'the lead car brakes at [m/s²]' },
    ],
    entities: [
      { entity: 'Ego', from: ['lead-brake', 'ego'], lane: -1, s: 50, speed: '$Speed' },
      // 12 m bumper to bumper: the ego's front is 3.75 m ahead of its position, the lead's rear 0.75 m behind its own.
      { entity: 'Lead', from: ['lead-brake', 'lead'], lane: -1, s: 66.5, speed: '$Speed' },
    ],
    uses: [
      {
        module: 'lead-brake',
        players: { lead: 'Lead', ego: 'Ego' },
        values: { 'SpeedActionDynamics.value': '$Deceleration', 'AbsoluteTargetSpeed.value': '0', 'TimeHeadwayCondition.value': '1' },
      },
    ],
    stopTime: '6',
  },
  {
    name: 'ncap-cpna',
    title: 'Car-to-pedestrian, nearside adult (Euro NCAP CPNA style)',
    summary:
      'The ego drives at 40 km/h in the lane next to the right sidewalk; an adult walks out from the sidewalk at 5 km/h, timed to reach the middle of the ego lane as the ego arrives (the 50 % impact point: 2 m to walk / 1.39 m/s = 1.44 s of ego headway).',
    parameters: [
      { name: 'EgoSpeed', type: 'double', value: '11.111', about: 'the ego speed [m/s] (40 km/h)' },
      { name: 'WalkSpeed', type: 'double', value: '1.389', about: 'the pedestrian walks at [m/s] (5 km/h)' },
    ],
    entities: [
      { entity: 'Ego', from: ['pedestrian-crossing', 'ego'], lane: -3, s: 20, speed: '$EgoSpeed' },
      {
        entity: 'Pedestrian',
        from: ['pedestrian-crossing', 'pedestrian'],
        lane: -4,
        s: 100,
        offset: 0.75,
        heading: 1.5708,
        speed: '0',
      },
    ],
    uses: [
      {
        module: 'pedestrian-crossing',
        players: { pedestrian: 'Pedestrian', ego: 'Ego' },
        values: { 'AbsoluteTargetSpeed.value': '$WalkSpeed', 'TimeHeadwayCondition.value': '1.44', 'RelativeObjectPosition.dx': '8' },
      },
    ],
    stopTime: '10',
  },
  {
    name: 'alks-cut-in',
    title: 'ALKS cut-in (UN R157 style), with a distribution over gap and speed',
    summary:
      'The ego (the ALKS) drives at 60 km/h; a slower car in the lane to its right cuts in once the gap is below $Gap. alks-cut-in.distribution.xosc varies the gap and the cutting-in car speed (3 x 3 concrete scenarios: modular2simple vary, batch, Run Variations).',
    parameters: [
      { name: 'EgoSpeed', type: 'double', value: '16.667', about: 'the ego speed [m/s] (60 km/h)' },
      { name: 'CutInSpeed', type: 'double', value: '11', about: 'the cutting-in car speed [m/s]' },
      { name: 'Gap', type: 'double', value: '20', about: 'the gap when the lane change starts [m]' },
    ],
    entities: [
      { entity: 'Ego', from: ['cut-in', 'ego'], lane: -1, s: 50, speed: '$EgoSpeed' },
      { entity: 'CutInCar', from: ['cut-in', 'adversary'], lane: -2, s: 90, speed: '$CutInSpeed' },
    ],
    uses: [
      {
        module: 'cut-in',
        players: { adversary: 'CutInCar', ego: 'Ego' },
        values: { 'AbsoluteTargetSpeed.value': '$CutInSpeed', 'RelativeDistanceCondition.value': '$Gap' },
      },
    ],
    stopTime: '15',
    distribution: {
      about: 'The gap when the cut-in starts and the cutting-in car speed, 3 x 3 = 9 concrete scenarios of alks-cut-in.xosc.',
      sets: { Gap: ['10', '20', '30'], CutInSpeed: ['8', '11', '14'] },
    },
  },
];

function entityText(module: LibraryModule, name: string, rename: string): string {
  const text = fs.readFileSync(module.file, 'utf8');
  const match = new RegExp(`\\n( *)<ScenarioObject name="${name}">[\\s\\S]*?</ScenarioObject>`).exec(text);
  if (!match) throw new Error(`${module.file} has no ScenarioObject '${name}'`);
  return match[0].replace(`name="${name}"`, `name="${rename}"`).replace(/\n {4}/g, `\n${INDENT.repeat(2)}`);
}

function placementText(placement: Placement): string {
  const i = (depth: number) => INDENT.repeat(depth);
  const orientation =
    placement.heading !== undefined
      ? `\n${i(9)}<Orientation type="relative" h="${placement.heading}" p="0" r="0"/>\n${i(8)}</LanePosition>`
      : '';
  const lane = `<LanePosition roadId="0" laneId="${placement.lane}" s="${placement.s}" offset="${placement.offset ?? 0}"${orientation ? '>' : '/>'}${orientation}`;
  return `
${i(4)}<Private entityRef="${placement.entity}">
${i(5)}<PrivateAction>
${i(6)}<TeleportAction>
${i(7)}<Position>
${i(8)}${lane}
${i(7)}</Position>
${i(6)}</TeleportAction>
${i(5)}</PrivateAction>
${i(5)}<PrivateAction>
${i(6)}<LongitudinalAction>
${i(7)}<SpeedAction>
${i(8)}<SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
${i(8)}<SpeedActionTarget>
${i(9)}<AbsoluteTargetSpeed value="${placement.speed}"/>
${i(8)}</SpeedActionTarget>
${i(7)}</SpeedAction>
${i(6)}</LongitudinalAction>
${i(5)}</PrivateAction>
${i(4)}</Private>`;
}

function skeleton(template: Template, modules: Map<string, LibraryModule>): string {
  const module = (name: string) => {
    const found = modules.get(name);
    if (!found) throw new Error(`no library module '${name}'`);
    return found;
  };
  const parameters = template.parameters
    .map(
      (parameter) =>
        `\n${INDENT.repeat(2)}<ParameterDeclaration name="${parameter.name}" parameterType="${parameter.type}" value="${parameter.value}"/>`,
    )
    .join('');
  const benchGroup = template.uses.length === 0;
  return `<?xml version="1.0" encoding="UTF-8"?>
<!-- library template
name: ${template.name}
title: ${template.title}
summary: ${template.summary}
${template.distribution ? `distribution: ${template.name}.distribution.xosc\n` : ''}${template.parameters.map((parameter) => `parameter ${parameter.name}: ${parameter.about}`).join('\n')}
-->
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-11-27T00:00:00" description="${template.title}" author="modular2simple library"/>
  <ParameterDeclarations>${parameters}
  </ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork>
    <LogicFile filepath="${ROAD}"/>
  </RoadNetwork>
  <Entities>${template.entities.map((placement) => entityText(module(placement.from[0]), placement.from[1], placement.entity)).join('')}
  </Entities>
  <Storyboard>
    <Init>
      <Actions>${template.entities.map(placementText).join('')}
      </Actions>
    </Init>
    <Story name="Story">
      <Act name="Act">${
        benchGroup
          ? `
        <ManeuverGroup name="EgoBehaviour" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="${template.entities[0].entity}"/>
          </Actors>
        </ManeuverGroup>`
          : ''
      }
        <StartTrigger>
          <ConditionGroup>
            <Condition name="ActStart" delay="0" conditionEdge="none">
              <ByValueCondition>
                <SimulationTimeCondition value="0" rule="greaterThan"/>
              </ByValueCondition>
            </Condition>
          </ConditionGroup>
        </StartTrigger>
      </Act>
    </Story>
    <StopTrigger>
      <ConditionGroup>
        <Condition name="End" delay="0" conditionEdge="none">
          <ByValueCondition>
            <SimulationTimeCondition value="${template.stopTime}" rule="greaterThan"/>
          </ByValueCondition>
        </Condition>
      </ConditionGroup>
    </StopTrigger>
  </Storyboard>
</OpenSCENARIO>
`;
}

/** The template's text: the skeleton with each module's group inserted as Insert into Main does, then its values set. */
export function templateText(template: Template, modules: Map<string, LibraryModule>): string {
  let text = skeleton(template, modules);
  for (const use of template.uses) {
    const module = modules.get(use.module);
    if (!module) throw new Error(`no library module '${use.module}'`);
    const inserted = insertModuleGroup(text, module, { players: use.players });
    let group = inserted.text;
    for (const [key, value] of Object.entries(use.values ?? {})) {
      const line = new RegExp(`(<ParameterReference key="${key.replace(/\./g, '\\.')}" value=")[^"]*(")`);
      if (!line.test(group)) throw new Error(`${template.name}: ${use.module} has no key ${key}`);
      group = group.replace(line, `$1${value}$2`);
    }
    text = text.slice(0, inserted.offset) + group + text.slice(inserted.offset);
  }
  return text;
}

function distributionText(template: Template): string | undefined {
  if (!template.distribution) return undefined;
  const sets = Object.entries(template.distribution.sets)
    .map(
      ([name, values]) => `      <DeterministicSingleParameterDistribution parameterName="${name}">
        <DistributionSet>
${values.map((value) => `          <Element value="${value}"/>`).join('\n')}
        </DistributionSet>
      </DeterministicSingleParameterDistribution>`,
    )
    .join('\n');
  return `<?xml version="1.0" encoding="UTF-8"?>
<!-- ${template.distribution.about} -->
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-11-27T00:00:00" description="${template.title}: the distribution" author="modular2simple library"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath="${template.name}.xosc"/>
    <Deterministic>
${sets}
    </Deterministic>
  </ParameterValueDistribution>
</OpenSCENARIO>
`;
}

/** Every template file: name (in library/templates/) and text. */
export async function templateFiles(library: string): Promise<Map<string, string>> {
  const listing = await listLibraries(nodeFileSystem, libraryFolders([], {}, library).slice(-1));
  const modules = new Map(listing.modules.map((module) => [module.name, module]));
  const files = new Map<string, string>();
  for (const template of TEMPLATES) {
    files.set(`${template.name}.xosc`, templateText(template, modules));
    const distribution = distributionText(template);
    if (distribution) files.set(`${template.name}.distribution.xosc`, distribution);
  }
  return files;
}

async function run(check: boolean): Promise<number> {
  const library = builtInLibraryFolder();
  if (!library) throw new Error('no library/ folder beside this project');
  const folder = path.join(library, 'templates');
  fs.mkdirSync(folder, { recursive: true });
  let stale = 0;
  for (const [name, text] of await templateFiles(library)) {
    const file = path.join(folder, name);
    const current = fs.existsSync(file) ? fs.readFileSync(file, 'utf8') : undefined;
    if (current === text) continue;
    stale++;
    if (check) console.log(`differs: ${path.relative(process.cwd(), file)}`);
    else fs.writeFileSync(file, text);
  }
  return check && stale > 0 ? 1 : 0;
}

if (require.main === module) {
  run(process.argv.includes('--check')).then(
    (code) => (process.exitCode = code),
    (error: unknown) => {
      console.error(error);
      process.exitCode = 1;
    },
  );
}

import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { cliPath } from './paths';

export interface CliRun {
  status: number;
  stdout: string;
  stderr: string;
}

/** Subcommands that check files against the OpenSCENARIO schemas. */
const SCHEMA_CHECKING = new Set(['flatten', 'check', '-cmx', '--convert-mosc-to-xosc']);

/** The arguments with the schema check turned off unless asked for: the fixtures here are minimal, not schema-valid. */
export function withoutSchema(args: string[], schema = false): string[] {
  const schemaOff = !schema && SCHEMA_CHECKING.has(args[0]) && !args.some((arg) => arg.startsWith('--schema-version'));
  return schemaOff ? [args[0], '--schema-version=off', ...args.slice(1)] : args;
}

/** Runs the CLI; the schema check is off unless `schema` is set, since the fixtures below are minimal, not schema-valid. */
export function runCli(args: string[], options: { cwd?: string; env?: Record<string, string | undefined>; schema?: boolean } = {}): CliRun {
  const env = { ...process.env, SCENARIO_PATH: '', ...options.env };
  const result = spawnSync(process.execPath, [cliPath, ...withoutSchema(args, options.schema)], {
    cwd: options.cwd,
    env,
    encoding: 'utf8',
    // A check over a whole corpus answers with megabytes of JSON; spawnSync's default 1 MB cuts it (status null).
    maxBuffer: 256 * 1024 * 1024,
  });
  return { status: result.status ?? -1, stdout: result.stdout, stderr: result.stderr };
}

const XML_DECLARATION = '<?xml version="1.0" encoding="UTF-8"?>';

/** The XML declaration without an encoding, as some fixtures write it. */
export const BARE_XML_DECLARATION = '<?xml version="1.0"?>';

export interface FileHeaderParts {
  revMajor?: string;
  revMinor?: string;
  date?: string;
  description?: string;
  author?: string;
}

/** A FileHeader: revision 1.2, dated 2026-01-01, "test" by "test" unless given. */
export function fileHeader(parts: FileHeaderParts = {}): string {
  const { revMajor = '1', revMinor = '2', date = '2026-01-01T00:00:00', description = 'test', author = 'test' } = parts;
  return `<FileHeader revMajor="${revMajor}" revMinor="${revMinor}" date="${date}" description="${description}" author="${author}"/>`;
}

/** An OpenSCENARIO file: the XML declaration, then the root holding `header` and `body` (the root's other children, indented and each ending its line). */
export function openScenarioFile(body: string, header = fileHeader(), declaration = XML_DECLARATION): string {
  return `${declaration}\n<OpenSCENARIO>\n  ${header}\n${body}</OpenSCENARIO>\n`;
}

/** An element `indent` spaces in: nothing when `body` is undefined, `<Name/>` when it is '', else holding `body` (its lines indented by the caller). */
export function element(name: string, body: string | undefined, indent: number, attributes = ''): string {
  if (body === undefined) return '';
  const pad = ' '.repeat(indent);
  return body === '' ? `${pad}<${name}${attributes}/>\n` : `${pad}<${name}${attributes}>\n${body}${pad}</${name}>\n`;
}

/** The children of each root element of a scenario file (indented by the caller); a part left out is not written. */
export interface ScenarioDocumentParts {
  header?: string;
  declaration?: string;
  parameters?: string;
  variables?: string;
  catalogLocations?: string;
  roadNetwork?: string;
  entities: string;
  storyboard: string;
}

/** A scenario file, two spaces per level, its root's children in schema order. */
export function scenarioDocument(parts: ScenarioDocumentParts): string {
  const body =
    element('ParameterDeclarations', parts.parameters, 2) +
    element('VariableDeclarations', parts.variables, 2) +
    element('CatalogLocations', parts.catalogLocations, 2) +
    element('RoadNetwork', parts.roadNetwork, 2) +
    element('Entities', parts.entities, 2) +
    element('Storyboard', parts.storyboard, 2);
  return openScenarioFile(body, parts.header, parts.declaration);
}

/** A catalog file holding `entries` (indented four spaces by the caller). */
export function catalogFile(name: string, entries: string, header = fileHeader(), declaration = XML_DECLARATION): string {
  return openScenarioFile(element('Catalog', entries, 2, ` name="${name}"`), header, declaration);
}

/** A parameter value distribution file of `scenarioFile`: `distributions` are its lines after the ScenarioFile (four spaces in, each ending its line). */
export function distributionFile(
  scenarioFile: string,
  distributions: string,
  header = fileHeader(),
  declaration = XML_DECLARATION,
): string {
  return openScenarioFile(
    element('ParameterValueDistribution', `    <ScenarioFile filepath="${scenarioFile}"/>\n${distributions}`, 2),
    header,
    declaration,
  );
}

/** A Deterministic holding `distributions` (six spaces in, each ending its line). */
export function deterministic(distributions: string): string {
  return element('Deterministic', distributions, 4);
}

/** ParameterDeclaration lines, `indent` spaces in, of [name, type, value]. */
export function parameterDeclarations(parameters: [string, string, string][], indent: number): string {
  return parameters
    .map(([name, type, value]) => `${' '.repeat(indent)}<ParameterDeclaration name="${name}" parameterType="${type}" value="${value}"/>\n`)
    .join('');
}

/** Entities' children: one ScenarioObject without an object per name. */
export function scenarioObjects(names: string[]): string {
  return names.map((name) => `    <ScenarioObject name="${name}"/>\n`).join('');
}

/** What a test sets of vehicleObject's car: where its bounding box's centre is, its length, top speed and deceleration. */
export interface VehicleParts {
  centerX?: string;
  centerZ?: string;
  length?: string;
  maxSpeed?: string;
  maxDeceleration?: string;
}

/** A ScenarioObject holding a schema-valid car named "car" (four spaces in): 4 m long, 50 m/s, 5 m/s² unless given. */
export function vehicleObject(name: string, parts: VehicleParts = {}): string {
  const { centerX = '0', centerZ = '0', length = '4', maxSpeed = '50', maxDeceleration = '5' } = parts;
  return `    <ScenarioObject name="${name}">
      <Vehicle name="car" vehicleCategory="car">
        <BoundingBox><Center x="${centerX}" y="0" z="${centerZ}"/><Dimensions width="2" length="${length}" height="1.5"/></BoundingBox>
        <Performance maxSpeed="${maxSpeed}" maxAcceleration="5" maxDeceleration="${maxDeceleration}"/>
        <Axles>
          <FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.8" positionX="3" positionZ="0.3"/>
          <RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.8" positionX="0" positionZ="0.3"/>
        </Axles>
        <Properties/>
      </Vehicle>
    </ScenarioObject>
`;
}

/** A Storyboard's Init with no actions. */
export const EMPTY_INIT = element('Init', element('Actions', '', 6), 4);

/** A Story of the Storyboard holding `acts`, with its own ParameterDeclarations (lines eight spaces in) when given. */
export function story(name: string, acts: string, declarations?: string): string {
  return `    <Story name="${name}">\n${element('ParameterDeclarations', declarations, 6)}${acts}    </Story>\n`;
}

/**
 * An Act holding `groups` (eight spaces in), then its StartTrigger: empty when `startTrigger` is true, none when
 * it is false, else holding `startTrigger` (its lines ten spaces in).
 */
export function act(name: string, groups: string, startTrigger: boolean | string = true): string {
  const trigger =
    typeof startTrigger === 'string' ? element('StartTrigger', startTrigger, 8) : startTrigger ? '        <StartTrigger/>\n' : '';
  return `      <Act name="${name}">\n${groups}${trigger}      </Act>\n`;
}

/** A minimal scenario (not schema-valid): the entities, then Story S with Act A holding `groups`. */
export function scenario(groups: string, entities: string[] = ['ego', 'car']): string {
  return scenarioDocument({
    header: fileHeader({ revMinor: '0' }),
    entities: scenarioObjects(entities),
    storyboard: story('S', act('A', groups, false)),
  });
}

/** The parts of a schema-valid OpenSCENARIO 1.2 scenario on a road file, one vehicle (Ego) in it, that a case puts in. */
export interface RoadScenarioParts {
  header?: string;
  parameters?: string;
  logicFile?: string;
  trafficSignals?: string;
  /** The Init actions; none when left out. */
  init?: string;
  groups: string[];
}

/** A schema-valid OpenSCENARIO 1.2 scenario on `road.xodr` (or `logicFile`) with one vehicle, Ego, and the parts a case puts in. */
export function roadScenario(parts: RoadScenarioParts): string {
  const body = `  <ParameterDeclarations>${parts.parameters ?? ''}</ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork>
    <LogicFile filepath="${parts.logicFile ?? 'road.xodr'}"/>
    ${parts.trafficSignals ?? ''}
  </RoadNetwork>
  <Entities>
    <ScenarioObject name="Ego"><Vehicle name="car" vehicleCategory="car"><BoundingBox><Center x="0" y="0" z="0"/><Dimensions width="2" length="4" height="1.5"/></BoundingBox><Performance maxSpeed="50" maxAcceleration="5" maxDeceleration="5"/><Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.8" positionX="3" positionZ="0.3"/><RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.8" positionX="0" positionZ="0.3"/></Axles><Properties/></Vehicle></ScenarioObject>
  </Entities>
  <Storyboard>
    <Init>${parts.init === undefined ? '<Actions/>' : `<Actions>${parts.init}</Actions>`}</Init>
    <Story name="S">
      <Act name="A">
        ${parts.groups.join('\n        ')}
        <StartTrigger/>
      </Act>
    </Story>
    <StopTrigger/>
  </Storyboard>
`;
  return openScenarioFile(body, parts.header ?? fileHeader({ description: 's', author: 't' }), BARE_XML_DECLARATION);
}

/**
 * A scenario on `logicFile` (esmini's straight_500m.xodr): Ego on lane -1 of road 1 at s 10, `group` in its Act (or, for 'Drive',
 * a group Drive that sets Ego's speed at once, overridable, default 10 m/s); it stops at 8 s.
 */
export function drivingScenario(logicFile: string, group: string): string {
  const drive = `<ManeuverGroup name="Drive" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><Maneuver name="M"><Event name="E" priority="override"><Action name="A"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed parameterAttributes="value" value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>`;
  const text = roadScenario({
    logicFile,
    init: '<Private entityRef="Ego"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="10" offset="0"/></Position></TeleportAction></PrivateAction></Private>',
    groups: [group === 'Drive' ? drive : group],
  });
  const stop =
    '<StopTrigger><ConditionGroup><Condition name="End" delay="0" conditionEdge="rising"><ByValueCondition><SimulationTimeCondition value="8" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>\n  </Storyboard>';
  assert.match(text, /<StopTrigger\/>\n {2}<\/Storyboard>/);
  return text.replace(/<StopTrigger\/>\n {2}<\/Storyboard>/, stop);
}

/** A simple scenario's group with overridable attributes. */
export function simpleGroup(name: string, body = ''): string {
  return `        <ManeuverGroup name="${name}" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="car"/>
          </Actors>
          <Maneuver name="${name}Maneuver">
            <Event name="Go" priority="overwrite">
              <Action name="Go">
                <SpeedActionTarget>
                  <AbsoluteTargetSpeed parameterAttributes="value" value="10"/>
                </SpeedActionTarget>
                <Position>
                  <WorldPosition parameterAttributes="x, y" x="1" y="2" z="0"/>
                </Position>
              </Action>
              <Condition parameterAttributes="delay" name="Start" delay="0" conditionEdge="rising">
                <EntityRef parameterAttributes="entityRef" entityRef="ego"/>
              </Condition>
${body}            </Event>
          </Maneuver>
        </ManeuverGroup>
`;
}

export interface ReferenceSpec {
  file: string;
  groups: { name: string; parameters?: [string, string][] }[];
}

/** A ManeuverGroup, eight spaces in, with `actor` as its one actor (no Actors when undefined), then `body` (ten spaces in). */
export function maneuverGroup(name: string, actor: string | undefined, body: string): string {
  const actors =
    actor === undefined
      ? ''
      : `          <Actors selectTriggeringEntities="false">\n            <EntityRef entityRef="${actor}"/>\n          </Actors>\n`;
  return `        <ManeuverGroup maximumExecutionCount="1" name="${name}">\n${actors}${body}        </ManeuverGroup>\n`;
}

/** A main file's outer group holding references. */
export function outerGroup(name: string, actor: string | undefined, references: ReferenceSpec[]): string {
  const body = references
    .map(
      (reference) =>
        `          <ScenarioReference scenarioFileName="${reference.file}">\n` +
        reference.groups
          .map(
            (group) =>
              `            <ManeuverGroupReference maneuverGroupName="${group.name}">\n` +
              (group.parameters ?? [])
                .map(([key, value]) => `              <ParameterReference key="${key}" value="${value}"/>\n`)
                .join('') +
              `            </ManeuverGroupReference>\n`,
          )
          .join('') +
        `          </ScenarioReference>\n`,
    )
    .join('');
  return maneuverGroup(name, actor, body);
}

/** Escapes a value for an attribute written by the fixtures above. */
export function xmlAttribute(value: string): string {
  return value.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
}

/** A main file importing group Go of `file` for the outer group Car. */
export function mainOf(file: string, groupName = 'Go'): string {
  return scenario(outerGroup('Car', 'car', [{ file, groups: [{ name: groupName }] }]));
}

/** Fails when a CLI's standard error holds a stack trace or an internal error. */
export function assertNoTrace(stderr: string): void {
  assert.doesNotMatch(stderr, /\n\s+at .*:\d+:\d+\)?/, 'no stack trace');
  assert.doesNotMatch(stderr, /internal error/);
}

/** A .mosc package holding the given files (names relative to its root). */
export async function packageOf(files: Record<string, string>): Promise<Uint8Array> {
  const zip = new JSZip();
  for (const [name, text] of Object.entries(files)) zip.file(name, text);
  return zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
}

/** A catalog of one maneuver, Flip, that sets variable Flag (declared by the scenarios that reference it). */
export const MANEUVER_CATALOG = catalogFile(
  'ManeuverCatalog',
  `    <Maneuver name="Flip">
      <Event name="E" priority="override"><Action name="A"><GlobalAction><VariableAction variableRef="Flag"><SetAction value="true"/></VariableAction></GlobalAction></Action></Event>
    </Maneuver>
`,
  fileHeader({ description: 'maneuvers', author: 't' }),
  BARE_XML_DECLARATION,
);

/** An event, twelve spaces in, that sets one speed at once; `startTrigger` (its lines sixteen spaces in) ends it. */
export function speedEvent(name: string, speed: string, startTrigger = ''): string {
  return `            <Event name="${name}" priority="overwrite">
              <Action name="A">
                <PrivateAction>
                  <LongitudinalAction>
                    <SpeedAction>
                      <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
                      <SpeedActionTarget>
                        <AbsoluteTargetSpeed value="${speed}"/>
                      </SpeedActionTarget>
                    </SpeedAction>
                  </LongitudinalAction>
                </PrivateAction>
              </Action>
${startTrigger}            </Event>
`;
}

/** A Maneuver, ten spaces in, holding `events`. */
export function maneuver(name: string, events: string): string {
  return `          <Maneuver name="${name}">\n${events}          </Maneuver>\n`;
}

/** A group doing one speed change after 5 m, its speed, actor, trigger entity and name as given; `extra` goes after its Actors. */
export function speedChangeGroup(name: string, actor: string, speed: string, trigger = 'ego', extra = ''): string {
  const afterFiveMetres = `              <StartTrigger>
                <ConditionGroup>
                  <Condition name="C" delay="0" conditionEdge="rising">
                    <ByEntityCondition>
                      <TriggeringEntities triggeringEntitiesRule="any">
                        <EntityRef entityRef="${trigger}"/>
                      </TriggeringEntities>
                      <EntityCondition>
                        <TraveledDistanceCondition value="5"/>
                      </EntityCondition>
                    </ByEntityCondition>
                  </Condition>
                </ConditionGroup>
              </StartTrigger>
`;
  return maneuverGroup(name, actor, extra + maneuver('M', speedEvent('E', speed, afterFiveMetres)));
}

/**
 * `folder/p.mosc`: a main.xosc (drivingScenario) that names its road through `$Road` (the first of `roads`) and drives at
 * `$Speed` (10), with `roads` packed beside it; and `folder/speeds.xosc`, a distribution of `values` for `parameter` over it.
 */
export async function roadParameterPackage(
  folder: string,
  roads: Record<string, Uint8Array>,
  parameter: 'Road' | 'Speed',
  values: string[],
): Promise<void> {
  const scenario = drivingScenario('$Road', 'Drive')
    .replace(
      '<ParameterDeclarations></ParameterDeclarations>',
      `<ParameterDeclarations><ParameterDeclaration name="Road" parameterType="string" value="${Object.keys(roads)[0]}"/><ParameterDeclaration name="Speed" parameterType="double" value="10"/></ParameterDeclarations>`,
    )
    .replace('parameterAttributes="value" value="10"', 'value="$Speed"');
  assert.match(scenario, /value="\$Speed"/);
  const zip = new JSZip();
  zip.file('main.xosc', scenario);
  for (const [name, bytes] of Object.entries(roads)) zip.file(name, bytes);
  fs.writeFileSync(path.join(folder, 'p.mosc'), await zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' }));
  const distribution = deterministic(
    `      <DeterministicSingleParameterDistribution parameterName="${parameter}">\n` +
      `        <DistributionSet>${values.map((value) => `<Element value="${value}"/>`).join('')}</DistributionSet>\n` +
      '      </DeterministicSingleParameterDistribution>\n',
  );
  fs.writeFileSync(path.join(folder, 'speeds.xosc'), distributionFile('p.mosc', distribution));
}

/**
 * Puts esmini's SUMO controller on the ego of `file`, a copy of test/fixtures/variations/follow.xosc: its File
 * `../sumo_inputs/e6mini.sumocfg` (as esmini's cut-in_sumo.xosc names it) lies in no test's folder, so esmini says where it looked.
 */
export function addSumoControllerToEgo(file: string): void {
  const scenario = fs.readFileSync(file, 'utf8');
  const controlled = scenario.replace(
    '</Vehicle>\n    </ScenarioObject>\n    <ScenarioObject name="Lead">',
    '</Vehicle>\n      <ObjectController><Controller name="sumo"><Properties><Property name="esminiController" value="SumoController"/><File filepath="../sumo_inputs/e6mini.sumocfg"/></Properties></Controller></ObjectController>\n    </ScenarioObject>\n    <ScenarioObject name="Lead">',
  );
  assert.notEqual(controlled, scenario, `${file} has the ego and Lead of follow.xosc`);
  fs.writeFileSync(file, controlled);
}

/**
 * Puts esmini's ACCController on both vehicles of `root`/follow.xosc (a copy of test/fixtures/variations/follow.xosc), each
 * File named through a `$CfgFile` parameter: the ego's inline (inputs/acc.cfg), the Lead's from a ControllerCatalog entry
 * in catalogs/ (inputs/lead.cfg); both files lie beside the scenario, empty (the ACCController reads none).
 */
export function addParameterControllers(root: string): void {
  const file = path.join(root, 'follow.xosc');
  const controller = (name: string, cfg: string) =>
    `<Controller name="${name}"><ParameterDeclarations><ParameterDeclaration name="CfgFile" parameterType="string" value="${cfg}"/></ParameterDeclarations>` +
    '<Properties><Property name="esminiController" value="ACCController"/><File filepath="$CfgFile"/></Properties></Controller>';
  const [before, ego, lead] = fs.readFileSync(file, 'utf8').split('</Vehicle>\n    </ScenarioObject>');
  assert.ok(lead !== undefined, `${file} has the ego and Lead of follow.xosc`);
  fs.writeFileSync(
    file,
    (
      before +
      `</Vehicle>\n      <ObjectController>${controller('acc', 'inputs/acc.cfg')}</ObjectController>\n    </ScenarioObject>` +
      ego +
      '</Vehicle>\n      <ObjectController><CatalogReference catalogName="ControllerCatalog" entryName="lead"/></ObjectController>\n    </ScenarioObject>' +
      lead
    ).replace(
      '<CatalogLocations/>',
      '<CatalogLocations><ControllerCatalog><Directory path="catalogs"/></ControllerCatalog></CatalogLocations>',
    ),
  );
  fs.mkdirSync(path.join(root, 'catalogs'));
  fs.writeFileSync(
    path.join(root, 'catalogs', 'ControllerCatalog.xosc'),
    '<?xml version="1.0"?>\n<OpenSCENARIO><FileHeader revMajor="1" revMinor="2" date="2026-11-24T00:00:00" description="c" author="t"/>' +
      `<Catalog name="ControllerCatalog">${controller('lead', 'inputs/lead.cfg')}</Catalog></OpenSCENARIO>\n`,
  );
  fs.mkdirSync(path.join(root, 'inputs'));
  for (const name of ['acc.cfg', 'lead.cfg']) fs.writeFileSync(path.join(root, 'inputs', name), '');
}

/**
 * A ManeuverCatalog file (1.0) with a Maneuver per name of `maneuvers`, its Events (the names given) all on the
 * maneuver's one line, each with priority="overwrite" (which ScenarioRunner ignores); the first maneuver on line 5.
 */
export function overwritingManeuverCatalog(maneuvers: Record<string, string[]>): string {
  const event = (name: string) =>
    `<Event name="${name}" priority="overwrite"><Action name="a${name}"><PrivateAction><TeleportAction><Position><WorldPosition x="0" y="0"/></Position></TeleportAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="c${name}" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>`;
  const lines = Object.entries(maneuvers).map(
    ([name, events]) => `    <Maneuver name="${name}">${events.map(event).join('')}</Maneuver>\n`,
  );
  return `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2026-01-01T00:00:00" description="maneuvers" author="test"/>
  <Catalog name="ManeuverCatalog">
${lines.join('')}  </Catalog>
</OpenSCENARIO>
`;
}

/**
 * A modular main (`root`/main.xosc) on `logicFile` whose group Controlled imports group Control of control.xosc, beside it:
 * Control assigns Ego the ControllerCatalog entry 'acc' (catalogs/ControllerCatalog.xosc, esmini's ACCController), whose File
 * is `inputs/acc.cfg` written as it stands, and sets Ego's speed. The main names no ControllerCatalog itself: the flattening
 * carries control.xosc's. The File is left for the case to write (`root`/inputs/acc.cfg, beside the main, where esmini looks).
 * `folder`: control.xosc and its catalogs lie in that sub-folder of `root` instead, which the main names.
 */
export function importedCatalogController(root: string, logicFile: string, folder = ''): { main: string; module: string } {
  const trigger =
    '<StartTrigger><ConditionGroup><Condition name="At0" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>';
  const control =
    '<ManeuverGroup name="Control" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><Maneuver name="CM">' +
    `<Event name="Assign" priority="override"><Action name="AssignAcc"><PrivateAction><ControllerAction><AssignControllerAction>\n          <CatalogReference catalogName="ControllerCatalog" entryName="acc"/>\n        </AssignControllerAction></ControllerAction></PrivateAction></Action>${trigger}</Event>` +
    `<Event name="Go" priority="parallel"><Action name="Speed"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>${trigger}</Event>` +
    '</Maneuver></ManeuverGroup>';
  fs.mkdirSync(path.join(root, folder), { recursive: true });
  const module = path.join(root, folder, 'control.xosc');
  fs.writeFileSync(
    module,
    drivingScenario(logicFile, control).replace(
      '<CatalogLocations/>',
      '<CatalogLocations><ControllerCatalog><Directory path="catalogs"/></ControllerCatalog></CatalogLocations>',
    ),
  );
  const main = path.join(root, 'main.xosc');
  fs.writeFileSync(
    main,
    drivingScenario(
      logicFile,
      `<ManeuverGroup name="Controlled" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><ScenarioReference scenarioFileName="${folder ? `${folder}/` : ''}control.xosc"><ManeuverGroupReference maneuverGroupName="Control"/></ScenarioReference></ManeuverGroup>`,
    ),
  );
  fs.mkdirSync(path.join(root, folder, 'catalogs'), { recursive: true });
  fs.writeFileSync(
    path.join(root, folder, 'catalogs', 'ControllerCatalog.xosc'),
    catalogFile(
      'ControllerCatalog',
      '    <Controller name="acc"><Properties><Property name="esminiController" value="ACCController"/><File filepath="inputs/acc.cfg"/></Properties></Controller>\n',
    ),
  );
  return { main, module };
}

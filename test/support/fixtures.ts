import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import JSZip from 'jszip';
import { cliPath } from './paths';

export interface CliRun {
  status: number;
  stdout: string;
  stderr: string;
}

/** Subcommands that check files against the OpenSCENARIO schemas. */
const SCHEMA_CHECKING = new Set(['flatten', 'check', '-cmx', '--convert-mosc-to-xosc']);

/** Runs the CLI; the schema check is off unless `schema` is set, since the fixtures below are minimal, not schema-valid. */
/** The arguments with the schema check turned off unless asked for: the fixtures here are minimal, not schema-valid. */
export function withoutSchema(args: string[], schema = false): string[] {
  const schemaOff = !schema && SCHEMA_CHECKING.has(args[0]) && !args.some((arg) => arg.startsWith('--schema-version'));
  return schemaOff ? [args[0], '--schema-version=off', ...args.slice(1)] : args;
}

export function runCli(args: string[], options: { cwd?: string; env?: Record<string, string | undefined>; schema?: boolean } = {}): CliRun {
  const env = { ...process.env, SCENARIO_PATH: '', ...options.env };
  const result = spawnSync(process.execPath, [cliPath, ...withoutSchema(args, options.schema)], {
    cwd: options.cwd,
    env,
    encoding: 'utf8',
  });
  return { status: result.status ?? -1, stdout: result.stdout, stderr: result.stderr };
}

const HEADER = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2026-01-01T00:00:00" description="test" author="test"/>
  <Entities>
{ENTITIES}  </Entities>
  <Storyboard>
    <Story name="S">
      <Act name="A">
{GROUPS}      </Act>
    </Story>
  </Storyboard>
</OpenSCENARIO>
`;

export function scenario(groups: string, entities: string[] = ['ego', 'car']): string {
  const declared = entities.map((name) => `    <ScenarioObject name="${name}"/>\n`).join('');
  return HEADER.replace('{ENTITIES}', () => declared).replace('{GROUPS}', () => groups);
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
  return `<?xml version="1.0"?>
<OpenSCENARIO>
  ${parts.header ?? '<FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="s" author="t"/>'}
  <ParameterDeclarations>${parts.parameters ?? ''}</ParameterDeclarations>
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
</OpenSCENARIO>
`;
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

/** A main file's outer group holding references. */
export function outerGroup(name: string, actor: string | undefined, references: ReferenceSpec[]): string {
  const actors =
    actor === undefined
      ? ''
      : `          <Actors selectTriggeringEntities="false">\n            <EntityRef entityRef="${actor}"/>\n          </Actors>\n`;
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
  return `        <ManeuverGroup maximumExecutionCount="1" name="${name}">\n${actors}${body}        </ManeuverGroup>\n`;
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
export const MANEUVER_CATALOG = `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="maneuvers" author="t"/>
  <Catalog name="ManeuverCatalog">
    <Maneuver name="Flip">
      <Event name="E" priority="override"><Action name="A"><GlobalAction><VariableAction variableRef="Flag"><SetAction value="true"/></VariableAction></GlobalAction></Action></Event>
    </Maneuver>
  </Catalog>
</OpenSCENARIO>
`;

/** A group doing one speed change after 5 m, its speed, actor, trigger entity and name as given; `extra` goes after its Actors. */
export function speedChangeGroup(name: string, actor: string, speed: string, trigger = 'ego', extra = ''): string {
  return `        <ManeuverGroup maximumExecutionCount="1" name="${name}">
          <Actors selectTriggeringEntities="false">
            <EntityRef entityRef="${actor}"/>
          </Actors>
${extra}          <Maneuver name="M">
            <Event name="E" priority="overwrite">
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
              <StartTrigger>
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
            </Event>
          </Maneuver>
        </ManeuverGroup>
`;
}

/**
 * Files that break each rule of ASAM's Quality Checker for OpenSCENARIO XML that the project maps a
 * problem to (core/rules.ts), and which project code and rule uid each problem reports (issue 18, item 2).
 */

import { roadScenario, RoadScenarioParts } from './fixtures';
import { SIGNAL_ROAD as ROAD } from './roads';

const HEADER = '<FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="rules" author="t"/>';

function event(name: string, action: string): string {
  return `<Event name="${name}" priority="override"><Action name="${name}Action">${action}</Action><StartTrigger/></Event>`;
}

function group(name: string, actors: string, events: string[]): string {
  return `<ManeuverGroup name="${name}" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false">${actors}</Actors>
          <Maneuver name="${name}Maneuver">
            ${events.join('\n            ')}
          </Maneuver>
        </ManeuverGroup>`;
}

const CUSTOM = '<UserDefinedAction><CustomCommandAction type="t"/></UserDefinedAction>';
const EGO = '<EntityRef entityRef="Ego"/>';

/** A 1.2 scenario on road.xodr with the parts a case puts in, under this file's header. */
function scenario(parts: RoadScenarioParts): string {
  return roadScenario({ ...parts, header: parts.header ?? HEADER });
}

const CLEAN = scenario({ groups: [group('G', EGO, [event('E', CUSTOM)])] });

const SIGNALS = `<TrafficSignals>
      <TrafficSignalController name="Ctrl">
        <Phase name="go" duration="-1"><TrafficSignalState trafficSignalId="101" state="on"/></Phase>
      </TrafficSignalController>
    </TrafficSignals>`;

const infrastructure = (action: string) =>
  `<GlobalAction><InfrastructureAction><TrafficSignalAction>${action}</TrafficSignalAction></InfrastructureAction></GlobalAction>`;

/** Each file breaks the rules of ASAM's Quality Checker the comment names (road.xodr is the road network of signals.xosc). */
export const RULE_FILES: Record<string, string> = {
  // xml.valid_xml_document
  'broken.xosc': '<OpenSCENARIO><FileHeader',
  // xml.root_tag_is_openscenario
  'root.xosc': CLEAN.replace('<OpenSCENARIO>', '<OpenScenario>').replace('</OpenSCENARIO>', '</OpenScenario>'),
  // xml.fileheader_is_present
  'headerless.xosc': CLEAN.replace(HEADER, ''),
  // xml.version_is_defined (a missing revMinor, a revMajor not an unsignedShort), xml.valid_schema (the FileHeader's date)
  'version.xosc': CLEAN.replace(HEADER, '<FileHeader revMajor="one" date="yesterday" description="rules" author="t"/>'),
  // reference_control: resolvable_entity_references, resolvable_variable_reference, resolvable_storyboard_element_reference,
  // unique_element_names_on_same_level, valid_actor_reference_in_private_actions; data_type.allowed_operators
  'references.xosc': scenario({
    parameters: '<ParameterDeclaration name="Half" parameterType="double" value="${pi / 2}"/>',
    groups: [
      group('G', '<EntityRef entityRef="Nobody"/>', [
        event('Twice', CUSTOM),
        event('Twice', '<GlobalAction><VariableAction variableRef="NoVariable"><SetAction value="1"/></VariableAction></GlobalAction>'),
      ]),
      group('NoActor', '', [
        event('Wait', '<PrivateAction><ActivateControllerAction longitudinal="false"/></PrivateAction>'),
        `<Event name="Late" priority="override"><Action name="LateAction">${CUSTOM}</Action><StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="NoEvent" state="endTransition"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>`,
      ]),
    ],
  }),
  // reference_control: resolvable_signal_id_in_traffic_signal_state_action, resolvable_traffic_signal_controller_by_traffic_signal_controller_ref;
  // data_type: non_negative_transition_time_in_light_state_action, positive_duration_in_phase
  'signals.xosc': scenario({
    trafficSignals: SIGNALS,
    groups: [
      group('G', EGO, [
        event('Signal', infrastructure('<TrafficSignalStateAction name="999" state="off;off;on"/>')),
        event('Controller', infrastructure('<TrafficSignalControllerAction trafficSignalControllerRef="NoController" phase="go"/>')),
        event(
          'Light',
          '<PrivateAction><AppearanceAction><LightStateAction transitionTime="-0.5"><LightType><VehicleLight vehicleLightType="headLights"/></LightType><LightState mode="on"/></LightStateAction></AppearanceAction></PrivateAction>',
        ),
      ]),
    ],
  }),
  'road.xodr': ROAD,
  // reference_control.uniquely_resolvable_entity_references, parameters.valid_parameter_declaration_in_catalogs
  'VehicleCatalog.xosc': `<?xml version="1.0"?>
<OpenSCENARIO>
  ${HEADER}
  <Catalog name="VehicleCatalog">
    <Vehicle name="car_white" vehicleCategory="car" mass="$Mass"/>
    <Vehicle name="car_white" vehicleCategory="car"/>
  </Catalog>
</OpenSCENARIO>
`,
};

const QC = 'asam.net:xosc:';

/** `[file, project code, rule uid]` of problems the files above report: the QC uid where ASAM's checker has the rule, undefined for the project's own. */
export const EXPECTED_RULES: readonly [file: string, code: string, qcRule: string | undefined][] = [
  ['broken.xosc', 'xml', `${QC}1.0.0:xml.valid_xml_document`],
  ['root.xosc', 'schema-unknown-element', `${QC}1.0.0:xml.root_tag_is_openscenario`],
  ['headerless.xosc', 'schema-missing-element', `${QC}1.0.0:xml.fileheader_is_present`],
  ['version.xosc', 'schema-missing-attribute', `${QC}1.0.0:xml.version_is_defined`],
  ['version.xosc', 'schema-value', `${QC}1.0.0:xml.version_is_defined`],
  ['version.xosc', 'schema-value', `${QC}1.0.0:xml.valid_schema`],
  ['version.xosc', 'schema-version', undefined],
  ['references.xosc', 'undeclared-entity', `${QC}1.2.0:reference_control.resolvable_entity_references`],
  ['references.xosc', 'undeclared-variable', `${QC}1.2.0:reference_control.resolvable_variable_reference`],
  ['references.xosc', 'unknown-storyboard-element', `${QC}1.2.0:reference_control.resolvable_storyboard_element_reference`],
  ['references.xosc', 'duplicate-name', `${QC}1.2.0:reference_control.unique_element_names_on_same_level`],
  ['references.xosc', 'no-actor', `${QC}1.2.0:reference_control.valid_actor_reference_in_private_actions`],
  ['references.xosc', 'nonstandard-expression', `${QC}1.2.0:data_type.allowed_operators`],
  ['references.xosc', 'unused-parameter', undefined],
  ['signals.xosc', 'unknown-traffic-signal', `${QC}1.2.0:reference_control.resolvable_signal_id_in_traffic_signal_state_action`],
  [
    'signals.xosc',
    'unknown-traffic-signal-controller',
    `${QC}1.2.0:reference_control.resolvable_traffic_signal_controller_by_traffic_signal_controller_ref`,
  ],
  ['signals.xosc', 'negative-transition-time', `${QC}1.2.0:data_type.non_negative_transition_time_in_light_state_action`],
  ['signals.xosc', 'non-positive-phase-duration', `${QC}1.2.0:data_type.positive_duration_in_phase`],
  ['VehicleCatalog.xosc', 'duplicate-catalog-entry', `${QC}1.2.0:reference_control.uniquely_resolvable_entity_references`],
  ['VehicleCatalog.xosc', 'undeclared-catalog-parameter', `${QC}1.2.0:parameters.valid_parameter_declaration_in_catalogs`],
];

/** Where ASAM describes a rule of its checker: checker_bundle_doc.md, one section per checker. */
export function qcRuleHref(uid: string): string {
  const rule = uid.slice(uid.lastIndexOf(':') + 1).replace('.', '_');
  return `https://github.com/asam-ev/qc-openscenarioxml/blob/main/checker_bundle_doc.md#check_asam_xosc_${rule}`;
}

/**
 * The rules of ASAM's Quality Checker for OpenSCENARIO XML (asam-ev/qc-openscenarioxml, checker_bundle_doc.md)
 * that this project's diagnostics map to, so that a report names the rule a team already knows.
 */
export const QC = {
  validXml: 'asam.net:xosc:1.0.0:xml.valid_xml_document',
  rootTag: 'asam.net:xosc:1.0.0:xml.root_tag_is_openscenario',
  fileHeader: 'asam.net:xosc:1.0.0:xml.fileheader_is_present',
  versionDefined: 'asam.net:xosc:1.0.0:xml.version_is_defined',
  validSchema: 'asam.net:xosc:1.0.0:xml.valid_schema',
  entityReferences: 'asam.net:xosc:1.2.0:reference_control.resolvable_entity_references',
  uniqueEntityReferences: 'asam.net:xosc:1.2.0:reference_control.uniquely_resolvable_entity_references',
  variableReference: 'asam.net:xosc:1.2.0:reference_control.resolvable_variable_reference',
  storyboardReference: 'asam.net:xosc:1.2.0:reference_control.resolvable_storyboard_element_reference',
  uniqueNames: 'asam.net:xosc:1.2.0:reference_control.unique_element_names_on_same_level',
  catalogParameters: 'asam.net:xosc:1.2.0:parameters.valid_parameter_declaration_in_catalogs',
  signalId: 'asam.net:xosc:1.2.0:reference_control.resolvable_signal_id_in_traffic_signal_state_action',
  signalController: 'asam.net:xosc:1.2.0:reference_control.resolvable_traffic_signal_controller_by_traffic_signal_controller_ref',
  privateActionActor: 'asam.net:xosc:1.2.0:reference_control.valid_actor_reference_in_private_actions',
  allowedOperators: 'asam.net:xosc:1.2.0:data_type.allowed_operators',
  transitionTime: 'asam.net:xosc:1.2.0:data_type.non_negative_transition_time_in_light_state_action',
  phaseDuration: 'asam.net:xosc:1.2.0:data_type.positive_duration_in_phase',
} as const;

/** An ASAM Quality Checker rule uid this project maps a problem to. */
export type QcRuleUid = (typeof QC)[keyof typeof QC];

/** What each ASAM Quality Checker rule requires, in our words (one rule may stand for several codes). */
export const QC_RULE_DESCRIPTIONS: Record<QcRuleUid, string> = {
  [QC.validXml]: 'The file is a well-formed XML document.',
  [QC.rootTag]: 'The root element is <OpenSCENARIO>.',
  [QC.fileHeader]: 'The root element has a <FileHeader>.',
  [QC.versionDefined]: 'The FileHeader states revMajor and revMinor, each an unsignedShort.',
  [QC.validSchema]: 'The file is valid against the ASAM OpenSCENARIO schema of its version.',
  [QC.entityReferences]: 'Every entity reference resolves to a declared entity.',
  [QC.uniqueEntityReferences]: 'Every entity reference resolves to exactly one element.',
  [QC.variableReference]: 'Every variable reference resolves to a declared variable.',
  [QC.storyboardReference]: 'Every storyboard element reference resolves to a storyboard element.',
  [QC.uniqueNames]: 'The names of the elements on one level (the children of one element) are unique.',
  [QC.catalogParameters]: 'A catalog entry declares every parameter it uses.',
  [QC.signalId]:
    'The signal a TrafficSignalStateAction names exists in the road network (or a TrafficSignalController of the scenario sets it).',
  [QC.signalController]: 'A trafficSignalControllerRef names a TrafficSignalController of the scenario.',
  [QC.privateActionActor]: 'A ManeuverGroup whose maneuvers hold private actions names actors for them.',
  [QC.allowedOperators]: 'Expressions use only the operators and functions the standard defines.',
  [QC.transitionTime]: 'The transitionTime of a LightStateAction is not negative.',
  [QC.phaseDuration]: 'The duration of a traffic-signal Phase is positive.',
};

/**
 * The rule a problem code stands for: a one-line description and, where ASAM's Quality Checker has the
 * same rule, its uid.
 */
export interface Rule {
  description: string;
  /** The ASAM Quality Checker rule uid, `asam.net:xosc:<version>:<group>.<rule>`. */
  qcRule?: QcRuleUid;
}

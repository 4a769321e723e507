import { ProblemCode } from './problems';

/**
 * The rule each problem code stands for: a one-line description and, where ASAM's Quality Checker for
 * OpenSCENARIO XML (asam-ev/qc-openscenarioxml, checker_bundle_doc.md) has the same rule, its uid, so
 * that a report names the rule a team already knows.
 */
export interface Rule {
  description: string;
  /** The ASAM Quality Checker rule uid, `asam.net:xosc:<version>:<group>.<rule>`. */
  qcRule?: string;
}

const QC = {
  validXml: 'asam.net:xosc:1.0.0:xml.valid_xml_document',
  validSchema: 'asam.net:xosc:1.0.0:xml.valid_schema',
  entityReferences: 'asam.net:xosc:1.2.0:reference_control.resolvable_entity_references',
  uniqueEntityReferences: 'asam.net:xosc:1.2.0:reference_control.uniquely_resolvable_entity_references',
  variableReference: 'asam.net:xosc:1.2.0:reference_control.resolvable_variable_reference',
  storyboardReference: 'asam.net:xosc:1.2.0:reference_control.resolvable_storyboard_element_reference',
} as const;

/** What each ASAM Quality Checker rule requires, in our words (one rule may stand for several codes). */
export const QC_RULE_DESCRIPTIONS: Record<(typeof QC)[keyof typeof QC], string> = {
  [QC.validXml]: 'The file is a well-formed XML document.',
  [QC.validSchema]: 'The file is valid against the ASAM OpenSCENARIO schema of its version.',
  [QC.entityReferences]: 'Every entity reference resolves to a declared entity.',
  [QC.uniqueEntityReferences]: 'Every entity reference resolves to exactly one element.',
  [QC.variableReference]: 'Every variable reference resolves to a declared variable.',
  [QC.storyboardReference]: 'Every storyboard element reference resolves to a storyboard element.',
};

/** Every code has an entry: a new code does not compile until it says what rule it is. */
export const RULES: Record<ProblemCode, Rule> = {
  xml: { description: 'The file is well-formed XML.', qcRule: QC.validXml },
  io: { description: 'The file can be read.' },
  'bad-package': { description: 'A .mosc package is a readable ZIP archive holding main.xosc.' },
  'missing-file': { description: 'A scenarioFileName resolves to a file (SPEC 3).' },
  'invalid-reference': { description: 'A ScenarioReference is written as SPEC 2 says.' },
  'xosc-fallback': { description: 'A NAME.xosc reference resolved only through the NAME.mosc fallback.' },
  'unknown-group': { description: 'A maneuverGroupName names a ManeuverGroup of the referenced file.' },
  'ambiguous-group': { description: 'A maneuverGroupName names exactly one ManeuverGroup.' },
  'duplicate-group': { description: 'A referenced file has no two ManeuverGroups of the same name.' },
  'unknown-key': { description: 'A ParameterReference key matches an attribute listed in parameterAttributes.' },
  'no-default': { description: 'An attribute listed in parameterAttributes has a default value.' },
  'unknown-parameter-attribute': { description: 'A parameterAttributes entry names an attribute of its element.' },
  'missing-attribute': { description: 'A reference element has its required attributes.' },
  'no-entity-ref': { description: 'A ManeuverGroup holding a ScenarioReference names its actor with an EntityRef.' },
  'reference-outside-group': { description: 'A ScenarioReference stands inside a ManeuverGroup.' },
  cycle: { description: 'References do not form a cycle.' },
  'undeclared-entity': { description: 'An entity reference names a declared entity.', qcRule: QC.entityReferences },
  'source-errors': { description: 'A referenced file has no errors of its own.' },
  'schema-unknown-element': { description: 'Every element is one the ASAM schema allows there.', qcRule: QC.validSchema },
  'schema-unknown-attribute': { description: 'Every attribute is one the ASAM schema allows on its element.', qcRule: QC.validSchema },
  'schema-missing-element': { description: 'Every element the ASAM schema requires is present.', qcRule: QC.validSchema },
  'schema-missing-attribute': { description: 'Every attribute the ASAM schema requires is present.', qcRule: QC.validSchema },
  'schema-order': { description: 'Child elements stand in the order the ASAM schema gives.', qcRule: QC.validSchema },
  'schema-cardinality': { description: 'Child elements occur as often as the ASAM schema allows.', qcRule: QC.validSchema },
  'schema-value': { description: "An attribute's value fits its ASAM schema type.", qcRule: QC.validSchema },
  'schema-deprecated': { description: 'No deprecated element, attribute or value is used.' },
  'schema-version': { description: "The FileHeader names an OpenSCENARIO version the project knows." },
  'too-large': { description: 'A file or a flattened result stays within the size bounds.' },
  'too-deep': { description: 'A chain of references stays within the depth bound.' },
  'undeclared-parameter': { description: 'A $name names a declared parameter.' },
  'unused-parameter': { description: 'A declared parameter is used.' },
  'duplicate-parameter': { description: 'A parameter is declared once in its scope.' },
  'expression-syntax': { description: 'A ${...} expression follows the standard\'s grammar.' },
  'type-mismatch': { description: "A value converts to the type that uses it." },
  'division-by-zero': { description: 'An expression does not divide by zero.' },
  'nonstandard-expression': { description: 'An expression uses only what the standard defines.' },
  'catalog-directory': { description: 'A CatalogLocations directory exists.' },
  'unknown-catalog': { description: 'A catalogName names a catalog found in the CatalogLocations.' },
  'unknown-catalog-entry': { description: 'An entryName names an entry of its catalog.' },
  'unknown-assigned-parameter': { description: 'A ParameterAssignment names a parameter the catalog entry declares.' },
  'unknown-storyboard-element': { description: 'A storyboardElementRef names a storyboard element.', qcRule: QC.storyboardReference },
  'ambiguous-reference': { description: 'A reference resolves to exactly one element.', qcRule: QC.uniqueEntityReferences },
  'undeclared-variable': { description: 'A variableRef names a declared variable.', qcRule: QC.variableReference },
  'key-mixed-defaults': { description: 'The attributes one key sets share one default.' },
  'parameter-conflict': { description: "A carried declaration agrees with the main file's declaration of the same name (SPEC 11)." },
  'catalog-location-conflict': { description: "A carried catalog location agrees with the main file's (SPEC 11)." },
  'renamed-reference': { description: 'A reference to a group that flattening renames is updated.' },
  simulator: { description: 'The selected simulator runs what the file uses.' },
  'lenient-value': { description: "A value is written in the standard's form, not only in a form esmini also accepts (SPEC 12)." },
  'simulator-value': { description: 'A value is the same in the standard and in the selected simulator.' },
  overflow: { description: "A number stays within its type's range (IEEE double, int, unsignedInt, unsignedShort)." },
  'file-path': { description: 'A file path of a written scenario names, from where it is written, the file its source named (SPEC 11.6).' },
  distribution: { description: 'A ParameterValueDistribution expands: its ScenarioFile resolves, its values fit their parameters, its ranges and steps make sense.' },
  'unknown-distribution-parameter': { description: "A distribution's parameterName is a parameter its ScenarioFile declares at its root." },
};

/** The id a report gives a problem's rule: the ASAM Quality Checker uid where one exists, the project's code otherwise. */
export function ruleIdOf(code: ProblemCode): string {
  return RULES[code].qcRule ?? `modular2simple:${code}`;
}

/** The description of a rule id as `ruleIdOf` gives it. */
export function ruleDescription(ruleId: string, code: ProblemCode): string {
  return Object.hasOwn(QC_RULE_DESCRIPTIONS, ruleId) ? QC_RULE_DESCRIPTIONS[ruleId as keyof typeof QC_RULE_DESCRIPTIONS] : RULES[code].description;
}

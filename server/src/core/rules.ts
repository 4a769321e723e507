import { DefinedCode, DIAGNOSTICS, QC, QC_RULE_DESCRIPTIONS, QcRuleUid, Rule } from './diagnostics';
import { Problem, ProblemCode } from './problems';

export { QC_RULE_DESCRIPTIONS };
export type { QcRuleUid, Rule };

/** Every code has an entry: a new code does not compile until it says what rule it is. */
export const RULES: Record<ProblemCode, Rule> = Object.fromEntries(
  DIAGNOSTICS.map((definition) => [definition.code, definition.rule]),
) as Record<DefinedCode, Rule>;

/** What `ruleOf` reads of a problem: its code, and for the rules that depend on it, its data and subject. */
export type RuledProblem = Pick<Problem, 'code' | 'data' | 'subject'>;

/** The rule a problem breaks, as the editor, `check --format json`, SARIF and qc-bundle name it. */
export interface ProblemRule {
  /** The ASAM Quality Checker uid where that checker has the rule, `modular2simple:<code>` otherwise. */
  id: string;
  /** The ASAM Quality Checker uid, where that checker has the rule. */
  qcRule?: QcRuleUid;
  description: string;
  /** Where the rule is described: ASAM's checker documentation for its rules; undefined for the project's own. */
  helpUri?: string;
}

/** The FileHeader attributes that state the version (ASAM QC xml.version_is_defined). */
const VERSION_ATTRIBUTES: readonly string[] = ['revMajor', 'revMinor'];

function missingNames(problem: RuledProblem): readonly string[] {
  const data = problem.data;
  return data && 'missing' in data && Array.isArray(data.missing) ? data.missing : [];
}

/**
 * ASAM's checker splits three schema rules off its valid_schema rule; a problem of one of them names
 * that rule instead of its code's: the root element, a missing FileHeader, the FileHeader's version. An
 * expression-syntax problem about an operator the standard lacks names its allowed_operators rule.
 */
function specificQcRule(problem: RuledProblem): QcRuleUid | undefined {
  const subject = problem.subject;
  if (!subject) return undefined;
  if (problem.code === 'schema-unknown-element' && subject.root) return QC.rootTag;
  if (problem.code === 'schema-missing-element' && subject.root && subject.absent?.includes('FileHeader')) return QC.fileHeader;
  // An operator, function or character the standard's expressions lack: ASAM's checker's allowed_operators (allowed_operators.py:29-42).
  if (problem.code === 'expression-syntax' && subject.token !== undefined) return QC.allowedOperators;
  // A catalog entry's parameter without a default value: ASAM's checker's valid_parameter_declaration_in_catalogs.
  if (problem.code === 'type-mismatch' && subject.noCatalogDefault) return QC.catalogParameters;
  // The schema allows a FileHeader only as the root's child: any FileHeader it reports on is that one.
  if (subject.element !== 'FileHeader') return undefined;
  if (problem.code === 'schema-missing-attribute' && missingNames(problem).some((name) => VERSION_ATTRIBUTES.includes(name)))
    return QC.versionDefined;
  if (problem.code === 'schema-value' && subject.attribute !== undefined && VERSION_ATTRIBUTES.includes(subject.attribute))
    return QC.versionDefined;
  return undefined;
}

/** Where ASAM describes its Quality Checker rules: one section per checker, `check_asam_xosc_<group>_<rule>`. */
const QC_CHECKER_DOC = 'https://github.com/asam-ev/qc-openscenarioxml/blob/main/checker_bundle_doc.md';

function qcHelpUri(uid: QcRuleUid): string {
  const rule = uid.slice(uid.lastIndexOf(':') + 1).replace('.', '_');
  return `${QC_CHECKER_DOC}#check_asam_xosc_${rule}`;
}

/** The rule of a problem: the one place that decides it (per problem, where ASAM's checker has a more specific rule than the code's). */
export function ruleOf(problem: RuledProblem): ProblemRule {
  const qcRule = specificQcRule(problem) ?? RULES[problem.code].qcRule;
  if (!qcRule) return { id: `modular2simple:${problem.code}`, description: RULES[problem.code].description };
  return { id: qcRule, qcRule, description: QC_RULE_DESCRIPTIONS[qcRule], helpUri: qcHelpUri(qcRule) };
}

/** The rule id of a code's problems in general (`ruleOf` of a problem may name a more specific one). */
export function ruleIdOf(code: ProblemCode): string {
  return ruleOf({ code }).id;
}

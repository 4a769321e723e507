import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener } from '../core/flatten';
import { Problem, Severity, uniqueProblems } from '../core/problems';
import { ProblemRule, ruleOf, RuledProblem } from '../core/rules';
import { displayRef } from '../core/sources';
import { decodeUtf8 } from '../core/text';
import { attributeValue, elementAt, escapeAttributeValue, parseXml, XmlDocument, XmlElement } from '../core/xml';
import { CliCommand, CliOutput, ExitCode, InputError, parseCommandLine, UsageError, VERSION, write } from './common';
import { mainOf, storeForInputs } from './inputs';

/**
 * `modular2simple qc-bundle -c CONFIG.xml [--out-dir DIR]`: `check` as a checker bundle of ASAM's
 * Quality Checker Framework (asam-ev/qc-framework, doc/manual: file_formats.md, manifest_file.md,
 * writing_user_defined_modules.md). The framework hands a bundle its configuration file (a `Config`
 * with `Param name="InputFile"` and a `CheckerBundle application="modular2simple"`) and an output
 * folder; the bundle writes its `.xqar` result file there (`CheckerResults` > `CheckerBundle` >
 * `Checker` per rule > `Issue` with level 1 error, 2 warning, 3 information and its `Locations`).
 */

/** The `application` a configuration names this bundle by (the manifest's `name`). */
export const BUNDLE_NAME = 'modular2simple';
const DEFAULT_RESULT_FILE = `${BUNDLE_NAME}.xqar`;

const LEVEL: Record<Severity, number> = { error: 1, warning: 2, information: 3, hint: 3 };

export interface BundleConfig {
  inputFile: string;
  /** A file name, no folder (the framework's rule): where in the output folder the result goes. */
  resultFile: string;
  /** The checkers the configuration names for this bundle; undefined: all of them. */
  checkerIds: Set<string> | undefined;
  params: { name: string; value: string }[];
}

function paramsOf(element: XmlElement): { name: string; value: string }[] {
  return element.children
    .filter((child) => child.name === 'Param')
    .map((param) => ({ name: attributeValue(param, 'name') ?? '', value: attributeValue(param, 'value') ?? '' }));
}

/** Reads a framework configuration file; throws InputError for one this bundle cannot run from. */
export function readBundleConfig(text: string, configPath: string): BundleConfig {
  const document = parseXml(text);
  const root = document.root;
  if (!root || root.name !== 'Config' || document.problems.some((problem) => problem.severity === 'error'))
    throw new InputError(`${configPath}: not a Quality Checker Framework configuration (an XML <Config>)`);
  const bundle = root.children.find((child) => child.name === 'CheckerBundle' && attributeValue(child, 'application') === BUNDLE_NAME);
  const globalParams = paramsOf(root);
  const bundleParams = bundle ? paramsOf(bundle) : [];
  // A bundle's own parameter wins over the configuration's global one of the same name.
  const param = (name: string) =>
    bundleParams.find((entry) => entry.name === name)?.value ?? globalParams.find((entry) => entry.name === name)?.value;
  const inputFile = param('InputFile');
  if (!inputFile) throw new InputError(`${configPath}: no <Param name="InputFile" value="..."/>`);
  const resultFile = param('resultFile') ?? DEFAULT_RESULT_FILE;
  if (path.basename(resultFile) !== resultFile || !resultFile.endsWith('.xqar'))
    throw new InputError(`${configPath}: resultFile '${resultFile}' must be a file name ending in .xqar, with no folder`);
  const checkers =
    bundle?.children.filter((child) => child.name === 'Checker').map((checker) => attributeValue(checker, 'checkerId') ?? '') ?? [];
  const merged = new Map([...globalParams, ...bundleParams].map((entry) => [entry.name, entry.value]));
  return {
    inputFile: path.resolve(path.dirname(configPath), inputFile),
    resultFile,
    checkerIds: checkers.length > 0 ? new Set(checkers) : undefined,
    params: [...merged].map(([name, value]) => ({ name, value })),
  };
}

/** The rule uid a result file names: the ASAM uid, or one of the same form for the project's own rules. */
export function qcRuleUid(problem: RuledProblem): string {
  return ruleOf(problem).qcRule ?? `${BUNDLE_NAME}:xosc:1.0.0:${BUNDLE_NAME}.${problem.code.replace(/-/g, '_')}`;
}

/** One checker per rule: its id is the rule's name. */
export function checkerIdOf(problem: RuledProblem): string {
  const qcRule = ruleOf(problem).qcRule;
  const name = qcRule ? qcRule.slice(qcRule.lastIndexOf(':') + 1).replace(/\./g, '_') : problem.code.replace(/-/g, '_');
  return `check_${BUNDLE_NAME}_${name}`;
}

/** `/OpenSCENARIO/Storyboard/Story[2]/...`: each step indexed among its same-named siblings where it has any. */
export function xpathOf(element: XmlElement): string {
  const steps: string[] = [];
  for (let current: XmlElement | undefined = element; current; current = current.parent) {
    const siblings = current.parent ? current.parent.children.filter((child) => child.name === current?.name) : [current];
    steps.unshift(siblings.length > 1 ? `${current.name}[${siblings.indexOf(current) + 1}]` : current.name);
  }
  return `/${steps.join('/')}`;
}

function xmlAttributes(values: Record<string, string | number>): string {
  return Object.entries(values)
    .map(([name, value]) => ` ${name}="${escapeAttributeValue(String(value))}"`)
    .join('');
}

/** The `.xqar` text of the problems of one checked input. */
export function resultFileText(config: BundleConfig, problems: Problem[], inputDocument: XmlDocument | undefined): string {
  const byChecker = new Map<string, { uid: string; rule: ProblemRule; problems: Problem[] }>();
  for (const problem of problems) {
    const checkerId = checkerIdOf(problem);
    if (config.checkerIds && !config.checkerIds.has(checkerId)) continue;
    const entry = byChecker.get(checkerId) ?? { uid: qcRuleUid(problem), rule: ruleOf(problem), problems: [] };
    entry.problems.push(problem);
    byChecker.set(checkerId, entry);
  }
  const lines = ['<?xml version="1.0" encoding="UTF-8"?>', '<CheckerResults version="1.0.0">'];
  const total = [...byChecker.values()].reduce((sum, entry) => sum + entry.problems.length, 0);
  const bundle = {
    name: BUNDLE_NAME,
    version: VERSION,
    description: 'modular2simple check: the OpenSCENARIO checks of the modular2simple toolkit',
    summary: `Found ${total} issue${total === 1 ? '' : 's'}`,
  };
  lines.push(`  <CheckerBundle${xmlAttributes(bundle)}>`);
  for (const param of config.params) lines.push(`    <Param${xmlAttributes(param)}/>`);
  let issueId = 0;
  for (const [checkerId, entry] of [...byChecker].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0))) {
    const uid = entry.uid;
    const count = entry.problems.length;
    lines.push(
      `    <Checker${xmlAttributes({ checkerId, description: entry.rule.description, summary: `Found ${count} issue${count === 1 ? '' : 's'}`, status: 'completed' })}>`,
    );
    for (const problem of entry.problems) {
      lines.push(
        `      <Issue${xmlAttributes({ issueId: issueId++, description: problem.message, level: LEVEL[problem.severity], ruleUID: uid })}>`,
      );
      lines.push(`        <Locations${xmlAttributes({ description: displayRef(problem.source, process.cwd()) })}>`);
      lines.push(
        `          <FileLocation${xmlAttributes({ row: problem.range.start.line + 1, column: problem.range.start.character + 1 })}/>`,
      );
      // An XPath only in the input file itself: the framework's viewers resolve it there.
      const inInput = inputDocument && problem.source.entries.length === 0 && path.resolve(problem.source.disk) === config.inputFile;
      const element = inInput ? elementAt(inputDocument, inputDocument.lines.offsetAt(problem.range.start)) : undefined;
      if (element) lines.push(`          <XMLLocation${xmlAttributes({ xpath: xpathOf(element) })}/>`);
      lines.push('        </Locations>');
      lines.push('      </Issue>');
    }
    lines.push(`      <AddressedRule${xmlAttributes({ ruleUID: uid })}/>`);
    lines.push('    </Checker>');
  }
  lines.push('  </CheckerBundle>', '</CheckerResults>', '');
  return lines.join('\n');
}

/** The module manifest that registers this bundle with a framework installation (manifest_file.md), for this installation's command. */
export function moduleManifest(command: string): string {
  const module = {
    name: BUNDLE_NAME,
    exec_type: 'executable',
    module_type: 'checker_bundle',
    exec_command: `${command} qc-bundle -c $ASAM_QC_FRAMEWORK_CONFIG_FILE -o $ASAM_QC_FRAMEWORK_OUTPUT_DIR`,
  };
  return JSON.stringify({ module: [module] }, null, 2);
}

function shellQuoted(text: string): string {
  return /^[\w@%+=:,./-]+$/.test(text) ? text : `'${text.replace(/'/g, `'\\''`)}'`;
}

/** `modular2simple qc-bundle -c CONFIG [--out-dir DIR]`, or `qc-bundle --manifest`. Exit 0 whenever a result file was written: issues are results, not failures. */
async function qcBundleCommand(args: string[], io: CliOutput): Promise<number> {
  const { values, positionals } = parseCommandLine(args, {
    config: { type: 'string', short: 'c' },
    'out-dir': { type: 'string' },
    // The framework's own form (the manifest's exec_command passes -o).
    'output-dir': { type: 'string', short: 'o' },
    manifest: { type: 'boolean', default: false },
  });
  if (values['out-dir'] !== undefined && values['output-dir'] !== undefined) throw new UsageError('use either -o or --out-dir');
  if (values.manifest) {
    io.out(moduleManifest([process.execPath, process.argv[1] ?? 'modular2simple'].map(shellQuoted).join(' ')));
    return ExitCode.ok;
  }
  // The framework's convention also allows the configuration as the only argument.
  const configPath = values.config ?? (positionals.length === 1 ? positionals[0] : undefined);
  if (!configPath || (values.config && positionals.length > 0))
    throw new UsageError('qc-bundle needs its configuration file: qc-bundle -c CONFIG.xml [--out-dir DIR]');
  if (!fs.existsSync(configPath)) throw new InputError(`${configPath}: no such file`);
  const config = readBundleConfig(fs.readFileSync(configPath, 'utf8'), path.resolve(configPath));
  if (!fs.existsSync(config.inputFile)) throw new InputError(`${config.inputFile}: no such file (the configuration's InputFile)`);

  // As `check` does by default: the schema of the file's version too (ASAM's checker has the schema rules).
  const flattener = new Flattener(storeForInputs([], undefined, [config.inputFile]), 'asam', { version: 'auto' });
  const problems = uniqueProblems((await flattener.flatten(mainOf(config.inputFile))).problems);
  const inputDocument =
    fs.statSync(config.inputFile).isFile() && config.inputFile.toLowerCase().endsWith('.xosc')
      ? parseXml(decodeUtf8(fs.readFileSync(config.inputFile)))
      : undefined;
  const outputDir = path.resolve(values['out-dir'] ?? values['output-dir'] ?? '.');
  const resultPath = path.join(outputDir, config.resultFile);
  try {
    fs.mkdirSync(outputDir, { recursive: true });
  } catch (error) {
    io.err(`${resultPath}: error: cannot write the output (${(error as Error).message}); nothing was changed`);
    return ExitCode.io;
  }
  // Written whole or not at all, as every output of this project; a failure is exit 3 as for every command.
  return write(
    [
      {
        target: resultPath,
        data: resultFileText(config, problems, inputDocument),
        summary: `${displayRef(mainOf(config.inputFile), process.cwd())}: ${problems.length} issue${problems.length === 1 ? '' : 's'} written to ${resultPath}`,
      },
    ],
    io,
    false,
  );
}

export const QC_BUNDLE: CliCommand = {
  help: `Check as a checker bundle of ASAM's Quality Checker Framework (modular2simple qc-bundle -c CONFIG.xml [--out-dir DIR]):
  -c, --config CONFIG.xml   the framework's configuration: its InputFile is checked as check does (the schema of the
                            file's version too); the configuration may also be the only argument
  --out-dir DIR             the folder the result file (.xqar) is written to (default: the working directory;
                            -o DIR and --output-dir DIR, the framework's form, too)
  --manifest                print the module manifest that registers this bundle with the framework
  Issues found are results, not failures: exit 0 whenever the result file was written.
  Exit codes: 0 the result file was written, 1 the configuration or its InputFile cannot be used, 2 usage,
  3 the result file could not be written (nothing was changed), 4 internal error.`,
  run: qcBundleCommand,
};

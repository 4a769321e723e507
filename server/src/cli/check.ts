import * as fs from 'node:fs';
import * as v8 from 'node:v8';
import { Flattener } from '../core/flatten';
import { Problem, uniqueProblems } from '../core/problems';
import { ruleOf } from '../core/rules';
import { displayRef } from '../core/sources';
import { SCENARIO_FILE, walkFiles } from '../core/walk';
import { CliCommand, CliOutput, ExitCode, InputError, report, UsageError } from './common';
import { mainOf } from './inputs';
import { distributionFileProblems } from './scenarioText';
import { makeStore, parseOptions, READING_OPTIONS_HELP, SIMULATOR_OPTION_HELP } from './options';

function problemJson(problem: Problem): Record<string, unknown> {
  return {
    file: displayRef(problem.source, process.cwd()),
    line: problem.range.start.line + 1,
    column: problem.range.start.character + 1,
    endLine: problem.range.end.line + 1,
    endColumn: problem.range.end.character + 1,
    severity: problem.severity,
    code: problem.code,
    rule: ruleOf(problem).id,
    message: problem.message,
    ...(problem.hint ? { hint: problem.hint } : {}),
    ...(problem.related?.length
      ? {
          related: problem.related.map((item) => ({
            file: displayRef(item.source, process.cwd()),
            line: item.range.start.line + 1,
            column: item.range.start.character + 1,
            message: item.message,
          })),
        }
      : {}),
  };
}

/** Problems in file order, then line and column, as a compiler lists them; ties keep the order they were found in. */
function sortedByPlace(problems: Problem[]): Problem[] {
  const keyed = problems.map((problem) => ({ problem, file: displayRef(problem.source, process.cwd()) }));
  keyed.sort(
    (a, b) =>
      (a.file < b.file ? -1 : a.file > b.file ? 1 : 0) ||
      a.problem.range.start.line - b.problem.range.start.line ||
      a.problem.range.start.character - b.problem.range.start.character,
  );
  return keyed.map((item) => item.problem);
}

/** A folder the user names is checked whole: only dot-entries and dependencies are left out, and an unreadable folder is reported. */
const CHECKED_SKIPPED_FOLDERS = new Set(['node_modules']);

/**
 * A folder check holds one file's trees at a time, yet over many files V8 grows its heap rather than
 * collect (issue 18: a 1,036-file folder peaked at 2.5x a one-file check's memory, the reachable heap
 * the same). Set before the loop, these flags hold it near a one-file check's (bench/check.mjs):
 * - the young generation keeps its start-up size instead of growing to 16 MB per semi-space;
 * - the old generation's limit grows by 10% over what survives a full collection, not 1.1x to 4x;
 * - no optimizing compiler (TurboFan): its compilations' memory was most of the rest, and a check spends
 *   its time in many short functions over many files, which the baseline tiers run about as fast;
 * - V8's own choice of memory over speed (--optimize-for-size): 80 -> 75 MB on bench/check.mjs's folder
 *   for about a tenth more CPU, once the command's own bundle had made one file's check 7 MB smaller.
 * Only the program's own process and only for more than one file: one file checks as before, and a
 * test runner or editor calling `main` keeps its V8 settings.
 */
function keepHeapSmallForManyFiles(): void {
  for (const flag of ['--semi-space-growth-factor=1', '--heap-growing-percent=10', '--no-opt', '--optimize-for-size'])
    v8.setFlagsFromString(flag);
}

/** `modular2simple check PATH... [--format json|sarif]`: every problem of every scenario file, as a compiler reports them. */
async function checkCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseOptions(args);
  const inputs = options.positional;
  if (inputs.length === 0) throw new UsageError('check needs at least one file or folder');
  const files: string[] = [];
  for (const input of inputs) {
    if (!fs.existsSync(input)) throw new InputError(`${input}: no such file or folder`);
    if (fs.statSync(input).isDirectory()) {
      const below = await walkFiles([input], {
        files: SCENARIO_FILE,
        skipFolders: CHECKED_SKIPPED_FOLDERS,
        skipDotFiles: true,
        regularFilesOnly: false,
        unreadable: 'throw',
        sorted: true,
      });
      // A folder with nothing to check passes nothing: a CI step on a mistyped or empty folder must not read as clean.
      if (below.length === 0)
        throw new InputError(
          `${input}: the folder holds no .xosc or .mosc file, so nothing was checked; name the folder (or files) that hold the scenarios`,
        );
      files.push(...below);
    } else files.push(input);
  }
  if (io.ownsProcess && files.length > 1) keepHeapSmallForManyFiles();
  const store = makeStore(options, inputs);
  const found: Problem[] = [];
  for (const file of files) {
    // A flattener per file holds one file's trees at a time (issue 18): a folder check's memory stays that of its largest file; catalogs are still modelled once (core/semantics/catalogs.ts).
    const flattener = new Flattener(store, options.simulator, { version: options.schemaVersion }, undefined, options.carlaRelease);
    const result = await flattener.flatten(mainOf(file));
    // A copy with strings of its own: a message cut from a file's text would keep the whole text alive until the report.
    for (const problem of result.problems) found.push(structuredClone(problem));
    // A distribution file is checked as vary reads it: a parameterName its ScenarioFile no longer declares is an error.
    found.push(...(await distributionFileProblems(file, options.scenarioPath)));
  }
  const problems = sortedByPlace(uniqueProblems(found));
  const errors = problems.filter((problem) => problem.severity === 'error').length;
  const warnings = problems.filter((problem) => problem.severity === 'warning').length;
  // Notes: information and hints, as SARIF's level 'note' counts them; the text lists the information, the editor shows hints faded.
  const notes = problems.length - errors - warnings;
  if (options.format === 'json') {
    io.out(JSON.stringify({ files: files.length, errors, warnings, notes, problems: problems.map(problemJson) }, null, 2));
  } else if (options.format === 'sarif') {
    const { sarifLog } = await import('./sarif');
    io.out(JSON.stringify(sarifLog(problems, process.cwd()), null, 2));
  } else {
    report(problems, io, options.quiet);
    if (!options.quiet)
      io.err(
        `checked ${files.length} file${files.length === 1 ? '' : 's'}: ${errors} error${errors === 1 ? '' : 's'}, ${warnings} warning${warnings === 1 ? '' : 's'}` +
          (notes > 0 ? `, ${notes} note${notes === 1 ? '' : 's'} (hints among them are listed by --format json|sarif and the editor)` : ''),
      );
  }
  return errors > 0 ? ExitCode.problems : ExitCode.ok;
}

export const CHECK: CliCommand = {
  help: `Report every problem of scenario files, as a compiler does (modular2simple check PATH... [--format text|json|sarif]):
  a folder is checked whole (every .xosc and .mosc below it); problems print as FILE:LINE:COL: SEVERITY: MESSAGE.
  --format text|json|sarif  text on standard error (the default), or JSON or SARIF 2.1.0 (for CI dashboards)
                            on standard output
${SIMULATOR_OPTION_HELP}
${READING_OPTIONS_HELP}
  Exit codes: 0 no error (warnings may have been printed), 1 errors found, an input cannot be read or a folder
  holds no scenario file, 2 usage, 4 internal error.`,
  run: checkCommand,
};

import * as fs from 'node:fs';
import * as path from 'node:path';
import { writeFileAtomic } from '../../../common/src/atomic';
import { Flattener } from '../core/flatten';
import { formatProblem } from '../core/problems';
import { isDistributionText } from '../core/variations/problems';
import { DEFAULT_LIMITS, displayRef, SourceRef, splitScenarioPath } from '../core/sources';
import { prepareScenario, Simulation, SimulationLoadError, SimulationOptions } from '../debug/simulation';
import { TraceRecord, traceToEnd } from '../debug/trace';
import { EsminiLibraryError } from '../esmini/library';
import { EsminiProblem } from '../esmini/messages';
import { csvNamingScenario } from '../esmini/process';
import { isEsminiSeed, removeRunFolder, RUN_DEFAULTS, runScenario } from '../esmini/run';
import {
  checkInputExists,
  CliCommand,
  CliOutput,
  durationOption,
  ExitCode,
  parseCommandLine,
  printed,
  UnavailableError,
  UsageError,
} from './common';
import { mainOf, storeForInputs } from './inputs';
import { LIMIT_OPTIONS, LIMIT_OPTIONS_HELP, limitsOption } from './options';

export const RUN_HELP = `Run in esmini (modular2simple run INPUT... [options]):
  --duration S              stop at S simulated seconds if the scenario has not ended by then (default: its own
                            end, when its StopTrigger fires; one not ended after ${RUN_DEFAULTS.runawaySeconds} s, or a second after the time
                            its StopTrigger ends it at when that is later, is stopped, and one whose
                            StopTrigger has no condition runs ${RUN_DEFAULTS.noEndSeconds} s); fixed step ${RUN_DEFAULTS.timeStep} s
  --seed N                  esmini's random seed, 0 to ${RUN_DEFAULTS.maxSeed} (default ${RUN_DEFAULTS.seed})
  --road-path DIRS          extra folders for road files and catalogs (separated by ';' or ':')
  --esmini PATH             the esmini program, or its folder (default: esmini on PATH, else the one npm start built)
  --check                   exit 1 when esmini reports an error (for CI over a library)
  --force                   run whatever can be flattened despite the scenario's errors, listing them
  --csv OUT                 keep esmini's CSV log of the run (one input only)
  --trace OUT.jsonl         also run it in esmini's library and write every storyboard transition and condition
                            firing as one JSON object a line (time, element, type, state, file, line; a condition's
                            rule, threshold and measured value); one input only (docs/debugging.md)
  --esmini-library PATH     esmini's libesminiLib.so or its folder (default: .cache/esmini/lib, where npm start builds it)
  --scenario-path DIRS      as for flatten
${LIMIT_OPTIONS_HELP}
  esmini's problems print as FILE:LINE:COL: error|warning: MESSAGE (esmini), on the source line they
  come from. Exit codes: 0 ran (with --check: and no error), 1 errors (or not flattened), 2 usage, 3 no esmini or it failed.`;

/** `file:line:col: severity: message (esmini)`, 1-based, as compilers print. */
export function formatEsminiProblem(problem: EsminiProblem, base?: string): string {
  const where = `${displayRef(problem.source, base)}:${problem.range.start.line + 1}:${problem.range.start.character + 1}`;
  const repeats = problem.count > 1 ? ` (${problem.count} times)` : '';
  const note = problem.note ? `\n  note: ${problem.note}` : '';
  return `${where}: ${problem.severity}: ${problem.message} (esmini)${repeats}${note}`;
}

/**
 * Rows of esmini's CSV up to `duration`: header lines kept, later rows dropped; its 'Scenario File Name' names `scenario`,
 * the input, not the run's private copy (removed when the run ends).
 */
function csvUpTo(text: string, duration: number, scenario: string): string {
  const lines = csvNamingScenario(text, scenario).split('\n');
  const kept = lines.filter((line) => {
    const time = Number(line.split(',')[1]);
    return !/^\s*\d/.test(line) || !Number.isFinite(time) || time <= duration + 1e-9;
  });
  return kept.join('\n');
}

/** The run again in esmini's library, every transition and condition firing as a trace record; undefined (said why) when it did not run. */
async function traceRun(
  flattener: Flattener,
  main: SourceRef,
  options: SimulationOptions,
  io: CliOutput,
): Promise<TraceRecord[] | undefined> {
  let simulation: Simulation | undefined;
  try {
    simulation = new Simulation(await prepareScenario(flattener, main, options), options);
    return traceToEnd(simulation, simulation.start(), process.cwd());
  } catch (error) {
    if (error instanceof EsminiLibraryError) throw new UnavailableError(error.message);
    if (!(error instanceof SimulationLoadError)) throw error;
    for (const problem of error.problems)
      io.err('code' in problem ? formatProblem(problem, process.cwd()) : formatEsminiProblem(problem, process.cwd()));
    io.err(`${displayRef(main, process.cwd())}: error: --trace: ${error.message}`);
    return undefined;
  } finally {
    simulation?.close();
  }
}

/**
 * Why a .xosc input is no scenario esmini could run, with what to do instead: a ParameterValueDistribution (which the
 * editor's Run in esmini runs as its concrete scenario 0) or a catalog; undefined for anything else.
 */
function notAScenario(input: string, maxFileBytes: number): string | undefined {
  // A file past --max-file-size is not read here: the flattening reports it, naming the option.
  if (!/\.xosc$/i.test(input) || !fs.statSync(input).isFile() || fs.statSync(input).size > maxFileBytes) return undefined;
  const text = fs.readFileSync(input, 'utf8');
  if (isDistributionText(text))
    return (
      `a ParameterValueDistribution, not a scenario: nothing was run. Run its concrete scenarios with ` +
      `'batch ${input} --results DIR', or write one with 'vary ${input} --index I -o OUT.xosc' and run that`
    );
  const catalog = /<Catalog\b[^>]*\bname\s*=\s*["']([^"']*)["']/.exec(text);
  if (catalog && !/<Storyboard\b/.test(text))
    return `a catalog ('${catalog[1]}'), not a scenario: nothing was run; run a scenario that references its entries`;
  return undefined;
}

/** `modular2simple run`: flattens each input, runs it in esmini and prints esmini's problems on their source lines. */
async function runCommand(args: string[], io: CliOutput): Promise<number> {
  const { values, positionals: inputs } = parseCommandLine(args, {
    duration: { type: 'string' },
    seed: { type: 'string' },
    'road-path': { type: 'string', multiple: true },
    esmini: { type: 'string' },
    check: { type: 'boolean', default: false },
    force: { type: 'boolean', default: false },
    csv: { type: 'string' },
    trace: { type: 'string' },
    'esmini-library': { type: 'string' },
    'scenario-path': { type: 'string', multiple: true },
    quiet: { type: 'boolean', short: 'q', default: false },
    ...LIMIT_OPTIONS,
  });
  if (inputs.length === 0) throw new UsageError('run needs a scenario: a .xosc, a .mosc or an unpacked folder');
  const duration = durationOption(values.duration);
  const seed = values.seed === undefined ? RUN_DEFAULTS.seed : Number(values.seed);
  if (!isEsminiSeed(seed))
    throw new UsageError(
      `--seed takes a whole number from 0 to ${RUN_DEFAULTS.maxSeed} (esmini's seed is an unsigned int), not '${values.seed}'`,
    );
  if (values.csv !== undefined && inputs.length > 1) throw new UsageError('--csv takes one input');
  if (values.trace !== undefined && inputs.length > 1) throw new UsageError('--trace takes one input');
  for (const input of inputs) checkInputExists(input);
  const roadPath = (values['road-path'] ?? []).flatMap(splitScenarioPath);
  const limits = limitsOption(values);
  // esmini searches the road folders for catalogs too (its --path): so does the check before the run.
  const flattener = new Flattener(
    storeForInputs((values['scenario-path'] ?? []).flatMap(splitScenarioPath), undefined, inputs, limits, roadPath),
  );
  let failed = false;
  let notRun = false;
  let errors = 0;
  for (const input of inputs) {
    const instead = notAScenario(input, limits.maxEntryBytes ?? DEFAULT_LIMITS.maxEntryBytes);
    if (instead !== undefined) {
      io.err(`${input}: error: ${instead}`);
      notRun = true;
      continue;
    }
    const result = await runScenario(flattener, mainOf(input), {
      esminiPath: values.esmini,
      roadPath,
      duration,
      durationSetBy: '--duration',
      seed,
      force: values.force,
    });
    try {
      for (const problem of result.flattenProblems) if (printed(problem, values.quiet)) io.err(formatProblem(problem, process.cwd()));
      // What esmini runs otherwise than written (a condition it never fires), whatever --simulator the check would take.
      for (const problem of result.esminiFindings) if (printed(problem, values.quiet)) io.err(formatProblem(problem, process.cwd()));
      for (const problem of result.problems)
        if (problem.severity === 'error' || !values.quiet) io.err(formatEsminiProblem(problem, process.cwd()));
      if (result.outcome === 'no-esmini') throw new UnavailableError(result.message);
      if (result.outcome === 'failed' || result.outcome === 'cancelled') {
        io.err(`${input}: error: ${result.message}`);
        if (result.log) io.err(result.log.split('\n').slice(-15).join('\n'));
        failed = true;
        continue;
      }
      if (result.outcome === 'not-flattened') notRun = true;
      if (result.outcome === 'errors') errors++;
      if (!values.quiet || result.outcome !== 'ok')
        io.err(`${input}: ${result.message}${result.forcible ? ' (--force runs it anyway)' : ''}`);
      if (values.csv !== undefined && result.csvFile) {
        const output = path.resolve(values.csv);
        await writeFileAtomic(output, csvUpTo(fs.readFileSync(result.csvFile, 'utf8'), result.duration, path.resolve(input)));
        if (!values.quiet) io.err(`wrote ${values.csv}`);
      }
    } finally {
      removeRunFolder(result);
    }
    if (values.trace !== undefined && result.outcome !== 'not-flattened') {
      const options = { duration, seed, roadPath, force: values.force, esminiLibrary: values['esmini-library'] };
      const records = await traceRun(flattener, mainOf(input), options, io);
      if (records === undefined) failed = true;
      else {
        await writeFileAtomic(path.resolve(values.trace), records.map((record) => JSON.stringify(record)).join('\n') + '\n');
        if (!values.quiet) io.err(`wrote ${values.trace} (${records.length} transitions and condition firings)`);
      }
    }
  }
  if (failed) return ExitCode.io;
  return notRun || (values.check && errors > 0) ? ExitCode.problems : ExitCode.ok;
}

export const RUN: CliCommand = { help: RUN_HELP, run: runCommand };

import * as fs from 'node:fs';
import * as path from 'node:path';
import { isSameFile, writeFilesAtomic } from '../../common/src/atomic';
import { Flattener, OVERRIDE_PROBLEM_CODES } from './core/flatten';
import { isSchemaVersion, SCHEMA_VERSIONS } from './core/schema/model';
import { SchemaVersionSetting } from './core/schema/version';
import { packFiles, packFolder, PackResult } from './core/pack';
import { formatProblem, Problem, uniqueProblems } from './core/problems';
import { diskRef, displayRef, Limits, ScenarioStore, SourceRef, splitScenarioPath } from './core/sources';
import { libraryStats } from './core/stats';
import { FORMAT_HELP, formatCommand } from './cli/format';
import { isSimulator, Simulator, SIMULATORS } from './core/profiles/simulators';
import { countEditorLines } from './core/text';
import { mainOf, storeForInputs } from './cli/inputs';
import { RUN_HELP, runCommand } from './cli/run';

/** Exit codes, as documented in the README. */
export const ExitCode = { ok: 0, problems: 1, usage: 2, io: 3, internal: 4 } as const;

const VERSION = '0.1.0';

const HELP = `modular2simple ${VERSION}: pack, flatten and check modular OpenSCENARIO scenarios

Usage:
  modular2simple flatten INPUT [-o OUT.xosc]       flatten a .mosc, a main.xosc or an unpacked folder
  modular2simple flatten INPUT... --out-dir DIR    flatten several inputs into DIR/NAME.xosc
  modular2simple pack FOLDER -o OUT.mosc           pack an unpacked folder and all it references
  modular2simple pack FILE... -o OUT.mosc          pack files at the root of a package (one main.xosc)
  modular2simple check PATH... [--format json]     report every problem, as a compiler does
  modular2simple stats LIBRARY [--format json]     lines of code of a library (the paper's Table 1)
  modular2simple run INPUT... [--check]            flatten and run in esmini; its messages on the source lines
${FORMAT_HELP}

Compatible with the original tool:
  modular2simple -cxm|--convert-xosc-into-mosc IN... OUT.mosc
  modular2simple -cmx|--convert-mosc-to-xosc IN.mosc OUT.xosc

Options:
  -o, --output FILE         where to write (flatten: '-' or no -o prints to standard output)
  --out-dir DIR             output folder for several inputs
  --force                   write the output despite overrides that cannot apply (unknown keys,
                            attributes without default): they are skipped, as the original did
  --scenario-path DIRS      folders searched after the package, before SCENARIO_PATH's own
                            (separated by ';' or ':')
  --root DIR                where the search upward from an unpacked folder stops (default: the
                            working directory, or the input's folder when it lies elsewhere)
  --include-scenario-path   pack: also store files found through SCENARIO_PATH
  --format text|json        output format of check and stats
  --simulator asam|carla|esmini
                            check, flatten: also warn about what this simulator does not run
                            (default asam: the standard alone)
  --check                   format: list the files that would change and write nothing (exit 1 if any)
  --width N                 format: past N columns a start tag puts each attribute on its own line (120)
  --indent N|tab            format: the indentation (default: what the file uses, else 2 spaces)
  --schema-version V        the OpenSCENARIO schema files are checked against: auto (each file's
                            FileHeader, the default), 1.0, 1.1, 1.2, 1.3, or off
  --max-file-size SIZE      largest scenario file or package entry read (default 32M)
  --max-unpacked-size SIZE  bytes one run may unpack from packages, all together (default 128M)
  --max-output-size SIZE    characters of one flattened result (default 8M)
  --max-depth N             files in one chain of references, nested packages included (default 64)
  -q, --quiet               print errors only
  -h, --help                this help
  -v, --version             the version

${RUN_HELP}

Environment:
  SCENARIO_PATH             folders searched for referenced scenarios (separated by ';' or ':')

Exit codes:
  0 success (warnings may have been printed)
  1 the input has errors; nothing was written
  2 wrong usage
  3 the output could not be written; nothing was changed
  4 internal error (a bug: please report it with the input)`;

class UsageError extends Error {}

interface Options {
  positional: string[];
  output?: string;
  outDir?: string;
  force: boolean;
  scenarioPath: string[];
  root?: string;
  includeScenarioPath: boolean;
  format: 'text' | 'json';
  quiet: boolean;
  simulator: Simulator;
  schemaVersion: SchemaVersionSetting | 'off';
  limits: Partial<Limits>;
}

/** A size such as 1048576, 512K, 64M or 2G. */
function parseSize(text: string, flag: string): number {
  const match = /^(\d+)([KMG]?)B?$/i.exec(text.trim());
  if (!match) throw new UsageError(`${flag} takes a size such as 64M, not '${text}'`);
  const factor = { '': 1, K: 1024, M: 1024 ** 2, G: 1024 ** 3 }[match[2].toUpperCase() as '' | 'K' | 'M' | 'G'];
  const size = Number(match[1]) * factor;
  if (!Number.isSafeInteger(size) || size <= 0) throw new UsageError(`${flag} takes a positive size, not '${text}'`);
  return size;
}

function parseOptions(args: string[]): Options {
  const options: Options = { positional: [], force: false, scenarioPath: [], includeScenarioPath: false, format: 'text', quiet: false, simulator: 'asam', schemaVersion: 'auto', limits: {} };
  const value = (index: number, flag: string): string => {
    const next = args[index + 1];
    if (next === undefined || (next.startsWith('-') && next.length > 1)) throw new UsageError(`${flag} needs a value`);
    return next;
  };
  for (let i = 0; i < args.length; i++) {
    const arg = args[i];
    const [flag, inline] = arg.startsWith('--') && arg.includes('=') ? [arg.slice(0, arg.indexOf('=')), arg.slice(arg.indexOf('=') + 1)] : [arg, undefined];
    const take = () => (inline !== undefined ? inline : value(i++, flag));
    switch (flag) {
      case '-o':
      case '--output':
        options.output = take();
        break;
      case '--out-dir':
        options.outDir = take();
        break;
      case '--force':
        options.force = true;
        break;
      case '--scenario-path':
        options.scenarioPath.push(...splitScenarioPath(take()));
        break;
      case '--root':
        options.root = take();
        break;
      case '--include-scenario-path':
        options.includeScenarioPath = true;
        break;
      case '--format': {
        const format = take();
        if (format !== 'text' && format !== 'json') throw new UsageError(`--format takes text or json, not '${format}'`);
        options.format = format;
        break;
      }
      case '--simulator': {
        const simulator = take();
        if (!isSimulator(simulator)) throw new UsageError(`--simulator takes ${SIMULATORS.join(', ')}, not '${simulator}'`);
        options.simulator = simulator;
        break;
      }
      case '--schema-version': {
        const version = take();
        if (version !== 'auto' && version !== 'off' && !isSchemaVersion(version)) throw new UsageError(`--schema-version takes auto, off, ${SCHEMA_VERSIONS.join(', ')}; not '${version}'`);
        options.schemaVersion = version;
        break;
      }
      case '-q':
      case '--quiet':
        options.quiet = true;
        break;
      case '--max-file-size':
        options.limits.maxEntryBytes = parseSize(take(), flag);
        break;
      case '--max-unpacked-size':
        options.limits.maxTotalBytes = parseSize(take(), flag);
        break;
      case '--max-output-size':
        options.limits.maxFlattenedChars = parseSize(take(), flag);
        break;
      case '--max-depth': {
        const depth = Number(take());
        if (!Number.isSafeInteger(depth) || depth < 1) throw new UsageError('--max-depth takes a positive whole number');
        options.limits.maxDepth = depth;
        break;
      }
      default:
        if (arg.startsWith('-') && arg !== '-') throw new UsageError(`unknown option '${arg}'`);
        options.positional.push(arg);
    }
  }
  return options;
}

interface Output {
  out: (text: string) => void;
  err: (text: string) => void;
}

function makeStore(options: Options, inputs: string[]): ScenarioStore {
  return storeForInputs(options.scenarioPath, options.root, inputs, options.limits);
}


function checkInputExists(input: string): void {
  if (!fs.existsSync(input)) throw new InputError(`${input}: no such file or folder`);
  const resolved = path.resolve(input);
  if (fs.statSync(resolved).isDirectory() && !fs.existsSync(path.join(resolved, 'main.xosc'))) {
    throw new InputError(`${input}: the folder holds no main.xosc, so it is not an unpacked package`);
  }
}

class InputError extends Error {}

function report(problems: Problem[], io: Output, quiet: boolean): { errors: number; warnings: number } {
  let errors = 0;
  let warnings = 0;
  for (const problem of uniqueProblems(problems)) {
    if (problem.severity === 'error') errors++;
    else if (problem.severity === 'warning') warnings++;
    // Hints (an unused parameter) are for the editor, where they show faded.
    if (problem.severity === 'hint') continue;
    if (quiet && problem.severity !== 'error') continue;
    io.err(formatProblem(problem));
  }
  return { errors, warnings };
}

function problemJson(problem: Problem): Record<string, unknown> {
  return {
    file: displayRef(problem.source),
    line: problem.range.start.line + 1,
    column: problem.range.start.character + 1,
    endLine: problem.range.end.line + 1,
    endColumn: problem.range.end.character + 1,
    severity: problem.severity,
    code: problem.code,
    message: problem.message,
    ...(problem.hint ? { hint: problem.hint } : {}),
    ...(problem.related?.length
      ? { related: problem.related.map((item) => ({ file: displayRef(item.source), line: item.range.start.line + 1, column: item.range.start.character + 1, message: item.message })) }
      : {}),
  };
}

/** Refuses to write over any file the run read. */
function checkNotAnInput(output: string, inputs: SourceRef[]): void {
  for (const input of inputs) {
    if (fs.existsSync(output) && isSameFile(output, input.disk)) {
      throw new InputError(`refusing to write ${output}: it is an input (${displayRef(input)}); choose another output file`);
    }
  }
}

/** Writes every output or none; `-` is standard output. */
async function write(outputs: { target: string; data: string | Uint8Array; summary: string }[], io: Output, quiet: boolean): Promise<number> {
  const files = outputs.filter((output) => output.target !== '-');
  for (const output of files) {
    const directory = path.dirname(path.resolve(output.target));
    if (!fs.existsSync(directory)) {
      io.err(`${output.target}: error: cannot write the output (the folder ${directory} does not exist); nothing was changed`);
      return ExitCode.io;
    }
  }
  const result = await writeFilesAtomic(files.map((output) => ({ target: output.target, data: output.data })));
  if (result.failed) {
    const { target, error } = result.failed;
    const changed = result.written.length === 0 ? 'nothing was changed' : `only ${result.written.join(', ')} ${result.written.length === 1 ? 'was' : 'were'} written`;
    io.err(`${target}: error: cannot write the output (${error.message}); ${changed}`);
    return ExitCode.io;
  }
  for (const output of outputs) {
    if (output.target === '-') io.out(output.data as string);
    else if (!quiet) io.err(output.summary);
  }
  return ExitCode.ok;
}

async function flattenCommand(inputs: string[], outputs: string[] | undefined, options: Options, io: Output): Promise<number> {
  for (const input of inputs) checkInputExists(input);
  const store = makeStore(options, inputs);
  const flattener = new Flattener(store, options.simulator, { version: options.schemaVersion });
  const results = [];
  let problems: Problem[] = [];
  for (const [index, input] of inputs.entries()) {
    const result = await flattener.flatten(mainOf(input), { force: options.force, outputPath: outputs?.[index] });
    results.push(result);
    problems = problems.concat(result.problems);
  }
  if (options.force) {
    // Forced past, these no longer stop the run: shown as warnings saying what was skipped.
    problems = problems.map((problem) =>
      problem.severity === 'error' && OVERRIDE_PROBLEM_CODES.has(problem.code)
        ? { ...problem, severity: 'warning', message: `${problem.message} (skipped: --force)` }
        : problem,
    );
  }
  const { errors } = report(problems, io, options.quiet);
  if (results.some((result) => result.text === undefined)) {
    io.err(`${errors} error${errors === 1 ? '' : 's'}; nothing was written` + (problems.some((p) => p.code === 'unknown-key' || p.code === 'no-default') && !options.force ? ' (--force writes the output without the overrides that cannot apply)' : ''));
    return ExitCode.problems;
  }
  if (!outputs) {
    for (const result of results) io.out(result.text as string);
    return ExitCode.ok;
  }
  for (let i = 0; i < results.length; i++) if (outputs[i] !== '-') checkNotAnInput(outputs[i], results[i].source.dependencies);
  return write(
    results.map((result, i) => ({ target: outputs[i], data: result.text as string, summary: `wrote ${outputs[i]} (${countEditorLines(result.text as string)} lines)` })),
    io,
    options.quiet,
  );
}

function outputNameFor(input: string): string {
  const resolved = path.resolve(input);
  const base = path.basename(resolved);
  if (fs.existsSync(resolved) && fs.statSync(resolved).isDirectory()) return `${base}.xosc`;
  if (base === 'main.xosc') return `${path.basename(path.dirname(resolved))}.xosc`;
  return `${base.replace(/\.(mosc|xosc)$/i, '')}.xosc`;
}

async function packCommand(inputs: string[], output: string, options: Options, io: Output): Promise<number> {
  if (!output.toLowerCase().endsWith('.mosc')) throw new UsageError(`the output '${output}' must end in .mosc`);
  const folderInput = inputs.length === 1 && fs.existsSync(inputs[0]) && fs.statSync(inputs[0]).isDirectory();
  let result: PackResult;
  if (folderInput) {
    checkInputExists(inputs[0]);
    result = await packFolder(inputs[0], makeStore(options, inputs), { includeScenarioPath: options.includeScenarioPath });
  } else {
    result = await packFiles(inputs, options.limits);
  }
  const { errors } = report(result.problems, io, options.quiet);
  if (!result.bytes) {
    io.err(`${errors} error${errors === 1 ? '' : 's'}; nothing was written`);
    return ExitCode.problems;
  }
  checkNotAnInput(output, [...inputs.map((input) => diskRef(input)), ...result.inputs]);
  return write([{ target: output, data: result.bytes, summary: `wrote ${output} (${result.entries.join(', ')})` }], io, options.quiet);
}

function listScenarioFiles(folder: string): string[] {
  const found: string[] = [];
  const walk = (directory: string) => {
    for (const entry of fs.readdirSync(directory, { withFileTypes: true })) {
      if (entry.name.startsWith('.') || entry.name === 'node_modules') continue;
      const full = path.join(directory, entry.name);
      if (entry.isDirectory()) walk(full);
      else if (/\.(xosc|mosc)$/i.test(entry.name)) found.push(full);
    }
  };
  walk(folder);
  return found.sort();
}

async function checkCommand(inputs: string[], options: Options, io: Output): Promise<number> {
  const files: string[] = [];
  for (const input of inputs) {
    if (!fs.existsSync(input)) throw new InputError(`${input}: no such file or folder`);
    if (fs.statSync(input).isDirectory()) files.push(...listScenarioFiles(input));
    else files.push(input);
  }
  const flattener = new Flattener(makeStore(options, inputs), options.simulator, { version: options.schemaVersion });
  let problems: Problem[] = [];
  for (const file of files) {
    const result = await flattener.flatten(mainOf(file));
    problems = problems.concat(result.problems);
  }
  problems = uniqueProblems(problems);
  const errors = problems.filter((problem) => problem.severity === 'error').length;
  const warnings = problems.filter((problem) => problem.severity === 'warning').length;
  if (options.format === 'json') {
    io.out(JSON.stringify({ files: files.length, errors, warnings, problems: problems.map(problemJson) }, null, 2));
  } else {
    report(problems, io, options.quiet);
    if (!options.quiet) io.err(`checked ${files.length} file${files.length === 1 ? '' : 's'}: ${errors} error${errors === 1 ? '' : 's'}, ${warnings} warning${warnings === 1 ? '' : 's'}`);
  }
  return errors > 0 ? ExitCode.problems : ExitCode.ok;
}

async function statsCommand(library: string, options: Options, io: Output): Promise<number> {
  if (!fs.existsSync(library) || !fs.statSync(library).isDirectory()) throw new InputError(`${library}: no such folder`);
  const stats = await libraryStats(library, options.limits, process.cwd());
  for (const problem of stats.problems) io.err(`${library}: error: ${problem}`);
  if (options.format === 'json') {
    io.out(JSON.stringify(stats, null, 2));
  } else {
    const width = Math.max(8, ...stats.rows.map((row) => row.scenario.length));
    io.out(`${'#'.padStart(3)}  ${'scenario'.padEnd(width)}  ${'modular'.padStart(8)}  ${'flattened'.padStart(9)}  reduction`);
    stats.rows.forEach((row, index) => {
      io.out(`${String(index + 1).padStart(3)}  ${row.scenario.padEnd(width)}  ${String(row.modularLines).padStart(8)}  ${String(row.flattenedLines).padStart(9)}  ${row.reduction.toFixed(1).padStart(8)} %`);
    });
    for (const item of stats.shared) io.out(`     ${('+ ' + path.relative(path.resolve(library), item.file)).padEnd(width)}  ${String(item.lines).padStart(8)}`);
    const { totals } = stats;
    io.out(`     ${'total'.padEnd(width)}  ${totals.modularLines.toLocaleString('en-US').padStart(8)}  ${totals.flattenedLines.toLocaleString('en-US').padStart(9)}  ${totals.reduction.toFixed(1).padStart(8)} %`);
  }
  return stats.problems.length > 0 ? ExitCode.problems : ExitCode.ok;
}

/** Runs the command line; returns the exit code. Never throws. */
export async function main(argv: string[], io: Output): Promise<number> {
  try {
    if (argv.length === 0 || argv[0] === '-h' || argv[0] === '--help' || argv[0] === 'help') {
      (argv.length === 0 ? io.err : io.out)(HELP);
      return argv.length === 0 ? ExitCode.usage : ExitCode.ok;
    }
    if (argv[0] === '-v' || argv[0] === '--version') {
      io.out(VERSION);
      return ExitCode.ok;
    }
    const [command, ...rest] = argv;
    if (command === 'run') return await runCommand(rest, io);
    if (command === 'format') return await formatCommand(rest, io);
    const options = parseOptions(rest);
    const inputs = options.positional;
    switch (command) {
      case '-cxm':
      case '--convert-xosc-into-mosc': {
        if (inputs.length < 2) throw new UsageError('-cxm takes the input files and then the output .mosc');
        return await packCommand(inputs.slice(0, -1), inputs[inputs.length - 1], options, io);
      }
      case '-cmx':
      case '--convert-mosc-to-xosc': {
        if (inputs.length !== 2) throw new UsageError('-cmx takes one input .mosc and one output .xosc');
        return await flattenCommand([inputs[0]], [inputs[1]], options, io);
      }
      case 'flatten': {
        if (inputs.length === 0) throw new UsageError('flatten needs an input: a .mosc, a main.xosc or an unpacked folder');
        if (options.outDir) {
          if (options.output) throw new UsageError('use either -o or --out-dir');
          if (!fs.existsSync(options.outDir) || !fs.statSync(options.outDir).isDirectory()) throw new InputError(`${options.outDir}: no such folder`);
          let names = inputs.map(outputNameFor);
          // Inputs with a shared file name (lib/*/result.mosc) are told apart by their folders.
          names = names.map((name, index) => (names.indexOf(name) !== names.lastIndexOf(name) ? `${path.basename(path.dirname(path.resolve(inputs[index])))}.xosc` : name));
          const outputs = names.map((name) => path.join(options.outDir as string, name));
          const duplicates = outputs.filter((output, index) => outputs.indexOf(output) !== index);
          if (duplicates.length > 0) throw new UsageError(`two inputs would both be written to ${duplicates[0]}`);
          return await flattenCommand(inputs, outputs, options, io);
        }
        if (inputs.length > 1) throw new UsageError('several inputs need --out-dir DIR');
        return await flattenCommand(inputs, options.output ? [options.output] : undefined, options, io);
      }
      case 'pack': {
        if (inputs.length === 0) throw new UsageError('pack needs a folder or files to pack');
        if (!options.output) throw new UsageError('pack needs -o OUT.mosc');
        return await packCommand(inputs, options.output, options, io);
      }
      case 'check':
        if (inputs.length === 0) throw new UsageError('check needs at least one file or folder');
        return await checkCommand(inputs, options, io);
      case 'stats':
        if (inputs.length !== 1) throw new UsageError('stats takes one library folder');
        return await statsCommand(inputs[0], options, io);
      default:
        throw new UsageError(`unknown command '${command}'`);
    }
  } catch (error) {
    if (error instanceof UsageError) {
      io.err(`modular2simple: ${error.message}\nRun 'modular2simple --help' for usage.`);
      return ExitCode.usage;
    }
    if (error instanceof InputError) {
      io.err(`modular2simple: error: ${error.message}`);
      return ExitCode.problems;
    }
    io.err(`modular2simple: internal error: ${(error as Error).stack ?? (error as Error).message}\nPlease report this with the input that caused it.`);
    return ExitCode.internal;
  }
}

if (require.main === module) {
  // A closed pipe (`| head`) ends the output quietly instead of with a stack trace.
  process.stdout.on('error', (error: NodeJS.ErrnoException) => {
    if (error.code === 'EPIPE') process.exit(process.exitCode ?? 0);
  });
  main(process.argv.slice(2), {
    out: (text) => process.stdout.write(text.endsWith('\n') ? text : text + '\n'),
    err: (text) => process.stderr.write(text + '\n'),
  }).then(
    (code) => {
      process.exitCode = code;
    },
    (error: unknown) => {
      // main answers every failure itself; reaching this is a bug, reported with its stack.
      process.stderr.write(`modular2simple: internal error: ${error instanceof Error ? error.stack : String(error)}\n`);
      process.exitCode = ExitCode.io;
    },
  );
}

import * as fs from 'node:fs';
import * as path from 'node:path';
import { isSameFile } from '../../../common/src/atomic';
import { CarlaExport, CarlaExportOptionError, CarlaExportOptions, exportForCarla, exportTextForCarla } from '../core/export/carla';
import { unknownBlueprintProblem } from '../core/export/carlaFacts';
import { diskRef, displayRef, nodeFileSystem, splitScenarioPath } from '../core/sources';
import { LineIndex } from '../core/text';
import {
  checkIndexInRange,
  checkInputExists,
  failure,
  CliCommand,
  CliOutput,
  ExitCode,
  InputError,
  parseCommandLine,
  UsageError,
  wholeNumber,
  writablePackagedFiles,
  write,
} from './common';
import { mainOf, storeForInputs } from './inputs';
import { CARLA_OPTION, carlaOptionHelp, carlaReleaseOption } from './options';
import { readUtf8Exactly } from './fileSystem';

export const EXPORT_HELP = `Export for CARLA's ScenarioRunner (modular2simple export INPUT... --target carla -o OUT.xosc|FOLDER):
  INPUT                     a .xosc, a modular main.xosc, an unpacked folder, a .mosc, or a
                            ParameterValueDistribution file with --index I; several inputs are
                            exported in one process, each as FOLDER/NAME.xosc (NAME: the input's)
  --target carla            the simulator (the only one for now)
  -o, --output OUT.xosc     where to write the OpenSCENARIO 1.0 file (never over an input); with
                            several inputs, the folder to write them into (made if absent)
  --report LOSSES.json      also write the loss report as JSON: {"losses": [{kind, file, line,
                            element, what, carla}], ...}; written when the export is refused too;
                            with several inputs, a folder for FOLDER/NAME.json
${carlaOptionHelp('refuses the export')}
  --blueprints FILE.json    {"car_white": "vehicle.audi.tt", ...}: entity names to CARLA blueprints
  --road TOWN|FILE.xodr     the road instead of the scenario's LogicFile
  --road-path DIRS          folders where the scenario's .xodr is looked for (separated by ':' or ';')
  --ego NAME                the vehicle ScenarioRunner takes as the ego (default: the one named
                            ego or hero, else the first vehicle)
  --force                   as for flatten: overrides that cannot apply are skipped (each listed)
  --index I                 the concrete scenario of a distribution file to export
  --scenario-path DIRS      as for flatten: where a modular main's references are looked for
  -q, --quiet               print refusals and errors only
  Every $parameter and \${expression} is evaluated, catalog entries are inlined, 1.1-1.3 forms are written
  in 1.0 where the meaning is kept; what is not kept is listed (file:line, what ScenarioRunner does
  instead). A file whose meaning would be lost is refused: exit 1, nothing written.
  Exit codes: 0 written (losses may be listed), 1 refused, 2 usage, 3 an output could not be written;
  with several inputs, the worst of theirs (each input is exported whatever the others gave).`;

/** One input's export, as the command line asks for it. */
interface ExportArguments {
  input: string;
  output: string;
  report: string | undefined;
  /** Several inputs: the folder `output` and `report` lie in, made before they are written. */
  folders: string[];
  index: bigint | undefined;
  scenarioPath: string[];
  quiet: boolean;
  options: CarlaExportOptions;
}

/** export's options (cli/start.ts's EXPORT_VALUE_OPTIONS names those that take a value, held equal by a test). */
export const EXPORT_OPTIONS = {
  target: { type: 'string' },
  output: { type: 'string', short: 'o' },
  report: { type: 'string' },
  ...CARLA_OPTION,
  blueprints: { type: 'string' },
  road: { type: 'string' },
  'road-path': { type: 'string', multiple: true },
  ego: { type: 'string' },
  force: { type: 'boolean', default: false },
  index: { type: 'string' },
  'scenario-path': { type: 'string', multiple: true },
  quiet: { type: 'boolean', short: 'q', default: false },
} as const;

function parse(argv: string[]): ExportArguments[] {
  const { values, positionals } = parseCommandLine(argv, EXPORT_OPTIONS);
  if (positionals.length === 0) throw new UsageError('export needs an input');
  if (values.target === undefined) throw new UsageError('export needs --target carla');
  if (values.target !== 'carla') throw new UsageError(`--target takes carla, not '${values.target}'`);
  if (values.output === undefined)
    throw new UsageError(positionals.length === 1 ? 'export needs -o OUT.xosc' : 'export of several inputs needs -o FOLDER');
  const release = carlaReleaseOption(values.carla);
  const index = wholeNumber(values.index, '--index');
  const several = positionals.length > 1;
  if (several && index !== undefined)
    throw new UsageError('--index chooses the concrete scenario of one distribution file: export it alone');
  const output = values.output;
  const report = values.report;
  if (several) for (const folder of [output, report]) if (folder !== undefined) notAFile(folder);
  const names = several ? outputNames(positionals) : undefined;
  // What every input's export shares; each adds where it is written.
  const scenarioPath = (values['scenario-path'] ?? []).flatMap(splitScenarioPath);
  const quiet = values.quiet ?? false;
  const options = {
    release,
    blueprints: values.blueprints === undefined ? undefined : readBlueprints(values.blueprints),
    road: values.road === undefined || values.road.toLowerCase().endsWith('.xodr') === false ? values.road : path.resolve(values.road),
    ego: values.ego,
    force: values.force ?? false,
    roadFolders: (values['road-path'] ?? []).flatMap(splitScenarioPath).map((folder) => path.resolve(folder)),
  };
  return positionals.map((input, at) => {
    const name = names?.[at];
    const written = name === undefined ? output : path.join(output, name + '.xosc');
    return {
      input,
      output: written,
      report: name === undefined || report === undefined ? report : path.join(report, name + '.json'),
      folders: name === undefined ? [] : [output, ...(report === undefined ? [] : [report])],
      index,
      scenarioPath,
      quiet,
      options: { ...options, outputPath: path.resolve(written) },
    };
  });
}

/** Several inputs are written into a folder: one that is a file is a usage error before anything is read. */
function notAFile(folder: string): void {
  if (fs.existsSync(folder) && !fs.statSync(folder).isDirectory())
    throw new UsageError(`with several inputs, -o and --report name folders, and ${folder} is a file`);
}

/** Each input's name in the output folder (a folder input's own name, else its file name without .xosc or .mosc); two alike are a usage error. */
function outputNames(inputs: string[]): string[] {
  const names = inputs.map((input) => path.basename(path.resolve(input)).replace(/\.(xosc|mosc)$/i, ''));
  const seen = new Map<string, string>();
  names.forEach((name, at) => {
    const earlier = seen.get(name.toLowerCase());
    if (earlier !== undefined)
      throw new UsageError(`${earlier} and ${inputs[at]} would both be written as ${name}.xosc: export one of them on its own`);
    seen.set(name.toLowerCase(), inputs[at]);
  });
  return names;
}

/** `line L, column C` of an offset in a file's text, for a message a user can find the place by. */
function placeInText(text: string, offset: number): string {
  const { line, character } = new LineIndex(text).positionAt(offset);
  return `line ${line + 1}, column ${character + 1}`;
}

function readBlueprints(file: string): Record<string, string> {
  let text: string;
  try {
    text = fs.readFileSync(file, 'utf8');
  } catch (error) {
    throw new InputError(`${file}: cannot read the blueprint table (${(error as NodeJS.ErrnoException).code ?? (error as Error).message})`);
  }
  let table: unknown;
  try {
    table = JSON.parse(text);
  } catch (error) {
    // Node names the offset ("at position 68"), newer releases its line and column too: given as a line and column.
    const message = (error as Error).message;
    const position = /\bat position (\d+)/.exec(message);
    const what = message.replace(/\s*in JSON at position \d+(?: \(line \d+ column \d+\))?/, '');
    throw new InputError(
      `${file}: the blueprint table is not JSON (${position ? `${placeInText(text, Number(position[1]))}: ` : ''}${what})`,
    );
  }
  if (
    typeof table !== 'object' ||
    table === null ||
    Array.isArray(table) ||
    Object.values(table).some((value) => typeof value !== 'string')
  )
    throw new InputError(
      `${file}: the blueprint table must be a JSON object of names to blueprint ids, such as {"car_white": "vehicle.audi.tt"}`,
    );
  for (const [name, blueprint] of Object.entries(table as Record<string, string>)) {
    const problem = unknownBlueprintProblem(name, blueprint);
    if (!problem) continue;
    const key = new RegExp(`${JSON.stringify(name).replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}\\s*:\\s*`).exec(text);
    throw new InputError(`${file}: ${problem}${key ? ` (${placeInText(text, key.index + key[0].length)})` : ''}`);
  }
  return table as Record<string, string>;
}

const DISTRIBUTION = /<ParameterValueDistribution\b/;

/** The export of one input: a distribution's concrete scenario, or any scenario the flattener takes. */
async function exportInput(args: ExportArguments, io: CliOutput): Promise<CarlaExport> {
  const input = args.input;
  checkInputExists(input);
  const store = storeForInputs(args.scenarioPath, undefined, [input]);
  const isFile = fs.statSync(input).isFile();
  let text: string | undefined;
  if (isFile && input.toLowerCase().endsWith('.xosc')) {
    try {
      text = await readUtf8Exactly(input);
    } catch (error) {
      throw new InputError(`${input}: cannot read it (${(error as NodeJS.ErrnoException).code ?? (error as Error).message})`);
    }
  }
  if (text !== undefined && DISTRIBUTION.test(text)) {
    if (args.index === undefined)
      throw new InputError(
        `${input}: a ParameterValueDistribution: choose its concrete scenario with --index I (modular2simple vary ${input} --count counts them)`,
      );
    // Loaded here: a distribution's expansion needs the flattener and the variations, which a plain export does not.
    const [{ loadVariations, formatVariationProblems, rebasedConcreteText, SamplingError }, { flatteningScenarioLoader }] =
      await Promise.all([import('../core/variations'), import('./scenarioText')]);
    const loaded = await loadVariations(text, path.resolve(input), flatteningScenarioLoader(args.scenarioPath));
    for (const line of formatVariationProblems(loaded.problems, loaded.lines, process.cwd())) io.err(line);
    const variations = loaded.variations;
    if (!variations) throw new InputError(`${input}: the distribution cannot be read`);
    checkIndexInRange(args.index, variations.count, input);
    let concrete;
    try {
      concrete = variations.concreteAt(args.index);
    } catch (error) {
      if (error instanceof SamplingError) throw new InputError(`${input}: ${error.message}`);
      throw error;
    }
    if ('broken' in concrete)
      throw new InputError(
        `${input}: concrete scenario ${args.index} is discarded by its ValueConstraintGroups ('${concrete.broken.parameter}' = '${concrete.broken.value}')`,
      );
    const scenarioFolder = path.dirname(variations.scenarioPath);
    const absolute = await rebasedConcreteText(concrete.text, scenarioFolder, undefined, (file) => nodeFileSystem.kind(file));
    return exportTextForCarla(store, diskRef(variations.scenarioPath), absolute.text, args.options);
  }
  if (args.index !== undefined) throw new UsageError('--index goes with a ParameterValueDistribution file');
  return exportForCarla(store, mainOf(input), args.options);
}

type CarlaLossEntry = CarlaExport['losses'][number];

/** A loss as `check` prints a problem: the file relative to the working directory, line and column. */
function lossLine(loss: CarlaLossEntry, file: string): string {
  const where = `${file}:${loss.line}:${loss.range.start.character + 1}`;
  return `${where}: ${loss.kind === 'refused' ? 'error' : 'warning'}: <${loss.element}> ${loss.what} [${loss.kind}; CARLA: ${loss.carla}]`;
}

/** What every loss report starts with: the input, the output and the release. */
function reportHeader(args: ExportArguments): { input: string; output: string; target: 'carla'; carla: string | undefined } {
  return { input: path.resolve(args.input), output: path.resolve(args.output), target: 'carla', carla: args.options.release };
}

/** `modular2simple export INPUT... --target carla -o OUT.xosc|FOLDER [--report LOSSES.json|FOLDER] [--carla 0.9.15|0.9.16]`. */
async function exportCommand(argv: string[], io: CliOutput): Promise<number> {
  const exports = parse(argv);
  if (exports.length === 1) return exportOne(exports[0], io);
  // One process for them all: a library's exports pay node's start and the bundle's once.
  let worst: number = ExitCode.ok;
  let written = 0;
  for (const args of exports) {
    let code: number;
    try {
      code = await exportOne(args, io);
    } catch (error) {
      const told = failure(error);
      if (!told) throw error;
      io.err(told.message);
      code = told.code;
    }
    if (code === ExitCode.ok) written++;
    worst = Math.max(worst, code);
  }
  const quiet = exports[0].quiet;
  if (!quiet || written < exports.length)
    io.err(`modular2simple: exported ${written} of ${exports.length} inputs${written > 0 ? ` into ${exports[0].folders[0]}` : ''}`);
  return worst;
}

/** Several inputs' folders, made when the first of their files is written: an export that writes nothing leaves none. */
function makeFolders(args: ExportArguments): void {
  for (const folder of args.folders) fs.mkdirSync(folder, { recursive: true });
}

async function exportOne(args: ExportArguments, io: CliOutput): Promise<number> {
  if (fs.existsSync(args.input) && isSameFile(args.input, args.output))
    throw new InputError(`refusing to write ${args.output}: it is the input; choose another output file`);
  let result: CarlaExport;
  try {
    result = await exportInput(args, io);
  } catch (error) {
    if (error instanceof CarlaExportOptionError) throw new InputError(error.message);
    // The input refused before any export (a discarded concrete scenario, an unreadable distribution): --report still says why.
    if (error instanceof InputError && args.report !== undefined) {
      const report = { ...reportHeader(args), written: false, refused: error.message, road: null, ego: null, losses: [] };
      makeFolders(args);
      const code = await write(
        [
          {
            target: args.report,
            data: JSON.stringify(report, null, 2) + '\n',
            summary: `wrote the loss report ${args.report} (0 entries)`,
          },
        ],
        io,
        args.quiet,
      );
      if (code !== ExitCode.ok) return code;
    }
    throw error;
  }
  // As a compiler lists its findings: by file, then line (the export finds them in the order it rewrites the tree).
  const listed = result.losses
    .map((loss) => ({ loss, file: displayRef(loss.source, process.cwd()) }))
    .sort((a, b) =>
      a.file !== b.file
        ? a.file < b.file
          ? -1
          : 1
        : a.loss.line - b.loss.line || a.loss.range.start.character - b.loss.range.start.character,
    );
  for (const { loss, file } of listed) if (!args.quiet || loss.kind === 'refused') io.err(lossLine(loss, file));
  const report = {
    ...reportHeader(args),
    written: result.text !== undefined,
    refused: result.refused ?? null,
    road: result.road ?? null,
    ego: result.ego ?? null,
    losses: result.losses.map(({ kind, file, line, element, what, carla }) => ({ kind, file, line, element, what, carla })),
  };
  const reportOutput =
    args.report === undefined
      ? []
      : [
          {
            target: args.report,
            data: JSON.stringify(report, null, 2) + '\n',
            summary: `wrote the loss report ${args.report} (${result.losses.length} entries)`,
          },
        ];
  if (result.text === undefined) {
    io.err(
      `modular2simple: export refused: ${result.refused ?? 'unknown reason'}; nothing was written${args.report ? ' but the report' : ''}`,
    );
    if (reportOutput.length > 0) {
      makeFolders(args);
      const code = await write(reportOutput, io, args.quiet);
      if (code !== ExitCode.ok) return code;
    }
    return ExitCode.problems;
  }
  const counts =
    result.losses.length === 0 ? 'nothing lost' : `${result.losses.length} loss${result.losses.length === 1 ? '' : 'es'} listed above`;
  // A road packed with the scenario goes beside the export that names it, as flatten writes it.
  makeFolders(args);
  const files = await writablePackagedFiles(result.files ?? [], args.output, io, args.quiet);
  for (const file of files) fs.mkdirSync(path.dirname(file.path), { recursive: true });
  return write(
    [
      ...files.map((file) => ({
        target: file.path,
        data: file.bytes,
        summary: `wrote ${path.relative(path.dirname(path.resolve(args.output)), file.path)} (a file of the package the export names)`,
      })),
      {
        target: args.output,
        data: result.text,
        summary: `wrote ${args.output} for CARLA ScenarioRunner ${args.options.release} (OpenSCENARIO 1.0; ${counts})`,
      },
      ...reportOutput,
    ],
    io,
    args.quiet,
  );
}

export const EXPORT: CliCommand = { help: EXPORT_HELP, run: exportCommand };

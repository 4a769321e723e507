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

export const EXPORT_HELP = `Export for CARLA's ScenarioRunner (modular2simple export INPUT --target carla -o OUT.xosc):
  INPUT                     a .xosc, a modular main.xosc, an unpacked folder, a .mosc, or a
                            ParameterValueDistribution file with --index I
  --target carla            the simulator (the only one for now)
  -o, --output OUT.xosc     where to write the OpenSCENARIO 1.0 file (never over an input)
  --report LOSSES.json      also write the loss report as JSON: {"losses": [{kind, file, line,
                            element, what, carla}], ...}; written when the export is refused too
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
  Exit codes: 0 written (losses may be listed), 1 refused, 2 usage, 3 an output could not be written.`;

interface ExportArguments {
  input: string;
  output: string;
  report: string | undefined;
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

function parse(argv: string[]): ExportArguments {
  const { values, positionals } = parseCommandLine(argv, EXPORT_OPTIONS);
  if (positionals.length !== 1) throw new UsageError('export takes one input');
  if (values.target === undefined) throw new UsageError('export needs --target carla');
  if (values.target !== 'carla') throw new UsageError(`--target takes carla, not '${values.target}'`);
  if (values.output === undefined) throw new UsageError('export needs -o OUT.xosc');
  const release = carlaReleaseOption(values.carla);
  return {
    input: positionals[0],
    output: values.output,
    report: values.report,
    index: wholeNumber(values.index, '--index'),
    scenarioPath: (values['scenario-path'] ?? []).flatMap(splitScenarioPath),
    quiet: values.quiet ?? false,
    options: {
      release,
      outputPath: path.resolve(values.output),
      blueprints: values.blueprints === undefined ? undefined : readBlueprints(values.blueprints),
      road: values.road === undefined || values.road.toLowerCase().endsWith('.xodr') === false ? values.road : path.resolve(values.road),
      ego: values.ego,
      force: values.force ?? false,
      roadFolders: (values['road-path'] ?? []).flatMap(splitScenarioPath).map((folder) => path.resolve(folder)),
    },
  };
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

/** `modular2simple export INPUT --target carla -o OUT.xosc [--report LOSSES.json] [--carla 0.9.15|0.9.16]`. */
async function exportCommand(argv: string[], io: CliOutput): Promise<number> {
  const args = parse(argv);
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
      const code = await write(reportOutput, io, args.quiet);
      if (code !== ExitCode.ok) return code;
    }
    return ExitCode.problems;
  }
  const counts =
    result.losses.length === 0 ? 'nothing lost' : `${result.losses.length} loss${result.losses.length === 1 ? '' : 'es'} listed above`;
  // A road packed with the scenario goes beside the export that names it, as flatten writes it.
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

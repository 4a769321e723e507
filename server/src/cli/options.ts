import { parseArgs } from 'node:util';
import { isSchemaVersion, SCHEMA_VERSIONS } from '../core/schema/model';
import { SchemaVersionSetting } from '../core/schema/version';
import {
  CARLA_RELEASES,
  CarlaRelease,
  DEFAULT_CARLA_RELEASE,
  isCarlaRelease,
  isSimulator,
  Simulator,
  SIMULATORS,
} from '../core/profiles/simulators';
import { Limits, ScenarioStore, splitScenarioPath } from '../core/sources';
import { dashValueMessage, UsageError } from './common';
import { storeForInputs } from './inputs';

/** The --help lines of the bounds on what a command reads: the shared set's, and run's. */
export const LIMIT_OPTIONS_HELP = `  --max-file-size SIZE      largest scenario file or package entry read (default 32M)
  --max-unpacked-size SIZE  bytes one run may unpack from packages, all together (default 128M)
  --max-output-size SIZE    characters of one flattened result (default 8M)
  --max-depth N             files in one chain of references, nested packages included (default 64)`;

/** The bounds' options, one table for the shared set and the commands with tables of their own (run). */
export const LIMIT_OPTIONS = {
  'max-file-size': { type: 'string' },
  'max-unpacked-size': { type: 'string' },
  'max-output-size': { type: 'string' },
  'max-depth': { type: 'string' },
} as const;

type LimitOptionName = keyof typeof LIMIT_OPTIONS;

/** Sets the bound that option `name` (a key of LIMIT_OPTIONS) gives, from its value as typed after `flag`. */
function setLimit(limits: Partial<Limits>, name: LimitOptionName, value: string, flag: string): void {
  switch (name) {
    case 'max-file-size':
      limits.maxEntryBytes = parseSize(value, flag);
      break;
    case 'max-unpacked-size':
      limits.maxTotalBytes = parseSize(value, flag);
      break;
    case 'max-output-size':
      limits.maxFlattenedChars = parseSize(value, flag);
      break;
    case 'max-depth': {
      const depth = Number(value);
      if (!Number.isSafeInteger(depth) || depth < 1) throw new UsageError(`${flag} takes a positive whole number, not '${value}'`);
      limits.maxDepth = depth;
      break;
    }
  }
}

/** The bounds the LIMIT_OPTIONS of a command's parsed values set. */
export function limitsOption(values: Partial<Record<LimitOptionName, string>>): Partial<Limits> {
  const limits: Partial<Limits> = {};
  for (const name of Object.keys(LIMIT_OPTIONS) as LimitOptionName[]) {
    const value = values[name];
    if (value !== undefined) setLimit(limits, name, value, `--${name}`);
  }
  return limits;
}

/** The --help lines of the options every command of the shared set reads, whatever it writes. */
export const READING_OPTIONS_HELP = `  --scenario-path DIRS      folders searched after the package, before SCENARIO_PATH's own
                            (separated by ';' or ':')
  --road-path DIRS          folders where esmini finds road files and catalogs, as for run (separated by
                            ';' or ':'): the road file is looked for there too
  --root DIR                where the search upward from an unpacked folder stops (default: the
                            working directory, or the input's folder when it lies elsewhere)
  --schema-version V        the OpenSCENARIO schema files are checked against: auto (each file's
                            FileHeader, the default), 1.0, 1.1, 1.2, 1.3, or off
${LIMIT_OPTIONS_HELP}
  -q, --quiet               print errors only`;

/**
 * --carla, one option for every command that takes it (check/flatten --simulator carla, export): its
 * table entry, its --help line and its reading.
 */
export const CARLA_OPTION = { carla: { type: 'string' } } as const;

/** The --help line of --carla; `crash` says what the default release's route crash does in that command. */
export function carlaOptionHelp(crash: string): string {
  return `  --carla ${CARLA_RELEASES.join('|')}     the ScenarioRunner release whose facts apply (default ${DEFAULT_CARLA_RELEASE}, whose
                            AssignRouteAction/AcquirePositionAction crash ${crash})`;
}

/** The release --carla names (the default when it is not given). */
export function carlaReleaseOption(value: string | undefined): CarlaRelease {
  const release = value ?? DEFAULT_CARLA_RELEASE;
  if (!isCarlaRelease(release)) throw new UsageError(`--carla takes ${CARLA_RELEASES.join(', ')}, not '${release}'`);
  return release;
}

/** The --help line of --simulator. */
export const SIMULATOR_OPTION_HELP = `  --simulator asam|carla|esmini
                            also report what this simulator does not run: an error where it refuses the
                            scenario, a warning where it runs it otherwise (default asam: the standard alone)
${carlaOptionHelp('is an error with --simulator carla')}`;

/** The exit codes of a command that writes a file from its inputs. */
export const WRITING_EXIT_CODES_HELP = `  Exit codes: 0 written (warnings may have been printed), 1 the input has errors and nothing was written,
  2 usage, 3 the output could not be written and nothing was changed, 4 internal error.`;

/** The options of flatten, pack, check, stats and -cxm/-cmx. */
export interface Options {
  positional: string[];
  output?: string;
  outDir?: string;
  force: boolean;
  scenarioPath: string[];
  /** --road-path: the folders a run hands esmini as --path besides the scenario's own (the store's catalogPath). */
  roadPath: string[];
  root?: string;
  includeScenarioPath: boolean;
  selfContained: boolean;
  format: 'text' | 'json' | 'sarif';
  quiet: boolean;
  simulator: Simulator;
  /** With --simulator carla: the ScenarioRunner release whose facts apply (--carla). */
  carlaRelease: CarlaRelease;
  schemaVersion: SchemaVersionSetting | 'off';
  limits: Partial<Limits>;
}

/**
 * Every command of the original set accepts the whole set (an option another command uses is accepted
 * and has no effect), so they share this table; a command with options of its own gives its own table.
 */
const SHARED_OPTIONS = {
  output: { type: 'string', short: 'o' },
  'out-dir': { type: 'string' },
  force: { type: 'boolean' },
  'scenario-path': { type: 'string' },
  'road-path': { type: 'string' },
  root: { type: 'string' },
  'include-scenario-path': { type: 'boolean' },
  'self-contained': { type: 'boolean' },
  format: { type: 'string' },
  simulator: { type: 'string' },
  ...CARLA_OPTION,
  'schema-version': { type: 'string' },
  quiet: { type: 'boolean', short: 'q' },
  ...LIMIT_OPTIONS,
} as const;

type OptionName = keyof typeof SHARED_OPTIONS;

const isOptionName = (name: string): name is OptionName => Object.hasOwn(SHARED_OPTIONS, name);

/** The tokens of `parseArgs` that parseOptions reads. */
type OptionToken =
  | { kind: 'positional'; index: number; value: string }
  | { kind: 'option-terminator'; index: number }
  | { kind: 'option'; index: number; name: string; rawName: string; value: string | undefined; inlineValue: boolean | undefined };

const SHORT_OPTION_NAMES = new Map<string, OptionName>(
  Object.entries(SHARED_OPTIONS).flatMap(([name, option]) => ('short' in option ? [[`-${option.short}`, name as OptionName]] : [])),
);

/**
 * parseArgs's tokens for a plain command line (paths, known flags, `--name VALUE`, `-o VALUE`) made
 * without it: loading and first running node:util's parseArgs was over a millisecond of a flatten.
 * Anything else (`--name=VALUE`, grouped short flags, `--`, `-`, a value that starts with '-', an
 * unknown option) is left to parseArgs: undefined.
 */
function plainTokens(args: readonly string[]): OptionToken[] | undefined {
  const tokens: OptionToken[] = [];
  for (let index = 0; index < args.length; index++) {
    const arg = args[index];
    if (!arg.startsWith('-')) {
      tokens.push({ kind: 'positional', index, value: arg });
      continue;
    }
    const name = arg.startsWith('--') ? arg.slice(2) : SHORT_OPTION_NAMES.get(arg);
    if (name === undefined || !isOptionName(name)) return undefined;
    if (SHARED_OPTIONS[name].type === 'boolean') {
      tokens.push({ kind: 'option', index, name, rawName: arg, value: undefined, inlineValue: undefined });
      continue;
    }
    const value = args[index + 1];
    if (value === undefined || value.startsWith('-')) return undefined;
    tokens.push({ kind: 'option', index, name, rawName: arg, value, inlineValue: false });
    index++;
  }
  return tokens;
}

/** The tokens of the command line, as parseArgs gives them (see plainTokens). */
export function optionTokens(args: string[]): OptionToken[] {
  return plainTokens(args) ?? parseArgs({ args, options: SHARED_OPTIONS, strict: false, allowPositionals: true, tokens: true }).tokens;
}

/** A size such as 1048576, 512K, 64M or 2G. */
export function parseSize(text: string, flag: string): number {
  const match = /^(\d+)([KMG]?)B?$/i.exec(text.trim());
  if (!match) throw new UsageError(`${flag} takes a size such as 64M, not '${text}'`);
  const factor = { '': 1, K: 1024, M: 1024 ** 2, G: 1024 ** 3 }[match[2].toUpperCase() as '' | 'K' | 'M' | 'G'];
  const size = Number(match[1]) * factor;
  if (!Number.isSafeInteger(size) || size <= 0) throw new UsageError(`${flag} takes a positive size, not '${text}'`);
  return size;
}

/**
 * The options in the order given, the first wrong one reported. The tokens of `parseArgs` are checked
 * against the forms the CLI has always taken: `-o VALUE`, `--name VALUE`, `--name=VALUE`; a value that
 * looks like an option is missing, not taken; grouped or glued short options and `--` are unknown options.
 */
export function parseOptions(args: string[]): Options {
  const options: Options = {
    positional: [],
    force: false,
    scenarioPath: [],
    roadPath: [],
    includeScenarioPath: false,
    selfContained: false,
    format: 'text',
    quiet: false,
    simulator: 'asam',
    carlaRelease: DEFAULT_CARLA_RELEASE,
    schemaVersion: 'auto',
    limits: {},
  };
  for (const token of optionTokens(args)) {
    if (token.kind === 'positional') {
      options.positional.push(token.value);
      continue;
    }
    const arg = args[token.index];
    if (token.kind === 'option-terminator') throw new UsageError(`unknown option '${arg}'`);
    const name = token.name;
    const asTyped =
      arg === token.rawName || (token.rawName.startsWith('--') && token.inlineValue === true && arg === `${token.rawName}=${token.value}`);
    if (!isOptionName(name) || !asTyped) throw new UsageError(`unknown option '${arg}'`);
    const flag = token.rawName;
    const take = (): string => {
      const value = token.value;
      if (!token.inlineValue && value === undefined) throw new UsageError(`${flag} needs a value`);
      if (!token.inlineValue && value !== undefined && value.startsWith('-') && value.length > 1)
        throw new UsageError(dashValueMessage(flag, `--${name}`, value));
      return value as string;
    };
    switch (name) {
      case 'output':
        options.output = take();
        break;
      case 'out-dir':
        options.outDir = take();
        break;
      case 'force':
        options.force = true;
        break;
      case 'scenario-path':
        options.scenarioPath.push(...splitScenarioPath(take()));
        break;
      case 'road-path':
        options.roadPath.push(...splitScenarioPath(take()));
        break;
      case 'root':
        options.root = take();
        break;
      case 'include-scenario-path':
        options.includeScenarioPath = true;
        break;
      case 'self-contained':
        options.selfContained = true;
        break;
      case 'format': {
        const format = take();
        if (format !== 'text' && format !== 'json' && format !== 'sarif')
          throw new UsageError(`--format takes text, json or sarif, not '${format}'`);
        options.format = format;
        break;
      }
      case 'simulator': {
        const simulator = take();
        if (!isSimulator(simulator)) throw new UsageError(`--simulator takes ${SIMULATORS.join(', ')}, not '${simulator}'`);
        options.simulator = simulator;
        break;
      }
      case 'carla':
        options.carlaRelease = carlaReleaseOption(take());
        break;
      case 'schema-version': {
        const version = take();
        if (version !== 'auto' && version !== 'off' && !isSchemaVersion(version))
          throw new UsageError(`--schema-version takes auto, off, ${SCHEMA_VERSIONS.join(', ')}; not '${version}'`);
        options.schemaVersion = version;
        break;
      }
      case 'quiet':
        options.quiet = true;
        break;
      case 'max-file-size':
      case 'max-unpacked-size':
      case 'max-output-size':
      case 'max-depth':
        setLimit(options.limits, name, take(), flag);
        break;
    }
  }
  return options;
}

export function makeStore(options: Options, inputs: string[]): ScenarioStore {
  return storeForInputs(options.scenarioPath, options.root, inputs, options.limits, options.roadPath);
}

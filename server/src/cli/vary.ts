import * as fs from 'node:fs';
import * as path from 'node:path';
import {
  checkIndexInRange,
  CliCommand,
  CliOutput,
  ExitCode,
  failure,
  InputError,
  parseCommandLine,
  UsageError,
  wholeNumber,
  writablePackagedFiles,
} from './common';
import { isSameFile, writeFileAtomic } from '../../../common/src/atomic';
import {
  loadVariations,
  LoadResult,
  formatVariationProblems,
  rebasedConcreteText,
  samplingProblem,
  SamplingError,
  ScenarioTextLoader,
  VariationProblem,
  Variations,
} from '../core/variations';
import { seedBits, Xoshiro128StarStar } from '../core/variations/random';
import {
  catalogFoldersThroughSearchPath,
  concretePackagedFiles,
  flatteningScenarioLoader,
  readDistributionFile,
  scenarioFolderOf,
} from './scenarioText';
import { diskRef, FileKind, nodeFileSystem, splitScenarioPath } from '../core/sources';
import { storeForInputs } from './inputs';
import type { PackagedFile } from '../core/flatten/types';

export const VARY_HELP = `Concrete scenarios of a ParameterValueDistribution (modular2simple vary FILE ...):
  --count                   print the number of combinations (esmini's permutations); when the scenario's
                            ValueConstraintGroups discard some, also how many are kept
  --index I [-o OUT.xosc]   write concrete scenario I (esmini's --param_permutation I; a discarded one keeps
                            its index and is refused); standard output without -o
  --out-dir DIR             write every concrete scenario as DIR/SCENARIO_I.xosc
  --sample N --seed S       with --out-dir: N indices drawn at random (seed S, default 0)
  --max-combinations N      refuse more combinations than N before writing anything (default 1000000)
  --scenario-path DIRS      as for flatten: where a modular ScenarioFile's references are looked for
  -q, --quiet               print errors only
  A concrete scenario is the ScenarioFile with its root parameter values replaced and its file paths (roads,
  catalogs) rebased onto the folder it is written to (absolute on standard output), every other byte kept,
  so that it runs from wherever it is written (a root parameter used only as a whole path, filepath="$Road",
  has its relative value rebased instead); a catalog folder found only through --scenario-path is written
  as it stands, with a warning naming the --path esmini then needs. A ScenarioFile that is a modular
  main.xosc, an unpacked folder or a .mosc is flattened first (as flatten does), then its values replaced.
  Exit codes: 0 done, 1 the input has errors (nothing written), 2 usage, 3 an output could not be written, 4 internal error.`;

const DEFAULT_MAX_COMBINATIONS = 1_000_000n;

type Output = CliOutput;

export { readUtf8Exactly } from './scenarioText';

/** N distinct indices below `count`, ascending, by Floyd's algorithm with the project's generator. */
export function sampleIndices(count: bigint, wanted: bigint, seed: number): bigint[] {
  if (wanted >= count) return enumerate(count);
  const random = new Xoshiro128StarStar(seedBits(seed));
  const chosen = new Set<bigint>();
  for (let j = count - wanted; j < count; j++) {
    const candidate = random.nextBigBelow(j + 1n);
    chosen.add(chosen.has(candidate) ? j : candidate);
  }
  return [...chosen].sort((a, b) => (a < b ? -1 : a > b ? 1 : 0));
}

/** Every index below `count`. */
export function enumerate(count: bigint): bigint[] {
  const all: bigint[] = [];
  for (let i = 0n; i < count; i++) all.push(i);
  return all;
}

/** How many concrete scenarios vary and batch make: --sample, --seed and --max-combinations. */
export interface Sampling {
  sample: bigint | undefined;
  seed: number;
  maxCombinations: bigint;
}

/** Reads and checks --sample, --seed and --max-combinations, as vary and batch take them. */
export function samplingOptions(values: { sample?: string; seed?: string; 'max-combinations'?: string }): Sampling {
  if (values.seed !== undefined && values.sample === undefined) throw new UsageError('--seed goes with --sample N');
  const sample = wholeNumber(values.sample, '--sample');
  const seed = values.seed === undefined ? 0 : Number(wholeNumber(values.seed, '--seed'));
  const maxCombinations = wholeNumber(values['max-combinations'], '--max-combinations') ?? DEFAULT_MAX_COMBINATIONS;
  if (sample === 0n) throw new UsageError('--sample takes at least 1');
  if (sample !== undefined && sample > maxCombinations)
    throw new UsageError(`--sample ${sample} is more than --max-combinations ${maxCombinations}`);
  return { sample, seed, maxCombinations };
}

/**
 * The indices of the concrete scenarios to make: all of them or a sample; more than --max-combinations in all is
 * refused (`where` names the distribution, `nothing` says what was not done). Every stochastic draw is made here,
 * before anything runs or is written, so that a Range that cannot be met leaves nothing behind: its error is the answer.
 */
export function chosenIndices(variations: Variations, sampling: Sampling, where: string, nothing: string): bigint[] | SamplingError {
  const { sample, seed, maxCombinations } = sampling;
  if (sample === undefined && variations.count > maxCombinations) {
    throw new InputError(
      `${where}: ${variations.count} combinations are more than --max-combinations ${maxCombinations}; ${nothing} (use --sample N, or raise --max-combinations)`,
    );
  }
  const chosen = sample === undefined ? enumerate(variations.count) : sampleIndices(variations.count, sample, seed);
  if (variations.kind === 'stochastic') {
    for (const index of chosen) {
      try {
        variations.assignmentAt(index);
      } catch (error) {
        if (!(error instanceof SamplingError)) throw error;
        return error;
      }
    }
  }
  return chosen;
}

/** The distribution's problems, as vary and batch print them (errors only with --quiet). */
export function problemPrinter(loaded: LoadResult, quiet: boolean, io: Output, base: string): (problems?: VariationProblem[]) => void {
  return (problems = loaded.problems) => {
    const shown = quiet ? problems.filter((problem) => problem.severity === 'error') : problems;
    for (const line of formatVariationProblems(shown, loaded.lines, base)) io.err(line);
  };
}

/**
 * `modular2simple vary`: counts or writes the concrete scenarios of a distribution file. `loadScenarioText`
 * turns the ScenarioFile's path into plain scenario text (by default the flattener's hook: a plain file as it
 * is, a modular main or a package flattened).
 */
export async function varyCommand(argv: string[], io: Output, loadScenarioText?: ScenarioTextLoader): Promise<number> {
  try {
    return await varyScenarios(argv, io, loadScenarioText);
  } catch (error) {
    // Called by main and by tests: answers its failures itself, as main does.
    const failed = failure(error);
    if (failed) {
      io.err(failed.message);
      return failed.code;
    }
    io.err(`modular2simple: internal error: ${(error as Error).stack ?? String(error)}\nPlease report this with the input that caused it.`);
    return ExitCode.internal;
  }
}

async function varyScenarios(argv: string[], io: Output, givenLoader: ScenarioTextLoader | undefined): Promise<number> {
  const { values, positionals } = parseCommandLine(argv, {
    count: { type: 'boolean', default: false },
    index: { type: 'string' },
    output: { type: 'string', short: 'o' },
    'out-dir': { type: 'string' },
    sample: { type: 'string' },
    seed: { type: 'string' },
    'max-combinations': { type: 'string' },
    'scenario-path': { type: 'string', multiple: true },
    quiet: { type: 'boolean', short: 'q', default: false },
  });
  if (positionals.length !== 1) throw new UsageError('vary takes one distribution file');
  const modes = [values.count, values.index !== undefined, values['out-dir'] !== undefined].filter(Boolean).length;
  if (modes !== 1) throw new UsageError('vary needs exactly one of --count, --index I or --out-dir DIR');
  if (values.output !== undefined && values.index === undefined)
    throw new UsageError('-o goes with --index I (use --out-dir DIR for many)');
  if ((values.sample !== undefined || values.seed !== undefined) && values['out-dir'] === undefined)
    throw new UsageError('--sample and --seed go with --out-dir DIR');
  const sampling = samplingOptions(values);
  const { sample, seed, maxCombinations } = sampling;
  const index = wholeNumber(values.index, '--index');

  const distribution = await readDistributionFile(positionals[0]);
  if ('problem' in distribution) throw new InputError(distribution.problem);
  const { path: distributionPath, text: distributionText } = distribution;
  const base = process.cwd();
  // The roads and catalogs a self-contained package ScenarioFile holds: written beside each concrete scenario, where it names them.
  const packagedFiles: PackagedFile[] = [];
  const scenarioPathList = (values['scenario-path'] ?? []).flatMap(splitScenarioPath);
  const loadScenarioText = givenLoader ?? flatteningScenarioLoader(scenarioPathList, packagedFiles);
  const loaded = await loadVariations(distributionText, distributionPath, loadScenarioText);
  const printProblems = problemPrinter(loaded, values.quiet, io, base);
  printProblems();
  const variations = loaded.variations;
  if (!variations) return ExitCode.problems;
  const where = (offset: number): string =>
    formatVariationProblems([{ file: distributionPath, offset, severity: 'error', message: '' }], loaded.lines, base)[0].replace(
      /: error: $/,
      '',
    );

  if (values.count) {
    if (!variations.constrained) {
      io.out(variations.count.toString());
      return ExitCode.ok;
    }
    if (variations.count > maxCombinations)
      throw new InputError(
        `${where(0)}: ${variations.count} combinations are more than --max-combinations ${maxCombinations}; the scenario's ValueConstraintGroups can only be counted by checking each`,
      );
    let discarded = 0n;
    try {
      for (const each of enumerate(variations.count)) if (variations.brokenAt(each)) discarded++;
    } catch (error) {
      if (!(error instanceof SamplingError)) throw error;
      printProblems([samplingProblem(error, distributionPath)]);
      return ExitCode.problems;
    }
    // Both numbers: esmini knows no ValueConstraintGroup, so its permutations are every combination, and index I stays its I.
    io.out(
      discarded === 0n
        ? variations.count.toString()
        : `${variations.count} combinations (esmini's --param_permutation 0..${variations.count - 1n}), ${variations.count - discarded} kept: ${discarded} break the scenario's ValueConstraintGroups and are discarded`,
    );
    return ExitCode.ok;
  }

  const inputs = [distributionPath, variations.scenarioPath];
  // What is written reaches the files the ScenarioFile reached, from wherever it is written (SPEC 11.6).
  const scenarioFolder = scenarioFolderOf(variations.scenarioPath);
  const kinds = new Map<string, Promise<FileKind>>();
  const kindOf = (diskPath: string): Promise<FileKind> => {
    let known = kinds.get(diskPath);
    if (!known) kinds.set(diskPath, (known = nodeFileSystem.kind(diskPath)));
    return known;
  };
  // A catalog folder found only through --scenario-path is written as it stands: the warning names the --path esmini then needs.
  const foundThroughSearchPath = catalogFoldersThroughSearchPath(
    storeForInputs(scenarioPathList, undefined, [variations.scenarioPath]),
    diskRef(path.join(scenarioFolder, path.basename(variations.scenarioPath))),
  );
  const warned = new Set<string>();
  const rebased = async (text: string, outputDirectory: string | undefined): Promise<string> => {
    const result = await rebasedConcreteText(
      text,
      scenarioFolder,
      outputDirectory === undefined ? undefined : path.resolve(outputDirectory),
      kindOf,
      foundThroughSearchPath,
    );
    for (const warning of result.warnings) {
      if (!values.quiet && !warned.has(warning))
        io.err(`${path.relative(base, variations.scenarioPath) || variations.scenarioPath}: warning: ${warning}`);
      warned.add(warning);
    }
    return result.text;
  };
  const writtenPackaged = new Set<string>();
  // A concrete scenario's `$parameter` road may be another file of the package than the one the flattening carried.
  const packagedOf = concretePackagedFiles(variations.scenarioPath, scenarioPathList);
  const writePackagedBeside = async (outputDirectory: string, concreteText: string): Promise<void> => {
    const at = (file: PackagedFile) => path.join(path.resolve(outputDirectory), path.relative(scenarioFolder, file.path));
    const label = path.relative(base, variations.scenarioPath) || variations.scenarioPath;
    const named = [...packagedFiles, ...(await packagedOf(concreteText))];
    const pending = named.filter(
      (file, index) => !writtenPackaged.has(at(file)) && named.findIndex((other) => at(other) === at(file)) === index,
    );
    const writable = await writablePackagedFiles(pending, label, io, values.quiet ?? false, at);
    // One left where another file lies is told once.
    for (const file of pending) if (!writable.includes(file)) writtenPackaged.add(at(file));
    for (const file of writable) {
      const target = at(file);
      await fs.promises.mkdir(path.dirname(target), { recursive: true });
      await writeFileAtomic(target, file.bytes);
      writtenPackaged.add(target);
    }
  };
  if (index !== undefined) {
    checkIndexInRange(index, variations.count, positionals[0]);
    const concrete = concreteOrProblem(variations, index, distributionPath, printProblems);
    if (!concrete) return ExitCode.problems;
    if ('broken' in concrete)
      throw new InputError(
        `${positionals[0]}: concrete scenario ${index} is discarded: parameter '${concrete.broken.parameter}' = '${concrete.broken.value}' breaks its ValueConstraintGroups; choose another --index ('vary ${positionals[0]} --count' says how many are kept)`,
      );
    if (values.output === undefined) {
      io.out(await rebased(concrete.text, undefined));
      const stored = new Set([...packagedFiles, ...(await packagedOf(concrete.text))].map((file) => file.path)).size;
      if (stored > 0 && !values.quiet)
        io.err(
          `${path.relative(base, variations.scenarioPath) || variations.scenarioPath}: warning: the scenario names ${stored} file${stored === 1 ? '' : 's'} stored in the package, which standard output cannot carry; write it with -o`,
        );
      return ExitCode.ok;
    }
    if (inputs.some((input) => isSameFile(input, values.output as string)))
      throw new UsageError(`-o ${values.output} is an input; it is never overwritten`);
    const text = await rebased(concrete.text, path.dirname(values.output));
    try {
      await writePackagedBeside(path.dirname(values.output), concrete.text);
      await writeFileAtomic(values.output, text);
    } catch (error) {
      io.err(`modular2simple: cannot write ${values.output}: ${(error as Error).message}`);
      return ExitCode.io;
    }
    // As --out-dir and the other commands say what they wrote; the values, as the editor's Run in esmini names them.
    if (!values.quiet) {
      const assigned = concrete.assignments.map((assignment) => `${assignment.parameter} = ${assignment.value}`).join(', ');
      io.err(`wrote ${values.output} (concrete scenario ${index} of ${variations.count}: ${assigned})`);
    }
    return ExitCode.ok;
  }

  const outDir = values['out-dir'] as string;
  const chosen = chosenIndices(variations, sampling, where(0), 'nothing was written');
  if (chosen instanceof SamplingError) {
    printProblems([samplingProblem(chosen, distributionPath)]);
    return ExitCode.problems;
  }
  try {
    await fs.promises.mkdir(outDir, { recursive: true });
  } catch (error) {
    io.err(`modular2simple: cannot create ${outDir}: ${(error as Error).message}`);
    return ExitCode.io;
  }
  const stem = path.basename(variations.scenarioPath).replace(/\.[^.]*$/, '');
  const width = (variations.count - 1n).toString().length;
  let written = 0;
  let discarded = 0;
  for (const chosenIndex of chosen) {
    const concrete = variations.concreteAt(chosenIndex);
    if ('broken' in concrete) {
      discarded++;
      continue;
    }
    const target = path.join(outDir, `${stem}_${chosenIndex.toString().padStart(width, '0')}.xosc`);
    if (inputs.some((input) => isSameFile(input, target))) throw new UsageError(`${target} is an input; it is never overwritten`);
    const text = await rebased(concrete.text, outDir);
    try {
      await writePackagedBeside(outDir, concrete.text);
      await writeFileAtomic(target, text);
    } catch (error) {
      io.err(`modular2simple: cannot write ${target}: ${(error as Error).message} (${written} concrete scenarios were written before it)`);
      return ExitCode.io;
    }
    written++;
  }
  if (!values.quiet)
    io.err(
      `wrote ${written} concrete scenario${written === 1 ? '' : 's'} to ${outDir}` +
        (discarded > 0 ? `; ${discarded} discarded by the scenario's ValueConstraintGroups` : '') +
        (sample !== undefined ? ` (a sample of ${chosen.length} of ${variations.count}, seed ${seed})` : ''),
    );
  return ExitCode.ok;
}

function concreteOrProblem(
  variations: Variations,
  index: bigint,
  distributionPath: string,
  printProblems: (problems: ReturnType<typeof samplingProblem>[]) => void,
): ReturnType<Variations['concreteAt']> | undefined {
  try {
    return variations.concreteAt(index);
  } catch (error) {
    if (!(error instanceof SamplingError)) throw error;
    printProblems([samplingProblem(error, distributionPath)]);
    return undefined;
  }
}

export const VARY: CliCommand = { help: VARY_HELP, run: (args, io) => varyCommand(args, io) };

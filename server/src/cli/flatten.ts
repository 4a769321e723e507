import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener, OVERRIDE_PROBLEM_CODES } from '../core/flatten';
import { pathBaseOf } from '../core/flatten/rebase';
import { rebasedConcreteText } from '../core/variations';
import { catalogFoldersThroughSearchPath } from './scenarioText';
import { Problem } from '../core/problems';
import { countEditorLines } from '../core/text';
import type { PackagedFile } from '../core/flatten/types';
import {
  checkInputExists,
  checkNotAnInput,
  CliCommand,
  CliOutput,
  ExitCode,
  report,
  UnavailableError,
  UsageError,
  writablePackagedFiles,
  write,
} from './common';
import { mainOf } from './inputs';
import { makeStore, Options, parseOptions, READING_OPTIONS_HELP, SIMULATOR_OPTION_HELP, WRITING_EXIT_CODES_HELP } from './options';

/** Flattens each input; without `outputs` the results go to standard output. */
async function flattenInputs(inputs: string[], outputs: string[] | undefined, options: Options, io: CliOutput): Promise<number> {
  for (const input of inputs) checkInputExists(input);
  const store = makeStore(options, inputs);
  const flattener = new Flattener(store, options.simulator, { version: options.schemaVersion }, undefined, options.carlaRelease);
  const results = [];
  let problems: Problem[] = [];
  for (const [index, input] of inputs.entries()) {
    const output = outputs?.[index];
    const standardOutput = output === undefined || output === '-';
    const result = await flattener.flatten(mainOf(input), {
      force: options.force,
      outputPath: standardOutput ? undefined : output,
      standardOutput,
    });
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
  const counted = `${errors} error${errors === 1 ? '' : 's'}`;
  if (results.some((result) => result.text === undefined)) {
    // The refused output could be rendered: only the errors stopped it, and --force writes it anyway.
    const forcible = !options.force && results.every((result) => result.text !== undefined || result.source.text !== undefined);
    const skipping = problems.some((problem) => OVERRIDE_PROBLEM_CODES.has(problem.code) && problem.severity === 'error')
      ? ', skipping the overrides that cannot apply'
      : '';
    io.err(`${counted}; nothing was written` + (forcible ? ` (--force writes it anyway${skipping})` : ''));
    return ExitCode.problems;
  }
  // Said once the output is written: an output refused (over an input, unwritable) was not written anyway.
  const forcedNote = options.force && errors > 0 ? `${counted}; written anyway (--force)` : undefined;
  // A catalog folder found only through the scenario path is written as it stands (SPEC 11.6): said, with the --path esmini then needs.
  if (!options.quiet) {
    for (const [index, result] of results.entries()) {
      const main = mainOf(inputs[index]);
      const output = outputs?.[index];
      const folder = output === undefined || output === '-' ? pathBaseOf(main) : path.dirname(path.resolve(output));
      const { warnings } = await rebasedConcreteText(
        result.text as string,
        folder,
        folder,
        (file) => store.kindOf(file),
        catalogFoldersThroughSearchPath(store, main),
      );
      for (const warning of new Set(warnings)) io.err(`${inputs[index]}: warning: ${warning}`);
    }
  }
  if (!outputs) {
    for (const result of results) io.out(result.text as string);
    if (forcedNote) io.err(forcedNote);
    return ExitCode.ok;
  }
  for (let i = 0; i < results.length; i++) if (outputs[i] !== '-') checkNotAnInput(outputs[i], results[i].source.dependencies);
  // A self-contained package's roads and catalogs go beside the output that names them.
  const files: PackagedFile[][] = [];
  for (const [i, result] of results.entries()) files.push(await writablePackagedFiles(result.files, outputs[i], io, options.quiet));
  for (const file of files.flat()) fs.mkdirSync(path.dirname(file.path), { recursive: true });
  const written = await write(
    results.flatMap((result, i) => [
      {
        target: outputs[i],
        data: result.text as string,
        summary: `wrote ${outputs[i]} (${countEditorLines(result.text as string)} lines)`,
      },
      ...files[i].map((file) => ({
        target: file.path,
        data: file.bytes,
        summary: `wrote ${path.relative(path.dirname(path.resolve(outputs[i])), file.path)} (a file of the package the output names)`,
      })),
    ]),
    io,
    options.quiet,
  );
  if (written === ExitCode.ok && forcedNote) io.err(forcedNote);
  return written;
}

function outputNameFor(input: string): string {
  const resolved = path.resolve(input);
  const base = path.basename(resolved);
  if (fs.existsSync(resolved) && fs.statSync(resolved).isDirectory()) return `${base}.xosc`;
  if (base === 'main.xosc') return `${path.basename(path.dirname(resolved))}.xosc`;
  return `${base.replace(/\.(mosc|xosc)$/i, '')}.xosc`;
}

/** `modular2simple flatten INPUT [-o OUT.xosc]` or `flatten INPUT... --out-dir DIR`. */
async function flattenCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseOptions(args);
  const inputs = options.positional;
  if (inputs.length === 0) throw new UsageError('flatten needs an input: a .mosc, a main.xosc or an unpacked folder');
  if (options.outDir) {
    if (options.output) throw new UsageError('use either -o or --out-dir');
    if (!fs.existsSync(options.outDir) || !fs.statSync(options.outDir).isDirectory())
      throw new UnavailableError(`${options.outDir}: cannot write the outputs (the folder does not exist); nothing was changed`);
    let names = inputs.map(outputNameFor);
    // Inputs with a shared file name (lib/*/result.mosc) are told apart by their folders.
    names = names.map((name, index) =>
      names.indexOf(name) !== names.lastIndexOf(name) ? `${path.basename(path.dirname(path.resolve(inputs[index])))}.xosc` : name,
    );
    const outputs = names.map((name) => path.join(options.outDir as string, name));
    const duplicates = outputs.filter((output, index) => outputs.indexOf(output) !== index);
    if (duplicates.length > 0) throw new UsageError(`two inputs would both be written to ${duplicates[0]}`);
    return flattenInputs(inputs, outputs, options, io);
  }
  if (inputs.length > 1) throw new UsageError('several inputs need --out-dir DIR');
  return flattenInputs(inputs, options.output ? [options.output] : undefined, options, io);
}

/** The original tool's `-cmx|--convert-mosc-to-xosc IN.mosc OUT.xosc`: a flatten to OUT. */
async function convertMoscToXoscCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseOptions(args);
  const inputs = options.positional;
  if (inputs.length !== 2) throw new UsageError('-cmx takes one input .mosc and one output .xosc');
  return flattenInputs([inputs[0]], [inputs[1]], options, io);
}

const FORCE_HELP = `  --force                   write whatever can be produced despite errors, listing them; overrides that cannot
                            apply (unknown keys, attributes without default) are skipped, as the original did`;

export const FLATTEN: CliCommand = {
  help: `Flatten a .mosc, a main.xosc or an unpacked folder into one plain scenario
(modular2simple flatten INPUT [-o FILE], or flatten INPUT... --out-dir DIR):
  -o, --output FILE         the scenario to write; '-' or no -o prints it to standard output
  --out-dir DIR             write each input to DIR/NAME.xosc (several inputs)
${FORCE_HELP}
${SIMULATOR_OPTION_HELP}
${READING_OPTIONS_HELP}
${WRITING_EXIT_CODES_HELP}`,
  run: flattenCommand,
};

export const CONVERT_MOSC_TO_XOSC: CliCommand = {
  help: `Flatten a package, as the original tool's -cmx did (modular2simple -cmx|--convert-mosc-to-xosc IN.mosc OUT.xosc):
  the same as modular2simple flatten IN.mosc -o OUT.xosc, with flatten's options.
${FORCE_HELP}
${READING_OPTIONS_HELP}
${WRITING_EXIT_CODES_HELP}`,
  run: convertMoscToXoscCommand,
};

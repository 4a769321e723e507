import * as fs from 'node:fs';
import { packFiles, packFolder, PackResult } from '../core/pack';
import { diskRef } from '../core/sources';
import { checkInputExists, checkNotAnInput, CliCommand, CliOutput, ExitCode, report, UsageError, write } from './common';
import { makeStore, Options, parseOptions, READING_OPTIONS_HELP, WRITING_EXIT_CODES_HELP } from './options';

/** Packs a folder, or files at the root of a package, into `output`. */
async function packInputs(inputs: string[], output: string, options: Options, io: CliOutput): Promise<number> {
  if (!output.toLowerCase().endsWith('.mosc')) throw new UsageError(`the output '${output}' must end in .mosc`);
  const folderInput = inputs.length === 1 && fs.existsSync(inputs[0]) && fs.statSync(inputs[0]).isDirectory();
  let result: PackResult;
  if (folderInput) {
    checkInputExists(inputs[0]);
    result = await packFolder(inputs[0], makeStore(options, inputs), {
      includeScenarioPath: options.includeScenarioPath,
      outputPath: output,
      selfContained: options.selfContained,
    });
  } else {
    result = await packFiles(inputs, options.limits, {
      outputPath: output,
      selfContained: options.selfContained,
      workingDirectory: process.cwd(),
    });
  }
  const { errors } = report(result.problems, io, options.quiet);
  if (!result.bytes) {
    io.err(`${errors} error${errors === 1 ? '' : 's'}; nothing was written`);
    return ExitCode.problems;
  }
  checkNotAnInput(output, [...inputs.map((input) => diskRef(input)), ...result.inputs]);
  return write([{ target: output, data: result.bytes, summary: `wrote ${output} (${result.entries.join(', ')})` }], io, options.quiet);
}

/** `modular2simple pack FOLDER -o OUT.mosc` or `pack FILE... -o OUT.mosc`. */
async function packCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseOptions(args);
  const inputs = options.positional;
  if (inputs.length === 0) throw new UsageError('pack needs a folder or files to pack');
  if (!options.output) throw new UsageError('pack needs -o OUT.mosc');
  return packInputs(inputs, options.output, options, io);
}

/** The original tool's `-cxm|--convert-xosc-into-mosc IN... OUT.mosc`: a pack whose last argument is the output. */
async function convertXoscIntoMoscCommand(args: string[], io: CliOutput): Promise<number> {
  const options = parseOptions(args);
  const inputs = options.positional;
  if (inputs.length < 2) throw new UsageError('-cxm takes the input files and then the output .mosc');
  return packInputs(inputs.slice(0, -1), inputs[inputs.length - 1], options, io);
}

const PACK_OPTIONS_HELP = `  --include-scenario-path   also store files found through SCENARIO_PATH
  --self-contained          store the road networks, catalogs and other files the scenarios name inside
                            the package (else pack warns about each one left outside)`;

export const PACK: CliCommand = {
  help: `Pack a scenario and all it references into a .mosc package
(modular2simple pack FOLDER -o FILE.mosc, or pack FILE... -o FILE.mosc with one main.xosc among the files):
  -o, --output FILE         the package to write (ends in .mosc)
${PACK_OPTIONS_HELP}
${READING_OPTIONS_HELP}
${WRITING_EXIT_CODES_HELP}`,
  run: packCommand,
};

export const CONVERT_XOSC_INTO_MOSC: CliCommand = {
  help: `Pack files, as the original tool's -cxm did (modular2simple -cxm|--convert-xosc-into-mosc IN... OUT.mosc):
  the same as modular2simple pack IN... -o OUT.mosc, with pack's options.
${PACK_OPTIONS_HELP}
${READING_OPTIONS_HELP}
${WRITING_EXIT_CODES_HELP}`,
  run: convertXoscIntoMoscCommand,
};

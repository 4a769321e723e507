import * as fs from 'node:fs';
import { writeFileAtomic } from '../../../common/src/atomic';
import { DEFAULT_FORMAT_OPTIONS, detectIndentation, FormatOptions, formatXml } from '../core/format';
import { walkFiles } from '../core/walk';
import { CliCommand, CliOutput, ExitCode, parseCommandLine, UsageError } from './common';

export const FORMAT_HELP = `  modular2simple format [--check] [--width N] [--indent N|tab] PATH...
                                                   format .xosc files in place (folders: every .xosc below)`;

interface Plan {
  file: string;
  /** The formatted text with its byte-order mark, when it differs from the file. */
  output: string | undefined;
}

/** Only .xosc files are formatted (a .mosc is an archive); a folder the user names is walked whole, in the order it lists. */
const FORMATTED_FILES = {
  files: /\.xosc$/i,
  skipFolders: new Set(['node_modules']),
  skipDotFiles: true,
  regularFilesOnly: true,
  unreadable: 'throw',
  sorted: false,
} as const;

function indentOption(value: string | undefined): Pick<FormatOptions, 'tabSize' | 'insertSpaces'> | undefined {
  if (value === undefined) return undefined;
  if (value === 'tab') return { tabSize: 4, insertSpaces: false };
  const spaces = Number(value);
  if (!Number.isInteger(spaces) || spaces < 0 || spaces > 16)
    throw new UsageError(`--indent takes a number of spaces (0-16) or 'tab', not '${value}'`);
  return { tabSize: spaces, insertSpaces: true };
}

/** Reads and formats one file; a problem is returned as a message naming the file and place. */
function planFile(file: string, indent: Pick<FormatOptions, 'tabSize' | 'insertSpaces'> | undefined, width: number): Plan | string {
  if (/\.mosc$/i.test(file)) return `${file}: error: a .mosc package is an archive; format its files before packing`;
  let bytes: Buffer;
  try {
    bytes = fs.readFileSync(file);
  } catch (error) {
    return `${file}: error: cannot read the file (${(error as Error).message})`;
  }
  let text: string;
  try {
    // Fatal decoding: a file in another encoding must be refused, not rewritten with replacement characters.
    text = new TextDecoder('utf-8', { fatal: true, ignoreBOM: true }).decode(bytes);
  } catch {
    return `${file}: error: the file is not UTF-8 text; it was not formatted`;
  }
  const result = formatXml(text, { ...(indent ?? detectIndentation(text)), maxLineWidth: width });
  if (!result.ok) return `${file}:${result.line + 1}:${result.column + 1}: error: ${result.message}`;
  return { file, output: result.text === text ? undefined : result.text };
}

/** `modular2simple format`: formats in place, or with --check only lists the files that would change. */
async function formatCommand(args: string[], io: CliOutput): Promise<number> {
  const { values, positionals } = parseCommandLine(args, {
    check: { type: 'boolean' },
    width: { type: 'string' },
    indent: { type: 'string' },
    quiet: { type: 'boolean', short: 'q' },
  });
  if (positionals.length === 0) throw new UsageError('format needs at least one .xosc file or folder');
  const indent = indentOption(values.indent);
  let width = DEFAULT_FORMAT_OPTIONS.maxLineWidth;
  if (values.width !== undefined) {
    width = Number(values.width);
    if (!Number.isInteger(width) || width < 1) throw new UsageError(`--width takes a positive number of columns, not '${values.width}'`);
  }

  const files: string[] = [];
  const problems: string[] = [];
  for (const input of positionals) {
    const stat = fs.statSync(input, { throwIfNoEntry: false });
    if (!stat) problems.push(`${input}: error: no such file or folder`);
    else if (stat.isDirectory()) {
      const below = await walkFiles([input], FORMATTED_FILES);
      // As for check: a folder with nothing to format is named, so that --check on a mistyped folder does not pass.
      if (below.length === 0)
        problems.push(
          `${input}: error: the folder holds no .xosc file, so nothing was formatted; name the folder (or files) that hold the scenarios`,
        );
      files.push(...below);
    } else files.push(input);
  }
  const plans: Plan[] = [];
  for (const file of files) {
    const plan = planFile(file, indent, width);
    if (typeof plan === 'string') problems.push(plan);
    else plans.push(plan);
  }
  for (const problem of problems) io.err(problem);
  const changed = plans.filter((plan) => plan.output !== undefined);

  if (values.check) {
    for (const plan of changed) io.out(plan.file);
    if (!values.quiet)
      io.err(
        `${changed.length} of ${files.length} file${files.length === 1 ? '' : 's'} would be reformatted` +
          (problems.length ? `; ${problems.length} could not be read or parsed` : ''),
      );
    return changed.length > 0 || problems.length > 0 ? ExitCode.problems : ExitCode.ok;
  }
  if (problems.length > 0) {
    io.err(`${problems.length} error${problems.length === 1 ? '' : 's'}; nothing was written`);
    return ExitCode.problems;
  }
  for (const plan of changed) {
    try {
      // The decoded text kept any byte-order mark (ignoreBOM), so the output carries it too.
      await writeFileAtomic(plan.file, plan.output as string);
    } catch (error) {
      io.err(`${plan.file}: error: cannot write the file (${(error as Error).message}); it is unchanged`);
      return ExitCode.io;
    }
  }
  if (!values.quiet) io.err(`formatted ${changed.length} of ${files.length} file${files.length === 1 ? '' : 's'}`);
  return ExitCode.ok;
}

export const FORMAT: CliCommand = {
  help: `Format .xosc files in place (modular2simple format [--check] [--width N] [--indent N|tab] PATH...):
  a folder is formatted whole (every .xosc below it); a file that does not parse is reported and left alone.
  --check                   list the files that would change and write nothing
  --width N                 past N columns a start tag puts each attribute on its own line (default 120)
  --indent N|tab            the indentation (default: what the file uses, else 2 spaces)
  -q, --quiet               print errors only
  Exit codes: 0 formatted (with --check: nothing would change), 1 a file could not be read or parsed, or a folder
  holds no .xosc file (nothing was written; with --check: or a file would change), 2 usage, 3 a file could not be written, 4 internal error.`,
  run: formatCommand,
};
